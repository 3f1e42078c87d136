/* core/base helpers that several modules share: the one integer hash
 * (rng.h), the one value noise (noise.c), the one orthonormal basis and
 * the one 4x4 product (vec.h). */
#include "support/check.h"

#include "core/base/noise.h"
#include "core/base/rng.h"
#include "core/base/vec.h"

#include <math.h>
#include <string.h>

static float channel_gap(pelt_vec3 a, pelt_vec3 b)
{
    return fmaxf(fabsf(a.x - b.x), fmaxf(fabsf(a.y - b.y), fabsf(a.z - b.z)));
}

static void hash32_is_the_murmur3_finaliser(void)
{
    /* fmix32 of Murmur3 (Appleby): 0 is its fixed point; a known value. */
    CHECK(pelt__hash32(0u) == 0u);
    CHECK(pelt__hash32(1u) == 0x514e28b7u);
    CHECK(pelt__hash_axis(7u, 3, 0x27d4eb2fu) == pelt__hash32(7u ^ (3u * 0x27d4eb2fu)));
}

static void noise_cell_is_floor_and_smoothstep(void)
{
    int32_t c = 0;
    CHECK(pelt__noise_cell(2.0f, &c) == 0.0f && c == 2);
    CHECK_NEAR(pelt__noise_cell(-1.5f, &c), 0.5f, 1e-7);
    CHECK(c == -2);
    CHECK_NEAR(pelt__noise_cell(0.25f, &c), 0.25f * 0.25f * (3.0f - 0.5f), 1e-7);
    /* Huge and not-a-number coordinates still give a cell and a weight in [0, 1]. */
    float w = pelt__noise_cell(3e38f, &c);
    CHECK(w >= 0.0f && w <= 1.0f && c == (int32_t)PELT__NOISE_MAX);
    w = pelt__noise_cell(NAN, &c);
    CHECK(w >= 0.0f && w <= 1.0f);
}

static void value_noise_is_deterministic_and_in_range(void)
{
    for (int dims = 1; dims <= 3; dims++) {
        float lo = 1.0f, hi = -1.0f;
        for (int i = 0; i < 4000; i++) {
            float x[3] = {0.173f * (float)i - 300.0f, 0.071f * (float)i, -0.37f * (float)i};
            pelt_vec3 a = pelt__value_noise(9u, dims, x, i % 5, 0);
            pelt_vec3 b = pelt__value_noise(9u, dims, x, i % 5, 0);
            CHECK(memcmp(&a, &b, sizeof a) == 0);
            CHECK(fabsf(a.x) <= 1.0f && fabsf(a.y) <= 1.0f && fabsf(a.z) <= 1.0f);
            lo = fminf(lo, a.x);
            hi = fmaxf(hi, a.x);
        }
        /* It spans most of [-1, 1]. */
        CHECK(lo < -0.8f && hi > 0.8f);
    }
}

static void value_noise_is_continuous_across_cells(void)
{
    /* Just below and just above a lattice plane, on every axis. */
    for (int axis = 0; axis < 3; axis++)
        for (int i = -5; i <= 5; i++) {
            float a[3] = {0.3f, 1.7f, -2.2f}, b[3];
            a[axis] = (float)i - 1e-4f;
            memcpy(b, a, sizeof b);
            b[axis] = (float)i + 1e-4f;
            CHECK(channel_gap(pelt__value_noise(3u, 3, a, 0, 0), pelt__value_noise(3u, 3, b, 0, 0)) < 1e-3f);
        }
}

static void value_noise_tiles_with_its_period(void)
{
    const int32_t period = 8;
    size_t differ_unwrapped = 0;
    for (int i = 0; i < 500; i++) {
        float x[2] = {0.0161f * (float)i * 8.0f, 0.0093f * (float)i * 8.0f};
        float y[2] = {x[0] + (float)period, x[1] - 2.0f * (float)period};
        pelt_vec3 a = pelt__value_noise(5u, 2, x, 1, period);
        pelt_vec3 b = pelt__value_noise(5u, 2, y, 1, period);
        CHECK(channel_gap(a, b) < 1e-4f);
        if (channel_gap(pelt__value_noise(5u, 2, x, 1, 0), pelt__value_noise(5u, 2, y, 1, 0)) > 1e-3f)
            differ_unwrapped++;
    }
    /* Without a period the same shift lands elsewhere. */
    CHECK(differ_unwrapped > 450);
}

static void value_noise_differs_by_seed_and_slice(void)
{
    size_t by_seed = 0, by_slice = 0;
    for (int i = 0; i < 200; i++) {
        float x[3] = {0.37f * (float)i, 0.11f * (float)i, 0.5f};
        pelt_vec3 a = pelt__value_noise(1u, 3, x, 0, 0);
        if (channel_gap(a, pelt__value_noise(2u, 3, x, 0, 0)) > 1e-3f) by_seed++;
        if (channel_gap(a, pelt__value_noise(1u, 3, x, 1, 0)) > 1e-3f) by_slice++;
    }
    CHECK(by_seed > 190);
    CHECK(by_slice > 190);
}

/* The one 4x4 product (column-major, out = a b): a translation after a
 * scale moves a point as the two applied in turn; out may alias a or b, as
 * the skeleton's node walk needs. */
static void mat4_mul_composes_column_major_and_may_alias(void)
{
    float scale[16] = {2, 0, 0, 0, 0, 3, 0, 0, 0, 0, 4, 0, 0, 0, 0, 1};
    float move[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1};
    float m[16];
    pelt__mat4_mul(m, move, scale); /* scale first, then move */
    const float want[16] = {2, 0, 0, 0, 0, 3, 0, 0, 0, 0, 4, 0, 5, 6, 7, 1};
    CHECK(memcmp(m, want, sizeof m) == 0);
    pelt__mat4_mul(m, scale, move); /* move first: the move is scaled */
    CHECK(m[12] == 10.0f && m[13] == 18.0f && m[14] == 28.0f && m[0] == 2.0f);
    float alias[16];
    memcpy(alias, scale, sizeof alias);
    pelt__mat4_mul(alias, move, alias);
    CHECK(memcmp(alias, want, sizeof alias) == 0);
}

static void basis_is_orthonormal_and_right_handed(void)
{
    pelt__rng r = pelt__rng_seed(3, 4);
    float worst = 0.0f;
    for (int i = 0; i < 20000; i++) {
        pelt_vec3 n = v3_norm_or(v3(pelt__rng_range(&r, -1, 1), pelt__rng_range(&r, -1, 1),
                                    pelt__rng_range(&r, -1, 1)), v3(0, 0, 1));
        if (i < 6) n = v3(i == 0 ? 1.0f : i == 1 ? -1.0f : 0.0f, i == 2 ? 1.0f : i == 3 ? -1.0f : 0.0f,
                          i == 4 ? 1.0f : i == 5 ? -1.0f : 0.0f); /* the axes */
        pelt_vec3 t, b;
        v3_basis(n, &t, &b);
        pelt_vec3 p = v3_perpendicular(n);
        CHECK(memcmp(&p, &t, sizeof p) == 0);
        float e = fmaxf(fabsf(v3_len(t) - 1.0f), fabsf(v3_len(b) - 1.0f));
        e = fmaxf(e, fmaxf(fabsf(v3_dot(t, n)), fmaxf(fabsf(v3_dot(b, n)), fabsf(v3_dot(t, b)))));
        e = fmaxf(e, v3_len(v3_sub(v3_cross(t, b), n))); /* (t, b, n) right-handed */
        worst = fmaxf(worst, e);
    }
    CHECK_NEAR(worst, 0.0f, 1e-5f);
    /* A few values by hand: n = +z gives (x, y); n = -z gives (x, -y). */
    pelt_vec3 t, b;
    v3_basis(v3(0, 0, 1), &t, &b);
    CHECK(t.x == 1.0f && t.y == 0.0f && t.z == 0.0f && b.x == 0.0f && b.y == 1.0f && b.z == 0.0f);
    v3_basis(v3(0, 0, -1), &t, &b);
    CHECK(t.x == 1.0f && t.y == 0.0f && t.z == 0.0f && b.x == 0.0f && b.y == -1.0f && b.z == 0.0f);
}

int main(void)
{
    RUN(hash32_is_the_murmur3_finaliser);
    RUN(noise_cell_is_floor_and_smoothstep);
    RUN(value_noise_is_deterministic_and_in_range);
    RUN(value_noise_is_continuous_across_cells);
    RUN(value_noise_tiles_with_its_period);
    RUN(value_noise_differs_by_seed_and_slice);
    RUN(basis_is_orthonormal_and_right_handed);
    RUN(mat4_mul_composes_column_major_and_may_alias);
    return check_summary();
}
