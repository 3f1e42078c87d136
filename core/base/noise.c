/* Seeded value noise over a hashed integer lattice (see noise.h). */
#include "core/base/noise.h"

#include "core/base/rng.h"

#include <math.h>

/* One hashing constant per axis of x, one for the slice, one to salt the
 * seed. */
static const uint32_t axis_key[3] = {0xfd7046c5u, 0xd3a2646cu, 0x165667b1u};
#define SLICE_KEY 0x27d4eb2fu
#define SEED_SALT 0x9e3779b9u

float pelt__noise_cell(float x, int32_t *cell)
{
    float xc = clampf(x, -PELT__NOISE_MAX, PELT__NOISE_MAX);
    if (xc != xc) xc = 0.0f; /* NaN */
    float fl = floorf(xc);
    float f = xc - fl;
    *cell = (int32_t)fl;
    return f * f * (3.0f - 2.0f * f);
}

/* Three channels in [-1, 1] from 10 bits each. */
static pelt_vec3 lattice_value(uint32_t h)
{
    const float s = 2.0f / 1023.0f;
    return v3((float)(h & 1023u) * s - 1.0f, (float)((h >> 10) & 1023u) * s - 1.0f,
              (float)((h >> 20) & 1023u) * s - 1.0f);
}

static int32_t wrap(int32_t c, int32_t period) { return ((c % period) + period) % period; }

/* The 2^dims corners of the cell are hashed one axis at a time from the
 * outermost (corners that share their outer coordinates share that part of
 * the hashing: 30 hashes for a 4D cell, not 64), then blended from the
 * innermost axis out. Inlined with a constant `dims`, the loops unroll. */
static inline pelt_vec3 lattice_noise(uint32_t seed, int dims, const float *x, int32_t slice,
                                      int32_t period)
{
    int32_t c0[3], c1[3];
    float w[3];
    for (int a = 0; a < dims; a++) {
        w[a] = pelt__noise_cell(x[a], &c0[a]);
        c1[a] = c0[a] + 1;
        if (period > 0) {
            c0[a] = wrap(c0[a], period);
            c1[a] = wrap(c1[a], period);
        }
    }
    /* Bit a of a corner's index: it takes c1 (not c0) on axis a. */
    uint32_t h[8];
    h[0] = pelt__hash_axis(pelt__hash32(seed ^ SEED_SALT), slice, SLICE_KEY);
    int n = 1;
    for (int a = dims - 1; a >= 0; a--) {
        for (int i = n - 1; i >= 0; i--) { /* downwards: h[i] is read before it is overwritten */
            uint32_t hi = h[i];
            h[2 * i] = pelt__hash_axis(hi, c0[a], axis_key[a]);
            h[2 * i + 1] = pelt__hash_axis(hi, c1[a], axis_key[a]);
        }
        n *= 2;
    }
    pelt_vec3 v[8];
    for (int i = 0; i < n; i++) v[i] = lattice_value(h[i]);
    for (int a = 0; a < dims; a++) {
        n /= 2;
        for (int i = 0; i < n; i++) v[i] = v3_lerp(v[2 * i], v[2 * i + 1], w[a]);
    }
    return v[0];
}

pelt_vec3 pelt__value_noise(uint32_t seed, int dims, const float *x, int32_t slice, int32_t period)
{
    /* A constant dims in each call, so each gets its own unrolled copy. */
    if (dims <= 1) return lattice_noise(seed, 1, x, slice, period);
    if (dims == 2) return lattice_noise(seed, 2, x, slice, period);
    return lattice_noise(seed, 3, x, slice, period);
}
