/* The water on one fur: the wetness mask, the natural clump cells, the
 * surface index droplets spread over, and the rain, owned together. Every
 * way water arrives (a droplet in uv, at a surface point, along a ray,
 * random drops, rain, a painted image) goes through here, so the clump
 * cells see exactly the texels each call changed, and the renderer takes
 * one dirty rectangle. */
#ifndef PELT_WATER_H
#define PELT_WATER_H

#include "pelt/wetness.h"
#include "core/mesh/raycast.h"
#include "core/wet/mask.h"

#include <stdint.h>

typedef struct pelt__water pelt__water;

typedef struct pelt__water_desc {
    unsigned mask_size; /* texels a side of the mask */
    float clump_size;   /* > 0: natural clumps of this world size; 0: one per droplet */
    uint32_t seed;      /* the clump cells' seeds */
} pelt__water_desc;

/* Water over `mesh` (which outlives it); droplets along a ray use `bvh`,
 * the mesh's triangle hierarchy, which the caller owns and keeps. */
pelt_status pelt__water_create(const pelt_mesh *mesh, const pelt__bvh *bvh, const pelt__water_desc *desc,
                               const pelt_allocator *a, pelt__water **out, pelt_error *err);
void pelt__water_destroy(pelt__water *w);

/* The mask, read-only: texels, the wet box, its size. */
const pelt__wetness *pelt__water_mask(const pelt__water *w);

/* Droplets in mask uv (Alg. 1), n in order; a bad one changes nothing. */
pelt_status pelt__water_drop_uv(pelt__water *w, const pelt_droplet *d, size_t n, pelt_error *err);
/* A droplet at a surface point (triangle, barycentrics), spread by
 * distance on the surface across patch borders. */
pelt_status pelt__water_drop_at(pelt__water *w, size_t triangle, const float bary[3], float radius_world,
                                float wetness, pelt_error *err);
/* A droplet where the ray first hits the surface; false on a miss. */
bool pelt__water_drop_ray(pelt__water *w, const float origin[3], const float dir[3], float radius_world,
                          float wetness);
/* `count` drops at random surface points, seeded by rain->seed. */
void pelt__water_random_drops(pelt__water *w, const pelt_rain *rain, unsigned count);
/* A greyscale image (w x h, 0 dry .. 255 soaked, scaled by `wetness`)
 * painted over the mask. */
pelt_status pelt__water_paint(pelt__water *w, const uint8_t *grey, unsigned width, unsigned height,
                              float wetness, const pelt_allocator *a, pelt_error *err);

/* dt seconds: the rain falls, then the mask dries at the dry rate. No
 * allocation. */
void pelt__water_step(pelt__water *w, float dt);
void pelt__water_set_rain(pelt__water *w, const pelt_rain *rain);
void pelt__water_set_rain_rate(pelt__water *w, float rate);
void pelt__water_set_dry_rate(pelt__water *w, float rate);
void pelt__water_clear(pelt__water *w);

/* The texels changed since the last call, {x0, y0, x1, y1} with x1, y1
 * exclusive; false when nothing changed. */
bool pelt__water_take_dirty(pelt__water *w, unsigned rect[4]);

#endif
