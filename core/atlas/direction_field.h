/* Hair direction field on a mesh (Lengyel et al. §3 "Hair direction", §2.1
 * global direction field). Vertices are welded by core/base/weld.h. */
#ifndef PELT_DIRECTION_FIELD_H
#define PELT_DIRECTION_FIELD_H

#include "pelt/base.h"


/* Computes a unit tangent direction dir (3 per vertex) and a slant weight in
 * [0,1] per vertex. The raw field is `global` projected on each tangent plane
 * (or per_vertex[3i..] projected, when per_vertex is not NULL); it is then
 * smoothed `iterations` times over the welded vertex adjacency and
 * re-projected. Where it vanishes the weight goes to 0 and dir is any
 * consistent tangent. canon is pelt__weld's (by position); vertices with the
 * same canon get the same value. */
bool pelt__direction_field(const float *positions, const float *normals, size_t vertex_count,
                           const uint32_t *indices, size_t triangle_count, const uint32_t *canon,
                           const float global[3], const float *per_vertex, unsigned iterations,
                           float *dir, float *weight);

#endif
