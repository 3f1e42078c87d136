/* Exact triangle rasterization over texel grids in fixed point, shared by
 * the atlas overlap check and the surface droplets, so both agree on which
 * triangle owns a texel centre. */
#ifndef PELT_RASTER_H
#define PELT_RASTER_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#define PELT__RASTER_SUB 256 /* fixed-point steps per texel */

/* A uv coordinate in fixed-point texels of a res-texel grid; far-outside
 * coordinates are clamped (they only matter for "outside"). */
static inline int64_t pelt__raster_fixed(float x, unsigned res)
{
    double v = (double)x * (double)res;
    double lim = 4.0 * (double)res + 4.0;
    if (!(v > -lim)) v = -lim;
    if (v > lim) v = lim;
    return (int64_t)llround(v * PELT__RASTER_SUB);
}

/* A sample exactly on an edge belongs to the triangle for which that edge
 * is "top-left": of the two opposite traversals of a shared edge exactly
 * one qualifies, so neighbours never both claim it. */
static inline bool pelt__raster_top_left(int64_t dx, int64_t dy)
{
    return dy < 0 || (dy == 0 && dx > 0);
}

#endif
