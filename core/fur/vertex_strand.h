/* A mesh vertex's strand as shell_vs.glsl displaces the shells over it
 * (the C references of core/fur/fur_shape.c): shared by the fins' frame
 * (core/fur/fin_frame.c) and the strand reference (core/fur/strand_ref.c). */
#ifndef PELT_CORE_FUR_VERTEX_STRAND_H
#define PELT_CORE_FUR_VERTEX_STRAND_H

#include "core/base/vec.h"
#include "core/fur/fur_internal.h"

typedef struct fin_strand {
    pelt_vec3 p, n, u, v, tip, shear;
    float L, K, omega, rho;
} fin_strand;

/* Vertex i's strand: root, frame, length L (times `length_scale`, the
 * fins' multiple or 1), curl, tip, comb shear; `slant` is tan of the
 * comb's slant, `wet` whether the mask is read. */
fin_strand pelt__fur_vertex_strand(const pelt_fur *f, const pelt_mesh_data *m, const float *tangents, bool wet,
                                   float slant, float length_scale, size_t i);
/* beta + phi + comb at h (0..1 of the full length), as shell_vs.glsl. */
pelt_vec3 pelt__fur_vertex_strand_offset(const fin_strand *st, float h);

#endif
