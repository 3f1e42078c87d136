/* Rain along -Y and random drops by area on a surface (Silva et al. §3.1 droplets). */
#ifndef PELT_CORE_WET_RAIN_H
#define PELT_CORE_WET_RAIN_H

#include "pelt/wetness.h"
#include "core/mesh/raycast.h"
#include "core/wet/surface_droplet.h"

/* Most drops one rain step lets fall; the rest of a huge rate * dt is
 * dropped (its fraction still carries) so a step stays bounded. */
#define PELT__RAIN_MAX_PER_STEP 65536u

/* The rain over one mesh: the pelt_rain settings, the random sequence, the
 * fraction of a drop carried between steps, and per-mesh tables (cumulative
 * triangle areas for random drops, the mean world length of one mask-uv
 * unit). It wets a mask given to each call; it owns no mask. */
typedef struct pelt__rain pelt__rain;

/* Makes the rain of `mesh` (positions, uvs, indices; at least one
 * triangle): rate 0, seed 1. The mesh is not copied: it must outlive the
 * rain. Allocates O(triangles); free with pelt__rain_destroy. */
pelt_status pelt__rain_create(const pelt_mesh *mesh, const pelt_allocator *a, pelt__rain **out, pelt_error *err);
void pelt__rain_destroy(pelt__rain *rain);

/* Takes new settings and restarts the random sequence from settings->seed,
 * with no fraction carried. */
void pelt__rain_set(pelt__rain *rain, const pelt_rain *settings);

/* Changes only the rate (non-finite or negative -> 0), keeping the random
 * sequence and the carried fraction. */
void pelt__rain_set_rate(pelt__rain *rain, float rate);

/* One step of dt seconds: rate * dt drops (the fraction carried to the
 * next step, at most PELT__RAIN_MAX_PER_STEP) start at random points of
 * the plane one bounds-height above the mesh's bounds, uniform over its X
 * and Z extent, and fall along -Y; each wets the mask by
 * pelt__droplet_ray (on bvh and index, both built from the rain's mesh)
 * where it hits, with a radius uniform in the settings' range (mask-uv
 * units, converted to world units by the mean uv scale) and a wetness
 * uniform in its range. A drop that misses falls past. Deterministic for
 * a seed and a sequence of dt. Returns the number of drops that fell
 * (hits and misses). No allocation. */
size_t pelt__rain_step(pelt__rain *rain, pelt__wetness *mask, pelt__surface_index *index,
                       const pelt__bvh *bvh, float dt);

/* `count` drops at random surface points (a triangle with probability
 * proportional to its area, a uniform point in it), seeded by
 * settings->seed alone (the rain's own sequence is untouched), radius and
 * wetness as pelt__rain_step; each wets the mask through
 * pelt__droplet_surface. settings->rate is ignored. No allocation. */
void pelt__rain_random_drops(const pelt__rain *rain, const pelt_rain *settings, unsigned count,
                             pelt__wetness *mask, pelt__surface_index *index);

#endif
