/* pelt — wetness: droplets blended into the wetness mask (Silva et al.
 * §3.1, Alg. 1), rain and drying. */
#ifndef PELT_WETNESS_H
#define PELT_WETNESS_H

#include "pelt/base.h"
#include "pelt/fur.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One droplet in mask (atlas) coordinates: centre in [0,1]^2, radius in
 * the same units, wetness in [-1, 1] (negative dries, a hair dryer; values
 * outside are clamped). It updates every mask texel whose centre lies
 * within the radius (Silva Alg. 1 as docs/wetness.md reads it), so a
 * radius below half a texel may touch no texel at all. */
typedef struct pelt_droplet {
    float center[2];
    float radius;
    float wetness;
} pelt_droplet;

/* Rain (pelt_fur_set_rain) and random drops (pelt_fur_add_random_droplets):
 * drops per second from seeded random places, radius and wetness uniform
 * in their ranges (reversed ranges are swapped). Rain falls along the
 * mesh's -Y axis from random points above its bounds, uniform over its X-Z
 * extent, and wets where it hits; a drop that misses falls past. At most
 * 65,536 drops fall in one step. Deterministic for a seed and a sequence
 * of time steps; fractional drops carry over from one step to the next.
 * Every drop wets by distance on the surface, as pelt_fur_add_droplet_at. */
typedef struct pelt_rain {
    float rate;             /* drops per second, 0 = no rain */
    float radius_min, radius_max;   /* in mask uv units, made world units by the
                                       mesh's mean uv scale; both 0 = [0.015, 0.04] */
    float wetness_min, wetness_max; /* both 0 = [0.5, 1] */
    uint32_t seed;
} pelt_rain;

/* Blends one droplet into the fur's wetness mask (Silva Alg. 1 as
 * docs/wetness.md reads it). Work is proportional to its footprint. */
pelt_status pelt_fur_add_droplet(pelt_fur *fur, const pelt_droplet *droplet, pelt_error *err);

/* Many droplets in order; faster than one call each (their memory is
 * fetched ahead). All are checked first: a bad one changes nothing. */
pelt_status pelt_fur_add_droplets(pelt_fur *fur, const pelt_droplet *droplets, size_t count,
                                  pelt_error *err);

/* A droplet at a surface point (triangle index and barycentrics) that wets
 * by distance on the surface, radius in world units: across patch borders
 * every patch within the radius is wetted, each texel storing the clump
 * centre in its own patch's coordinates, so the clump renders as one. */
pelt_status pelt_fur_add_droplet_at(pelt_fur *fur, size_t triangle, const float bary[3],
                                    float radius_world, float wetness, pelt_error *err);

/* A droplet where a ray (in mesh coordinates) first hits the mesh, found
 * through a BVH built with the fur (fast enough per mouse event on a
 * 365k-triangle mesh), then wetting as pelt_fur_add_droplet_at there; rain
 * takes the same path. False when the ray misses or the radius or wetness
 * is not a finite number (radius >= 0). */
bool pelt_fur_add_droplet_ray(pelt_fur *fur, const float origin[3], const float direction[3],
                              float radius_world, float wetness);

/* `count` droplets at seeded random surface points (uniform by area),
 * radii and wetness from the ranges of `rain` (its rate is ignored); radii
 * in mask units convert to world units by the mesh's mean uv scale. Each
 * wets by distance on the surface, across patch borders. */
void pelt_fur_add_random_droplets(pelt_fur *fur, const pelt_rain *rain, unsigned count);

/* Rain that pelt_fur_step lets fall (rate 0 stops it; see pelt_rain):
 * drops fall along the mesh's -Y axis from above its bounds and wet where
 * they hit (top surfaces first). Restarts the random sequence from
 * rain->seed. And the drying rate: wetness lost per second. */
void pelt_fur_set_rain(pelt_fur *fur, const pelt_rain *rain);
void pelt_fur_set_dry_rate(pelt_fur *fur, float rate_per_second);
/* Dries all the fur at once (a towel). */
void pelt_fur_clear_wetness(pelt_fur *fur);

/* Changes only the rain's rate (0 stops it), keeping its random sequence. */
void pelt_fur_set_rain_rate(pelt_fur *fur, float drops_per_second);

/* Paints wetness from an 8-bit greyscale image (Silva Fig. 12c): grey
 * level times `wetness`, cut into clumps. */
pelt_status pelt_fur_paint_wetness(pelt_fur *fur, const uint8_t *grey, unsigned width,
                                   unsigned height, float wetness, pelt_error *err);

/* The mask as a picture like the insets of Silva Fig. 11 (black dry, blue
 * wet), RGBA8, mask_size^2 * 4 bytes, top row first. */
unsigned pelt_fur_mask_size(const pelt_fur *fur);
void pelt_fur_mask_picture(const pelt_fur *fur, uint8_t *rgba);

#ifdef __cplusplus
}
#endif
#endif
