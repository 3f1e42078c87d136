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

/* Random rain: droplets per second at seeded random places, uniform over
 * [0,1]^2 of the mask, radius and wetness uniform in their ranges.
 * Deterministic for a seed and a sequence of time steps; fractional
 * droplets carry over from one step to the next. */
typedef struct pelt_rain {
    float rate;             /* droplets per second, 0 = no rain */
    float radius_min, radius_max;   /* in mask uv units; both 0 = [0.015, 0.04] */
    float wetness_min, wetness_max; /* both 0 = [0.5, 1] */
    uint32_t seed;
} pelt_rain;

#ifdef __cplusplus
}
#endif
#endif
