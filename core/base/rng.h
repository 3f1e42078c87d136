/* Randomness for core/: a small seeded random generator (PCG32, state owned
 * by the caller) for sequences, and one integer hash for lattices and
 * noise, where a value must come from a position, not from a sequence. */
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

/* The integer hash of pelt: Murmur3's 32-bit finaliser, a bijection in
 * which every input bit affects every output bit. Every lattice and noise
 * takes its values from it (core/base/noise.h). */
static inline uint32_t pelt__hash32(uint32_t h)
{
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
}

/* Folds one integer coordinate c into the hash h. A lattice point hashes
 * one axis at a time, each axis with its own constant `axis_key`, so
 * points that share their outer coordinates share that part of the work. */
static inline uint32_t pelt__hash_axis(uint32_t h, int32_t c, uint32_t axis_key)
{
    return pelt__hash32(h ^ ((uint32_t)c * axis_key));
}

#endif
