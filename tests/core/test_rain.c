/* Rain, random drops and the ray -> droplet path, as the product runs them:
 * core/wet/rain.c (pelt__rain_step, pelt__rain_random_drops), core/wet/
 * surface_droplet.c (pelt__droplet_ray) and their pelt_fur_* entry points.
 * Expected values come from the geometry of hand-made meshes. */
#include "support/check.h"
#include "core/mesh/mesh_internal.h"
#include "core/wet/rain.h"
#include "pelt/dynamics.h"
#include "pelt/fur.h"
#include "pelt/wetness.h"

#include <stdlib.h>
#include <string.h>

/* A horizontal square (normal +Y) at height y over x in [x0, x0 + side],
 * z in [0, side], mapped to the uv rectangle [u0, u0 + du] x [0, dv]. */
typedef struct quad {
    float x0, side, y, u0, du, dv;
} quad;

static pelt_mesh *quads_mesh(const quad *q, size_t n)
{
    float pos[8 * 12], uv[8 * 8];
    uint32_t idx[8 * 6];
    for (size_t k = 0; k < n; k++) {
        const float cx[4] = {0, 1, 1, 0}, cz[4] = {0, 0, 1, 1};
        for (int c = 0; c < 4; c++) {
            size_t v = 4 * k + (size_t)c;
            pos[3 * v + 0] = q[k].x0 + cx[c] * q[k].side;
            pos[3 * v + 1] = q[k].y;
            pos[3 * v + 2] = cz[c] * q[k].side;
            uv[2 * v + 0] = q[k].u0 + cx[c] * q[k].du;
            uv[2 * v + 1] = cz[c] * q[k].dv;
        }
        const uint32_t t[6] = {0, 2, 1, 0, 3, 2}; /* counter-clockwise seen from +Y */
        for (int i = 0; i < 6; i++) idx[6 * k + (size_t)i] = (uint32_t)(4 * k) + t[i];
    }
    pelt_mesh_data d = {.positions = pos, .uvs = uv, .vertex_count = 4 * n, .indices = idx,
                        .triangle_count = 2 * n};
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_create(&d, &m, NULL) == PELT_OK);
    return m;
}

/* What a rain needs to fall: the mesh's surface index and BVH and a mask. */
typedef struct sky {
    pelt_mesh *mesh;
    pelt__surface_index *index;
    pelt__bvh *bvh;
    pelt__wetness *mask;
    pelt__rain *rains[4]; /* made by make_rain, freed by sky_free */
    int rain_count;
} sky;

static bool sky_make(sky *s, const quad *q, size_t n, unsigned mask_size)
{
    memset(s, 0, sizeof *s);
    s->mesh = quads_mesh(q, n);
    if (!s->mesh) return false;
    CHECK(pelt__surface_index_create(s->mesh, NULL, &s->index, NULL) == PELT_OK);
    CHECK(pelt__bvh_build(s->mesh, NULL, &s->bvh, NULL) == PELT_OK);
    CHECK(pelt__wetness_create(mask_size, mask_size, NULL, &s->mask, NULL) == PELT_OK);
    return s->index && s->bvh && s->mask;
}

static void sky_free(sky *s)
{
    for (int i = 0; i < s->rain_count; i++) pelt__rain_destroy(s->rains[i]);
    pelt__wetness_destroy(s->mask);
    pelt__bvh_destroy(s->bvh);
    pelt__surface_index_destroy(s->index);
    pelt_mesh_destroy(s->mesh);
}

/* Rain over the sky's mesh, kept with the sky. */
static pelt__rain *make_rain(sky *s, const pelt_rain *settings)
{
    pelt__rain *r = NULL;
    CHECK(s->rain_count < 4 && pelt__rain_create(s->mesh, NULL, &r, NULL) == PELT_OK);
    if (r) s->rains[s->rain_count++] = r;
    if (r && settings) pelt__rain_set(r, settings);
    return r;
}

static size_t texel_bytes(const pelt__wetness *m)
{
    return (size_t)m->width * m->height * 4 * sizeof(float);
}

static const quad unit_square = {0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 1.0f}; /* uv = (x, z) */

static void rain_is_deterministic_per_seed(void)
{
    sky a, b, c;
    if (!sky_make(&a, &unit_square, 1, 64) || !sky_make(&b, &unit_square, 1, 64) ||
        !sky_make(&c, &unit_square, 1, 64))
        return;
    pelt_rain rain = {.rate = 50.0f, .seed = 7}, other = rain;
    other.seed = 8;
    pelt__rain *ra = make_rain(&a, &rain), *rb = make_rain(&b, &rain), *rc = make_rain(&c, &other);
    for (int i = 0; i < 30; i++) {
        float dt = 0.01f + 0.002f * (float)(i % 7);
        pelt__rain_step(ra, a.mask, a.index, a.bvh, dt);
        pelt__rain_step(rb, b.mask, b.index, b.bvh, dt);
        pelt__rain_step(rc, c.mask, c.index, c.bvh, dt);
    }
    CHECK(memcmp(a.mask->texels, b.mask->texels, texel_bytes(a.mask)) == 0);
    CHECK(memcmp(a.mask->texels, c.mask->texels, texel_bytes(a.mask)) != 0);
    sky_free(&a);
    sky_free(&b);
    sky_free(&c);
}

static void rain_rate_is_right_on_average_and_fractions_carry(void)
{
    sky s;
    if (!sky_make(&s, &unit_square, 1, 32)) return;
    pelt_rain rain = {.rate = 37.5f, .radius_min = 0.01f, .radius_max = 0.02f,
                      .wetness_min = 0.2f, .wetness_max = 0.4f, .seed = 3};
    pelt__rain *r = make_rain(&s, &rain);
    size_t total = 0;
    double time = 0.0;
    for (int i = 0; i < 1000; i++) {
        float dt = (i % 3 == 0) ? 0.005f : 0.02f; /* fractions must carry */
        total += pelt__rain_step(r, s.mask, s.index, s.bvh, dt);
        time += dt;
    }
    /* Accumulated fractions: off by less than one drop overall. */
    CHECK_NEAR((double)total, 37.5 * time, 1.0);
    /* Every wet texel's wetness is from the range or merges clamped to 1. */
    size_t wet = 0;
    for (unsigned i = 0; i < 32 * 32; i++) {
        float w = s.mask->texels[i * 4 + 3];
        wet += w > 0.0f;
        CHECK(w == 0.0f || (w >= 0.2f - 1e-6f && w <= 1.0f));
    }
    CHECK(wet > 100);
    CHECK(pelt__rain_step(r, s.mask, s.index, s.bvh, 0.0f) == 0);
    CHECK(pelt__rain_step(r, s.mask, s.index, s.bvh, -1.0f) == 0);
    pelt__rain_set_rate(r, NAN);
    CHECK(pelt__rain_step(r, s.mask, s.index, s.bvh, 1.0f) == 0);
    pelt_rain none = {0};
    pelt__rain_set(r, &none);
    CHECK(pelt__rain_step(r, s.mask, s.index, s.bvh, 1.0f) == 0);
    sky_free(&s);
}

static void rain_step_is_bounded(void)
{
    sky s;
    if (!sky_make(&s, &unit_square, 1, 16)) return;
    pelt_rain rain = {.rate = 1e9f, .radius_min = 0.01f, .radius_max = 0.01f, .seed = 2};
    pelt__rain *r = make_rain(&s, &rain);
    CHECK(pelt__rain_step(r, s.mask, s.index, s.bvh, 1.0f) == PELT__RAIN_MAX_PER_STEP);
    rain.rate = INFINITY;
    pelt__rain_set(r, &rain);
    CHECK(pelt__rain_step(r, s.mask, s.index, s.bvh, 1.0f) == 0);
    sky_free(&s);
}

static void rain_falls_uniformly_over_the_bounds(void)
{
    /* Drops of wetness 1 that cover the whole square merge with alpha = 1,
     * so every texel of a 2x2 mask holds the last drop's centre: the uv of
     * the point it hit, (x, z) of where it fell. */
    sky s;
    if (!sky_make(&s, &unit_square, 1, 2)) return;
    pelt_rain rain = {.rate = 1.0f, .radius_min = 1.5f, .radius_max = 1.5f,
                      .wetness_min = 1.0f, .wetness_max = 1.0f, .seed = 11};
    pelt__rain *r = make_rain(&s, &rain);
    double sx = 0.0, sz = 0.0, sxx = 0.0, szz = 0.0;
    const int n = 4000;
    for (int i = 0; i < n; i++) {
        CHECK(pelt__rain_step(r, s.mask, s.index, s.bvh, 1.0f) == 1);
        double x = s.mask->texels[0], z = s.mask->texels[1];
        CHECK(s.mask->texels[4 * 3 + 0] == (float)x && s.mask->texels[4 * 3 + 1] == (float)z);
        sx += x, sz += z, sxx += x * x, szz += z * z;
    }
    /* Uniform on [0,1]: mean 1/2, mean square 1/3. */
    CHECK_NEAR(sx / n, 0.5, 0.02);
    CHECK_NEAR(sz / n, 0.5, 0.02);
    CHECK_NEAR(sxx / n, 1.0 / 3.0, 0.02);
    CHECK_NEAR(szz / n, 1.0 / 3.0, 0.02);
    sky_free(&s);
}

static void rain_wets_only_what_it_falls_on(void)
{
    /* A roof at y = 1 over a floor at y = 0, same x-z extent; the roof
     * holds the left half of the mask, the floor the right half. Rain
     * falls along -Y, so the floor stays dry. */
    const quad q[2] = {{0.0f, 1.0f, 1.0f, 0.0f, 0.5f, 1.0f}, {0.0f, 1.0f, 0.0f, 0.5f, 0.5f, 1.0f}};
    sky s;
    if (!sky_make(&s, q, 2, 32)) return;
    pelt_rain rain = {.rate = 200.0f, .radius_min = 0.02f, .radius_max = 0.05f, .seed = 4};
    pelt__rain *r = make_rain(&s, &rain);
    for (int i = 0; i < 10; i++) pelt__rain_step(r, s.mask, s.index, s.bvh, 0.1f);
    size_t roof = 0, floor_ = 0;
    for (unsigned y = 0; y < 32; y++)
        for (unsigned x = 0; x < 32; x++) {
            bool wet = s.mask->texels[((size_t)y * 32 + x) * 4 + 3] > 0.0f;
            if (x < 16) roof += wet;
            else floor_ += wet;
        }
    CHECK(roof > 16 * 32 / 2);
    CHECK(floor_ == 0);
    sky_free(&s);
}

static void rain_radius_converts_by_the_mean_uv_scale(void)
{
    /* A square of side 2 mapped to the whole uv square: 2 world units per
     * uv unit. A 0.05-uv drop is 0.1 world units wide and stores r = 0.05. */
    const quad q = {0.0f, 2.0f, 0.0f, 0.0f, 1.0f, 1.0f};
    sky s;
    if (!sky_make(&s, &q, 1, 64)) return;
    pelt_rain rain = {.rate = 20.0f, .radius_min = 0.05f, .radius_max = 0.05f,
                      .wetness_min = 0.5f, .wetness_max = 0.5f, .seed = 9};
    pelt__rain *r = make_rain(&s, &rain);
    pelt__rain_step(r, s.mask, s.index, s.bvh, 1.0f);
    size_t wet = 0;
    for (unsigned i = 0; i < 64 * 64; i++) {
        const float *t = s.mask->texels + (size_t)i * 4;
        if (!(t[3] > 0.0f)) continue;
        wet++;
        CHECK_NEAR(t[2], 0.05, 1e-6);
        /* Every wet texel lies within its clump (distance on this flat
         * square is uv distance times 2). */
        double u = (i % 64 + 0.5) / 64.0, v = (i / 64 + 0.5) / 64.0;
        CHECK(hypot(u - t[0], v - t[1]) <= 0.05 + 1e-6);
    }
    CHECK(wet > 0);
    sky_free(&s);
}

static void rain_set_restarts_the_sequence_and_set_rate_keeps_it(void)
{
    sky a, b, c;
    if (!sky_make(&a, &unit_square, 1, 32) || !sky_make(&b, &unit_square, 1, 32) ||
        !sky_make(&c, &unit_square, 1, 32))
        return;
    pelt_rain rain = {.rate = 10.0f, .seed = 5};
    pelt__rain *ra = make_rain(&a, &rain), *rb = make_rain(&b, &rain), *rc = make_rain(&c, &rain);
    /* a: two steps; b: a pause (rate 0) between them; c: restarted. */
    pelt__rain_step(ra, a.mask, a.index, a.bvh, 1.0f);
    pelt__rain_step(ra, a.mask, a.index, a.bvh, 1.0f);
    pelt__rain_step(rb, b.mask, b.index, b.bvh, 1.0f);
    pelt__rain_set_rate(rb, 0.0f);
    CHECK(pelt__rain_step(rb, b.mask, b.index, b.bvh, 1.0f) == 0);
    pelt__rain_set_rate(rb, 10.0f);
    pelt__rain_step(rb, b.mask, b.index, b.bvh, 1.0f);
    pelt__rain_step(rc, c.mask, c.index, c.bvh, 1.0f);
    pelt__rain_set(rc, &rain);
    pelt__rain_step(rc, c.mask, c.index, c.bvh, 1.0f);
    CHECK(memcmp(a.mask->texels, b.mask->texels, texel_bytes(a.mask)) == 0);
    CHECK(memcmp(a.mask->texels, c.mask->texels, texel_bytes(a.mask)) != 0);
    sky_free(&a);
    sky_free(&b);
    sky_free(&c);
}

static void rain_needs_a_mesh(void)
{
    int dummy = 0;
    pelt__rain *r = (pelt__rain *)(void *)&dummy;
    pelt_error err = {0};
    CHECK(pelt__rain_create(NULL, NULL, &r, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(r == NULL);
    CHECK(strstr(err.message, "rain") != NULL);
}

static void random_drops_land_by_area(void)
{
    /* Two separate squares, areas 1 and 4, each holding one half of a 2x2
     * mask; a drop wide enough to cover its square wets only its half.
     * One drop per seed: the big square takes 4/5 of them. */
    const quad q[2] = {{0.0f, 1.0f, 0.0f, 0.0f, 0.5f, 1.0f}, {3.0f, 2.0f, 0.0f, 0.5f, 0.5f, 1.0f}};
    sky s;
    if (!sky_make(&s, q, 2, 2)) return;
    pelt__rain *r = make_rain(&s, NULL);
    const int n = 2000;
    int big = 0, small = 0;
    for (int i = 0; i < n; i++) {
        pelt_rain drops = {.radius_min = 1.5f, .radius_max = 1.5f, .seed = (uint32_t)i + 1};
        pelt__wetness_clear(s.mask);
        pelt__rain_random_drops(r, &drops, 1, s.mask, s.index);
        bool left = s.mask->texels[3] > 0.0f, right = s.mask->texels[4 + 3] > 0.0f;
        CHECK(left != right);
        big += right;
        small += left;
    }
    CHECK_NEAR((double)big / n, 0.8, 0.03);
    CHECK(big + small == n);
    sky_free(&s);
}

static void random_drops_are_seeded_and_leave_the_rain_alone(void)
{
    sky a, b;
    if (!sky_make(&a, &unit_square, 1, 64) || !sky_make(&b, &unit_square, 1, 64)) return;
    pelt__wetness *scratch = NULL;
    CHECK(pelt__wetness_create(64, 64, NULL, &scratch, NULL) == PELT_OK);
    if (!scratch) return;
    pelt_rain drops = {.radius_min = 0.02f, .radius_max = 0.04f, .seed = 21};
    pelt_rain rain = {.rate = 10.0f, .seed = 6};
    pelt__rain *ra = make_rain(&a, &rain), *rb = make_rain(&b, &rain);
    /* Same seed, same drops. */
    pelt__rain_random_drops(ra, &drops, 50, a.mask, a.index);
    pelt__rain_random_drops(rb, &drops, 50, scratch, b.index);
    CHECK(memcmp(a.mask->texels, scratch->texels, texel_bytes(scratch)) == 0);
    size_t wet = 0;
    for (unsigned i = 0; i < 64 * 64; i++) wet += a.mask->texels[(size_t)i * 4 + 3] > 0.0f;
    CHECK(wet > 50);
    /* Random drops do not draw from the rain's sequence: after them (rb)
     * or without them (a fresh rain) the rain falls the same. */
    pelt__rain *fresh = make_rain(&a, &rain);
    pelt__wetness_clear(a.mask);
    pelt__rain_step(fresh, a.mask, a.index, a.bvh, 1.0f);
    pelt__rain_step(rb, b.mask, b.index, b.bvh, 1.0f);
    CHECK(memcmp(a.mask->texels, b.mask->texels, texel_bytes(a.mask)) == 0);
    pelt__wetness_destroy(scratch);
    sky_free(&a);
    sky_free(&b);
}

static void ray_droplet_lands_where_the_ray_hits(void)
{
    /* The unit square (uv = (x, z)) seen from above: a ray down through
     * (0.3, 0.7) wets the clump centred there, radius 0.05 in world and uv
     * units alike. */
    sky s;
    if (!sky_make(&s, &unit_square, 1, 64)) return;
    float o[3] = {0.3f, 2.0f, 0.7f}, down[3] = {0.0f, -1.0f, 0.0f};
    CHECK(pelt__droplet_ray(s.mask, s.mesh, s.index, s.bvh, o, down, 0.05f, 0.9f));
    size_t wet = 0;
    for (unsigned y = 0; y < 64; y++)
        for (unsigned x = 0; x < 64; x++) {
            const float *t = s.mask->texels + ((size_t)y * 64 + x) * 4;
            double dist = hypot((x + 0.5) / 64.0 - 0.3, (y + 0.5) / 64.0 - 0.7);
            if (fabs(dist - 0.05) < 1e-5) continue; /* float rounding decides */
            CHECK((t[3] > 0.0f) == (dist < 0.05));
            if (!(t[3] > 0.0f)) continue;
            wet++;
            CHECK_NEAR(t[0], 0.3, 1e-6);
            CHECK_NEAR(t[1], 0.7, 1e-6);
            CHECK_NEAR(t[2], 0.05, 1e-6);
            CHECK(t[3] == 0.9f);
        }
    CHECK(wet > 20);
    /* A miss, or a bad radius, changes nothing. */
    unsigned rect[4];
    pelt__wetness_take_dirty(s.mask, rect);
    float miss[3] = {2.0f, 2.0f, 2.0f}, up[3] = {0.0f, 1.0f, 0.0f};
    CHECK(!pelt__droplet_ray(s.mask, s.mesh, s.index, s.bvh, miss, down, 0.05f, 0.9f));
    CHECK(!pelt__droplet_ray(s.mask, s.mesh, s.index, s.bvh, o, up, 0.05f, 0.9f));
    CHECK(!pelt__droplet_ray(s.mask, s.mesh, s.index, s.bvh, o, down, -0.05f, 0.9f));
    CHECK(!pelt__droplet_ray(s.mask, s.mesh, s.index, s.bvh, o, down, NAN, 0.9f));
    CHECK(!pelt__wetness_take_dirty(s.mask, rect));
    sky_free(&s);
}

/* The public entry points: pelt_fur_add_droplet_ray, pelt_fur_set_rain,
 * pelt_fur_step and pelt_fur_add_random_droplets over a fur. */
static pelt_fur *small_fur(const pelt_mesh *m)
{
    pelt_fur_desc d = {.layers = 2, .look = {.texture_size = 8}, .wet = {.mask_size = 64}};
    pelt_fur *f = NULL;
    CHECK(pelt_fur_create(m, &d, &f, NULL) == PELT_OK);
    return f;
}

static size_t wet_pixels(const pelt_fur *f, uint8_t *px)
{
    unsigned n = pelt_fur_mask_size(f);
    pelt_fur_mask_picture(f, px);
    size_t wet = 0;
    for (size_t i = 0; i < (size_t)n * n; i++) wet += px[i * 4 + 2] > 0;
    return wet;
}

static void fur_rain_and_ray_droplets_through_the_public_api(void)
{
    pelt_mesh *m = quads_mesh(&unit_square, 1);
    if (!m) return;
    pelt_fur *a = small_fur(m), *b = small_fur(m);
    if (!a || !b) return;
    CHECK(pelt_fur_mask_size(a) == 64);
    size_t bytes = 64 * 64 * 4;
    uint8_t *pa = malloc(bytes), *pb = malloc(bytes);
    /* A ray down onto the square wets it; one beside it misses. */
    float o[3] = {0.5f, 1.0f, 0.5f}, down[3] = {0.0f, -1.0f, 0.0f}, miss[3] = {3.0f, 1.0f, 0.5f};
    CHECK(pelt_fur_add_droplet_ray(a, o, down, 0.1f, 1.0f));
    CHECK(!pelt_fur_add_droplet_ray(a, miss, down, 0.1f, 1.0f));
    size_t one = wet_pixels(a, pa);
    /* pi (0.1 * 64)^2 texels, give or take the rim. */
    CHECK(one > 110 && one < 145);
    CHECK(pa[((64 - 1 - 32) * 64 + 32) * 4 + 2] > 0);
    /* Same rain, same steps: same mask; no rain: nothing more. */
    pelt_fur_clear_wetness(a);
    pelt_rain rain = {.rate = 40.0f, .radius_min = 0.02f, .radius_max = 0.03f, .seed = 3};
    pelt_fur_set_rain(a, &rain);
    pelt_fur_set_rain(b, &rain);
    for (int i = 0; i < 10; i++) {
        pelt_fur_step(a, 0.05f, NULL);
        pelt_fur_step(b, 0.05f, NULL);
    }
    size_t wa = wet_pixels(a, pa), wb = wet_pixels(b, pb);
    CHECK(wa > 0 && wa == wb && memcmp(pa, pb, bytes) == 0);
    pelt_fur_set_rain_rate(a, 0.0f);
    pelt_fur_step(a, 1.0f, NULL);
    CHECK(wet_pixels(a, pa) == wa);
    /* Random drops: seeded, the same on both. */
    pelt_fur_clear_wetness(a);
    pelt_fur_clear_wetness(b);
    pelt_rain drops = {.radius_min = 0.03f, .radius_max = 0.03f, .seed = 8};
    pelt_fur_add_random_droplets(a, &drops, 20);
    pelt_fur_add_random_droplets(b, &drops, 20);
    CHECK(wet_pixels(a, pa) > 0 && wet_pixels(b, pb) > 0 && memcmp(pa, pb, bytes) == 0);
    free(pa);
    free(pb);
    pelt_fur_destroy(a);
    pelt_fur_destroy(b);
    pelt_mesh_destroy(m);
}

int main(void)
{
    RUN(rain_is_deterministic_per_seed);
    RUN(rain_rate_is_right_on_average_and_fractions_carry);
    RUN(rain_step_is_bounded);
    RUN(rain_falls_uniformly_over_the_bounds);
    RUN(rain_wets_only_what_it_falls_on);
    RUN(rain_radius_converts_by_the_mean_uv_scale);
    RUN(rain_set_restarts_the_sequence_and_set_rate_keeps_it);
    RUN(rain_needs_a_mesh);
    RUN(random_drops_land_by_area);
    RUN(random_drops_are_seeded_and_leave_the_rain_alone);
    RUN(ray_droplet_lands_where_the_ray_hits);
    RUN(fur_rain_and_ray_droplets_through_the_public_api);
    return check_summary();
}
