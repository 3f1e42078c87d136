/* Ray-mesh closest hits through a bounding volume hierarchy over the
 * triangles (binned SAH build, flat node array, iterative traversal,
 * Moller-Trumbore). Used to drop water where the user clicks. No GL. */
#ifndef PELT_CORE_RAYCAST_H
#define PELT_CORE_RAYCAST_H

#include "pelt/mesh.h"

typedef struct pelt__bvh pelt__bvh;

/* A closest hit: triangle index into the mesh, ray parameter t (hit point
 * = origin + t * dir) and barycentric weights of the triangle's vertices
 * 0, 1, 2 (they sum to 1). */
typedef struct pelt__hit {
    size_t triangle;
    float t;
    float bary[3];
} pelt__hit;

/* Builds the hierarchy over mesh's triangles (positions are copied; the
 * mesh may change or go afterwards, but hits index its triangles). The
 * caller frees *out with pelt__bvh_destroy. */
pelt_status pelt__bvh_build(const pelt_mesh *mesh, const pelt_allocator *alloc, pelt__bvh **out, pelt_error *err);
void pelt__bvh_destroy(pelt__bvh *bvh);

/* Closest hit with t in (0, t_max] on either side of the triangles (no
 * culling). dir need not be unit length. Returns false on a miss or on
 * non-finite input. No allocation. */
bool pelt__bvh_raycast(const pelt__bvh *bvh, const float origin[3],
                       const float dir[3], float t_max, pelt__hit *hit);

/* Calls visit(triangle, user) for every triangle whose bounding box comes
 * within `radius` of `center` (a superset of the triangles the ball
 * touches), for brushes: the work grows with the triangles near the ball,
 * not with the mesh. Returns how many were visited. No allocation. */
size_t pelt__bvh_query_ball(const pelt__bvh *bvh, const float center[3], float radius,
                            void (*visit)(size_t triangle, void *user), void *user);

/* The same query by testing every triangle: the reference for tests. */
bool pelt__raycast_brute(const pelt_mesh *mesh, const float origin[3],
                         const float dir[3], float t_max, pelt__hit *hit);

/* Node count and depth of the hierarchy, for reports. */
void pelt__bvh_stats(const pelt__bvh *bvh, size_t *nodes, unsigned *depth);

#endif
