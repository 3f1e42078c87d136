/* A small seeded random generator (PCG32), state owned by the caller. */
#ifndef PELT_RNG_H
#define PELT_RNG_H

#include <stdint.h>

typedef struct pelt__rng { uint64_t state, inc; } pelt__rng;

static inline uint32_t pelt__rng_next(pelt__rng *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ULL + r->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31u));
}

static inline pelt__rng pelt__rng_seed(uint64_t seed, uint64_t stream)
{
    pelt__rng r = {0u, (stream << 1u) | 1u};
    pelt__rng_next(&r);
    r.state += seed;
    pelt__rng_next(&r);
    return r;
}

/* Uniform in [0, 1). */
static inline float pelt__rng_float(pelt__rng *r)
{
    return (float)(pelt__rng_next(r) >> 8) * (1.0f / 16777216.0f);
}

static inline float pelt__rng_range(pelt__rng *r, float lo, float hi)
{
    return lo + (hi - lo) * pelt__rng_float(r);
}

#endif
