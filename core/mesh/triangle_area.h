/* Areas of one triangle of a mesh's arrays (pelt_mesh_get_data), in world
 * space or in a 2-float-per-vertex coordinate set. */
#ifndef PELT_TRIANGLE_AREA_H
#define PELT_TRIANGLE_AREA_H

#include "pelt/mesh.h"

#include "core/base/vec.h"

#include <math.h>

static inline float pelt__triangle_area(const pelt_mesh_data *d, size_t t)
{
    const uint32_t *ix = d->indices + 3 * t;
    pelt_vec3 p0 = v3_load(d->positions + 3 * ix[0]);
    pelt_vec3 e1 = v3_sub(v3_load(d->positions + 3 * ix[1]), p0);
    pelt_vec3 e2 = v3_sub(v3_load(d->positions + 3 * ix[2]), p0);
    return 0.5f * v3_len(v3_cross(e1, e2));
}

/* Unsigned area in `coords` (uvs or fur_uvs, 2 floats per vertex). */
static inline float pelt__triangle_area_2d(const pelt_mesh_data *d, const float *coords, size_t t)
{
    const uint32_t *ix = d->indices + 3 * t;
    const float *a = coords + 2 * ix[0], *b = coords + 2 * ix[1], *c = coords + 2 * ix[2];
    return 0.5f * fabsf((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
}

#endif
