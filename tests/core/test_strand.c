/* Mass-spring strands (core/fur/strand.c): Silva et al. Eq. 2-3 invariants,
 * rest, wind, inertia, seams and bad input. */
#include "support/check.h"

#include "core/mesh/mesh_internal.h"
#include "core/base/rng.h"
#include "core/fur/fur_internal.h"
#include "core/fur/strand.h"
#include "core/wet/clump.h"
#include "pelt/wetness.h"
#include "core/base/vec.h"
#include "core/base/workers.h"

#include <math.h>
#include <string.h>

static pelt_mesh *torus(unsigned major, unsigned minor)
{
    pelt_mesh *m = NULL;
    pelt_error err;
    if (pelt_mesh_torus(1.0f, 0.4f, major, minor, &m, &err) != PELT_OK) {
        fprintf(stderr, "  torus: %s\n", err.message);
        return NULL;
    }
    return m;
}

static pelt_mesh *square(unsigned subdivisions)
{
    pelt_mesh *m = NULL;
    if (pelt_mesh_square(1.0f, subdivisions, &m, NULL) != PELT_OK) return NULL;
    return m;
}

static pelt__strands *strands_for(const pelt_mesh *m, const pelt__strand_params *p)
{
    pelt__strands *s = NULL;
    pelt_error err;
    if (pelt__strands_create(m, p, NULL, &s, &err) != PELT_OK) {
        fprintf(stderr, "  strands: %s\n", err.message);
        return NULL;
    }
    return s;
}

/* The fur length most tests use. */
#define L0_TEST 0.1f

/* The strand parameters the product runs for fur of length L0: the fur
 * desc's defaults (pelt__fur_desc_defaults), the one home of them. */
static pelt__strand_params fur_defaults(float length)
{
    pelt_fur_desc d = {0};
    d.length = length;
    pelt__fur_desc_defaults(&d, NULL);
    pelt__strand_params p = {d.length, d.dynamics.spring_k, d.dynamics.mass, d.dynamics.damping, 0};
    return p;
}

static pelt__strands *strands_default(const pelt_mesh *m)
{
    pelt__strand_params p = fur_defaults(L0_TEST);
    return strands_for(m, &p);
}

static pelt_forces no_forces(void)
{
    pelt_forces f = pelt_forces_default();
    memset(f.gravity, 0, sizeof f.gravity);
    f.gust_strength = 0.0f;
    return f;
}

static pelt_vec3 offset_of(const pelt__strands *s, size_t i)
{
    return v3_load(pelt__strands_tip_offsets(s) + 3 * i);
}

static pelt_vec3 normal_of(const pelt_mesh *m, size_t i) { return v3_load(m->normals + 3 * i); }

/* Random magnitude spanning 1e-3..1e12, random sign, now and then NaN/inf. */
static float wild(pelt__rng *r)
{
    uint32_t pick = pelt__rng_next(r) % 50u;
    if (pick == 0) return NAN;
    if (pick == 1) return INFINITY;
    if (pick == 2) return -INFINITY;
    if (pick == 3) return 3e38f;
    float mag = powf(10.0f, pelt__rng_range(r, -3.0f, 12.0f));
    return (pelt__rng_next(r) & 1u) ? mag : -mag;
}

static void strand_constraints_hold_after_100000_random_steps(void)
{
    pelt_mesh *m = torus(8, 6);
    pelt__strand_params p = fur_defaults(0.1f);
    pelt__strands *s = m ? strands_for(m, &p) : NULL;
    CHECK(s != NULL);
    if (!s) {
        pelt_mesh_destroy(m);
        return;
    }
    pelt__rng r = pelt__rng_seed(42, 7);
    const float L0 = p.length;
    size_t violations = 0, nonfinite = 0;
    float worst_len = 0.0f, worst_dn = 0.0f;
    float time = 0.0f;
    for (int step = 0; step < 100000; step++) {
        pelt_forces f = pelt_forces_default();
        uint32_t kind = pelt__rng_next(&r) % 4u;
        for (int k = 0; k < 3; k++) {
            /* Mostly sane forces, a quarter of the time anything at all. */
            f.gravity[k] = kind == 0 ? wild(&r) : pelt__rng_range(&r, -50.0f, 50.0f);
            f.wind[k] = kind == 0 ? wild(&r) : pelt__rng_range(&r, -200.0f, 200.0f);
        }
        f.gust_strength = kind == 0 ? wild(&r) : pelt__rng_range(&r, 0.0f, 2.0f);
        f.gust_scale = kind == 0 ? wild(&r) : pelt__rng_range(&r, 0.01f, 2.0f);
        f.gust_frequency = kind == 0 ? wild(&r) : pelt__rng_range(&r, 0.0f, 5.0f);
        /* dt log-uniform in [1e-5, 0.5] s. */
        float dt = 1e-5f * powf(0.5f / 1e-5f, pelt__rng_float(&r));
        if (step % 97 == 0) {
            /* Rigid motion: rotation about a random axis plus a translation. */
            float model[16];
            pelt_vec3 axis = v3_norm_or(v3(pelt__rng_range(&r, -1, 1), pelt__rng_range(&r, -1, 1),
                                           pelt__rng_range(&r, -1, 1)),
                                        v3(0, 1, 0));
            pelt__mat4_rotate(model, axis, pelt__rng_range(&r, -3.14f, 3.14f));
            model[12] = pelt__rng_range(&r, -5, 5);
            model[13] = pelt__rng_range(&r, -5, 5);
            model[14] = pelt__rng_range(&r, -5, 5);
            CHECK(pelt__strands_set_transform(s, model));
        }
        pelt__strands_step(s, dt, &f, time);
        time += dt;
        for (size_t i = 0; i < pelt__strands_count(s); i++) {
            /* The transform is rigid, so Eq. 3 can be read in mesh-local
             * coordinates with the mesh's own normal. */
            pelt_vec3 d = offset_of(s, i);
            float tip[3];
            pelt__strands_tip_world(s, i, tip);
            if (!(isfinite(d.x) && isfinite(d.y) && isfinite(d.z) && isfinite(tip[0]) &&
                  isfinite(tip[1]) && isfinite(tip[2]))) {
                nonfinite++;
                continue;
            }
            float len = v3_len(d), dn = v3_dot(d, normal_of(m, i));
            if (len > worst_len) worst_len = len;
            if (dn < worst_dn) worst_dn = dn;
            if (len > L0 * (1.0f + 1e-4f) || dn < -1e-5f * L0) violations++;
        }
    }
    CHECK(nonfinite == 0);
    CHECK(violations == 0);
    CHECK_NEAR(fmaxf(worst_len, L0), L0, 1e-4f * L0);
    CHECK_NEAR(fminf(worst_dn, 0.0f), 0.0f, 1e-5f * L0);
    pelt__strands_destroy(s);
    pelt_mesh_destroy(m);
}

static void strand_returns_to_rest_without_force_when_damped(void)
{
    pelt_mesh *m = torus(12, 8);
    pelt__strand_params p = fur_defaults(0.1f);
    pelt__strands *s = m ? strands_for(m, &p) : NULL;
    CHECK(s != NULL);
    if (!s) {
        pelt_mesh_destroy(m);
        return;
    }
    /* Blow the fur about first, so it starts far from rest... */
    pelt_forces f = pelt_forces_default();
    f.wind[0] = 40.0f;
    f.wind[2] = -25.0f;
    float t = 0.0f;
    for (int i = 0; i < 60; i++, t += 1.0f / 60.0f) pelt__strands_step(s, 1.0f / 60.0f, &f, t);
    float moved = 0.0f;
    for (size_t i = 0; i < pelt__strands_count(s); i++)
        moved = fmaxf(moved, v3_len(v3_sub(offset_of(s, i), v3_scale(normal_of(m, i), p.length))));
    CHECK(moved > 0.3f * p.length);
    /* ...then let it go: damping (ratio 0.25) settles it within a few seconds. */
    pelt_forces none = no_forces();
    for (int i = 0; i < 600; i++, t += 1.0f / 60.0f) pelt__strands_step(s, 1.0f / 60.0f, &none, t);
    float worst = 0.0f;
    for (size_t i = 0; i < pelt__strands_count(s); i++)
        worst = fmaxf(worst, v3_len(v3_sub(offset_of(s, i), v3_scale(normal_of(m, i), p.length))));
    CHECK_NEAR(worst, 0.0f, 1e-4f * p.length);
    pelt__strands_destroy(s);
    pelt_mesh_destroy(m);
}

static void strand_static_sag_equals_force_over_stiffness(void)
{
    /* Square with normal +y, a small downward pull: equilibrium
     * k (p0 - p) = m g, i.e. the tip sinks by g m / k along -n (inside
     * Eq. 3, so nothing clips it). */
    pelt_mesh *m = square(2);
    pelt__strand_params p = {.length = 0.1f, .spring_k = 200.0f, .mass = 2.0f, .damping = 10.0f};
    pelt__strands *s = m ? strands_for(m, &p) : NULL;
    CHECK(s != NULL);
    if (!s) {
        pelt_mesh_destroy(m);
        return;
    }
    pelt_forces f = no_forces();
    f.gravity[1] = -3.0f;
    for (int i = 0; i < 1200; i++) pelt__strands_step(s, 1.0f / 60.0f, &f, (float)i / 60.0f);
    float expected = 0.1f - 3.0f * 2.0f / 200.0f; /* 0.07 */
    for (size_t i = 0; i < pelt__strands_count(s); i++) {
        pelt_vec3 d = offset_of(s, i);
        CHECK_NEAR(d.y, expected, 1e-5);
        CHECK_NEAR(d.x, 0.0f, 1e-6);
        CHECK_NEAR(d.z, 0.0f, 1e-6);
    }
    pelt__strands_destroy(s);
    pelt_mesh_destroy(m);
}

/* Water's weight (docs/dynamics.md, Wet fur hangs): half the strands
 * carry their tip's mass again in water (load 1). Under a small pull along
 * -n the wet tips sink twice as far as the dry ones (k (p0 - p) = (1 +
 * load) m g); a steady wind bends both alike (its push and the spring are
 * both forces per mass), but the wet tips get there later; a load of 0
 * steps to the bit as no load. */
static void strand_water_weight_doubles_the_sag_and_slows_the_swing(void)
{
    pelt_mesh *m = square(2);
    pelt__strand_params p = {.length = 0.1f, .spring_k = 200.0f, .mass = 2.0f, .damping = 10.0f};
    pelt__strands *s = m ? strands_for(m, &p) : NULL, *plain = m ? strands_for(m, &p) : NULL;
    CHECK(s && plain);
    if (!s || !plain) {
        pelt__strands_destroy(s);
        pelt__strands_destroy(plain);
        pelt_mesh_destroy(m);
        return;
    }
    const size_t n = pelt__strands_count(s);
    float *load = pelt__strands_water_load(s);
    CHECK(load != NULL && pelt__strands_water_load(NULL) == NULL);
    for (size_t i = 0; i < n; i++) CHECK(load[i] == 0.0f); /* dry at creation */
    for (size_t i = 0; i < n; i += 2) load[i] = 1.0f;
    pelt_forces f = no_forces();
    f.gravity[1] = -3.0f;
    for (int i = 0; i < 1200; i++) {
        pelt__strands_step(s, 1.0f / 60.0f, &f, (float)i / 60.0f);
        pelt__strands_step(plain, 1.0f / 60.0f, &f, (float)i / 60.0f);
    }
    const float dry_sag = 3.0f * 2.0f / 200.0f; /* 0.03 */
    const float wet_sag = 0.1f - offset_of(s, 0).y;
    for (size_t i = 0; i < n; i++) {
        float sag = 0.1f - offset_of(s, i).y;
        CHECK_NEAR(sag, (i % 2 == 0 ? 2.0f : 1.0f) * dry_sag, 1e-5);
        if (i % 2 == 1) CHECK(memcmp(pelt__strands_tip_offsets(s) + 3 * i, pelt__strands_tip_offsets(plain) + 3 * i,
                                     3 * sizeof(float)) == 0);
    }
    /* Wind along +x from rest, no gravity: after 0.1 s the wet tips have
     * moved less; after 20 s they stand where the dry ones do. */
    pelt__strands_reset(s);
    f = no_forces();
    f.wind[0] = 1.5f;
    for (int i = 0; i < 6; i++) pelt__strands_step(s, 1.0f / 60.0f, &f, (float)i / 60.0f);
    float early_wet = offset_of(s, 0).x, early_dry = offset_of(s, 1).x;
    printf("  sag %.4f wet, %.4f dry; after 0.1 s of wind %.4f wet, %.4f dry", wet_sag, dry_sag, early_wet,
           early_dry);
    CHECK(early_dry > 0.0f && early_wet < 0.8f * early_dry);
    for (int i = 6; i < 1200; i++) pelt__strands_step(s, 1.0f / 60.0f, &f, (float)i / 60.0f);
    printf(", after 20 s %.4f and %.4f\n", offset_of(s, 0).x, offset_of(s, 1).x);
    CHECK_NEAR(offset_of(s, 0).x, offset_of(s, 1).x, 1e-5);
    pelt__strands_destroy(s);
    pelt__strands_destroy(plain);
    pelt_mesh_destroy(m);
}

/* The fur loads its strands from the wetness mask: on a square under
 * gravity (along -n), a vertex at wetness rho sinks by (1 + weight rho)
 * times the dry sag, a dry one as before; towelled dry, every tip rises
 * back to the dry sag. */
static void wet_fur_hangs_by_its_wetness(void)
{
    pelt_mesh *m = square(8);
    pelt_fur_desc d = {.length = L0_TEST, .wet.weight = 1.0f};
    pelt_fur *fur = NULL;
    CHECK(m && pelt_fur_create(m, &d, &fur, NULL) == PELT_OK);
    if (!fur) {
        pelt_mesh_destroy(m);
        return;
    }
    pelt_droplet drop = {{0.25f, 0.5f}, 0.3f, 1.0f};
    CHECK(pelt_fur_add_droplet(fur, &drop, NULL) == PELT_OK);
    pelt_forces f = pelt_forces_default();
    f.gust_strength = 0.0f;
    for (int i = 0; i < 600; i++) pelt_fur_step(fur, 1.0f / 60.0f, &f);
    const float dry_sag = 0.4f * L0_TEST; /* spring_k's default: m g / k = 0.4 L */
    const pelt__wetness *mask = pelt__water_mask(fur->water);
    size_t wet = 0, dry = 0;
    float worst = 0.0f;
    for (size_t i = 0; i < m->vertex_count; i++) {
        float rho = pelt__clump_texel(mask->texels, mask->width, mask->height, m->uvs + 2 * i)[3];
        float sag = L0_TEST - fur->tips[3 * i + 1];
        float err = fabsf(sag - (1.0f + rho) * dry_sag);
        worst = err > worst ? err : worst;
        wet += rho > 0.9f;
        dry += rho == 0.0f;
    }
    printf("  %zu soaked vertices, %zu dry; worst sag error %.2g of %.3g\n", wet, dry, worst, dry_sag);
    CHECK(wet > 4 && dry > 4 && worst < 1e-3f * L0_TEST);
    pelt_fur_clear_wetness(fur);
    for (int i = 0; i < 600; i++) pelt_fur_step(fur, 1.0f / 60.0f, &f);
    worst = 0.0f;
    for (size_t i = 0; i < m->vertex_count; i++) {
        float err = fabsf(L0_TEST - fur->tips[3 * i + 1] - dry_sag);
        worst = err > worst ? err : worst;
    }
    CHECK(worst < 1e-3f * L0_TEST);
    pelt_fur_destroy(fur);
    pelt_mesh_destroy(m);
}

static void strand_defaults_bend_under_gravity_and_lean_in_wind(void)
{
    /* A wall: the square turned so its normal is +x, the fur defaults. */
    pelt_mesh *m = square(1);
    pelt__strands *s = m ? strands_default(m) : NULL;
    CHECK(s != NULL);
    if (!s) {
        pelt_mesh_destroy(m);
        return;
    }
    float model[16];
    pelt__mat4_rotate(model, v3(0, 0, 1), -1.5707963f); /* +y to +x */
    CHECK(pelt__strands_set_transform(s, model));
    pelt__strands_reset(s);
    const float L0 = L0_TEST;
    pelt_forces f = pelt_forces_default();
    f.gust_strength = 0.0f;
    for (int i = 0; i < 300; i++) pelt__strands_step(s, 1.0f / 60.0f, &f, (float)i / 60.0f);
    float tip[3], root[3];
    pelt__strands_tip_world(s, 0, tip);
    pelt__strands_root_world(s, 0, root);
    pelt_vec3 d = v3_sub(v3_load(tip), v3_load(root));
    /* Visibly bent (sag of 0.2-0.6 L0) but still standing out from the wall. */
    CHECK(d.y < -0.2f * L0 && d.y > -0.6f * L0);
    CHECK(d.x > 0.7f * L0);

    /* A wind of 25 across the fur leans it by more than 30 degrees. */
    pelt__mat4_identity(model);
    CHECK(pelt__strands_set_transform(s, model));
    pelt__strands_reset(s);
    f = no_forces();
    f.wind[0] = 25.0f;
    for (int i = 0; i < 300; i++) pelt__strands_step(s, 1.0f / 60.0f, &f, (float)i / 60.0f);
    pelt_vec3 o = offset_of(s, 0);
    float angle = acosf(clampf(o.y / v3_len(o), -1.0f, 1.0f));
    CHECK(angle > 0.5236f);
    CHECK(o.y > 0.0f);
    pelt__strands_destroy(s);
    pelt_mesh_destroy(m);
}

static void strand_steady_wind_moves_every_tip_downwind(void)
{
    pelt_mesh *m = torus(24, 16);
    pelt__strands *s = m ? strands_default(m) : NULL;
    CHECK(s != NULL);
    if (!s) {
        pelt_mesh_destroy(m);
        return;
    }
    const float L0 = L0_TEST;
    pelt_forces f = no_forces();
    pelt_vec3 wind = v3(20.0f, 0.0f, 10.0f);
    v3_store(f.wind, wind);
    for (int i = 0; i < 180; i++) pelt__strands_step(s, 1.0f / 60.0f, &f, (float)i / 60.0f);
    pelt_vec3 w = v3_norm_or(wind, v3(1, 0, 0));
    size_t checked = 0, upwind = 0;
    for (size_t i = 0; i < pelt__strands_count(s); i++) {
        pelt_vec3 n = normal_of(m, i);
        /* Blocked by the hemisphere: wind straight along the rest strand. */
        if (v3_dot(n, w) > 0.999f) continue;
        checked++;
        float moved = v3_dot(v3_sub(offset_of(s, i), v3_scale(n, L0)), w);
        if (!(moved > 0.0f)) upwind++;
    }
    CHECK(checked > pelt__strands_count(s) * 9 / 10);
    CHECK(upwind == 0);
    pelt__strands_destroy(s);
    pelt_mesh_destroy(m);
}

/* A local blow (the viewer's hair dryer) moves the tips whose roots are
 * within its radius, downwind, and no other tip. */
static void strand_local_blow_moves_only_the_tips_within_its_radius(void)
{
    pelt_mesh *m = torus(24, 16);
    pelt__strands *s = m ? strands_default(m) : NULL;
    CHECK(s != NULL);
    if (!s) {
        pelt_mesh_destroy(m);
        return;
    }
    const float L0 = L0_TEST, radius = 0.5f;
    pelt_forces f = no_forces();
    pelt_vec3 blow = v3(0.0f, 0.0f, -40.0f), centre = v3(0.0f, 0.0f, 1.4f);
    v3_store(f.blow, blow);
    v3_store(f.blow_center, centre);
    f.blow_radius = radius;
    for (int i = 0; i < 60; i++) pelt__strands_step(s, 1.0f / 60.0f, &f, (float)i / 60.0f);
    size_t inside = 0, inside_moved = 0, outside_moved = 0;
    for (size_t i = 0; i < pelt__strands_count(s); i++) {
        pelt_vec3 n = normal_of(m, i), root = v3_load(m->positions + 3 * i);
        float moved = v3_len(v3_sub(offset_of(s, i), v3_scale(n, L0)));
        float d = v3_len(v3_sub(root, centre));
        if (d < 0.8f * radius) {
            inside++;
            /* blocked only where the blow runs straight along the strand */
            if (moved > 0.05f * L0 || v3_dot(n, v3(0, 0, -1)) > 0.99f) inside_moved++;
        } else if (d > radius && moved > 1e-6f) {
            outside_moved++;
        }
    }
    CHECK(inside > 10);
    CHECK(inside_moved == inside);
    CHECK(outside_moved == 0);
    pelt__strands_destroy(s);
    pelt_mesh_destroy(m);
}

static void strand_tips_lag_behind_translation(void)
{
    pelt_mesh *m = square(3);
    pelt__strands *s = m ? strands_default(m) : NULL;
    CHECK(s != NULL);
    if (!s) {
        pelt_mesh_destroy(m);
        return;
    }
    pelt_forces f = no_forces();
    float model[16];
    pelt__mat4_identity(model);
    /* The mesh slides along +x at 1 unit/s; roots follow, tips trail. */
    for (int i = 1; i <= 30; i++) {
        model[12] = (float)i / 60.0f;
        CHECK(pelt__strands_set_transform(s, model));
        pelt__strands_step(s, 1.0f / 60.0f, &f, (float)i / 60.0f);
    }
    for (size_t i = 0; i < pelt__strands_count(s); i++) {
        float tip[3], root[3];
        pelt__strands_tip_world(s, i, tip);
        pelt__strands_root_world(s, i, root);
        CHECK_NEAR(root[0], m->positions[3 * i] + 0.5f, 1e-5);
        CHECK(tip[0] - root[0] < -0.01f * L0_TEST);
        CHECK(offset_of(s, i).x < 0.0f); /* seen in mesh-local terms too */
    }
    pelt__strands_destroy(s);
    pelt_mesh_destroy(m);
}

static void strand_tips_lag_behind_turntable(void)
{
    pelt_mesh *m = torus(24, 16);
    pelt__strands *s = m ? strands_default(m) : NULL;
    CHECK(s != NULL);
    if (!s) {
        pelt_mesh_destroy(m);
        return;
    }
    pelt_forces f = no_forces();
    const float spin = 2.0f; /* rad/s about +y */
    float model[16];
    for (int i = 1; i <= 180; i++) {
        pelt__mat4_rotate(model, v3(0, 1, 0), spin * (float)i / 60.0f);
        CHECK(pelt__strands_set_transform(s, model));
        pelt__strands_step(s, 1.0f / 60.0f, &f, (float)i / 60.0f);
    }
    size_t checked = 0, ahead = 0;
    for (size_t i = 0; i < pelt__strands_count(s); i++) {
        float tip[3], root[3];
        pelt__strands_tip_world(s, i, tip);
        pelt__strands_root_world(s, i, root);
        pelt_vec3 r = v3_load(root);
        pelt_vec3 motion = v3_norm_or(v3_cross(v3(0, spin, 0), r), v3(1, 0, 0));
        pelt_vec3 n = pelt__mat4_apply(model, normal_of(m, i), 0.0f);
        /* Fur pointing backwards cannot trail further: the sphere stops it. */
        if (v3_dot(n, motion) < -0.9f) continue;
        checked++;
        pelt_vec3 rest = v3_mad(r, n, L0_TEST);
        if (!(v3_dot(v3_sub(v3_load(tip), rest), motion) < 0.0f)) ahead++;
    }
    CHECK(checked > pelt__strands_count(s) / 2);
    CHECK(ahead == 0);
    pelt__strands_destroy(s);
    pelt_mesh_destroy(m);
}

static void strand_coincident_seam_vertices_get_identical_tips(void)
{
    const unsigned M = 20, mm = 12;
    pelt_mesh *m = torus(M, mm);
    pelt__strands *s = m ? strands_default(m) : NULL;
    CHECK(s != NULL);
    if (!s) {
        pelt_mesh_destroy(m);
        return;
    }
    pelt_forces f = pelt_forces_default();
    f.wind[0] = 25.0f;
    f.wind[1] = 5.0f;
    f.gust_strength = 1.0f;
    float model[16];
    for (int i = 1; i <= 120; i++) {
        pelt__mat4_rotate(model, v3(0.3f, 1.0f, 0.1f), 0.05f * (float)i);
        model[12] = 0.01f * (float)i;
        pelt__strands_set_transform(s, model);
        pelt__strands_step(s, 1.0f / 60.0f + 0.001f * (float)(i % 7), &f, (float)i / 60.0f);
    }
    const float *o = pelt__strands_tip_offsets(s);
    const size_t row = mm + 1;
    size_t differ = 0;
    /* The torus repeats column 0 as column M and row 0 as row mm. */
    for (size_t j = 0; j <= mm; j++)
        if (memcmp(o + 3 * j, o + 3 * (M * row + j), 3 * sizeof(float)) != 0) differ++;
    for (size_t i = 0; i <= M; i++)
        if (memcmp(o + 3 * (i * row), o + 3 * (i * row + mm), 3 * sizeof(float)) != 0) differ++;
    CHECK(differ == 0);
    /* And the fur did move, so the equality is not that of resting tips. */
    CHECK(v3_len(v3_sub(offset_of(s, 0), v3_scale(normal_of(m, 0), L0_TEST))) >
          0.01f * L0_TEST);
    pelt__strands_destroy(s);
    pelt_mesh_destroy(m);
}

static void gust_is_deterministic_smooth_and_varies_in_space_and_time(void)
{
    pelt_forces f = pelt_forces_default();
    f.wind[0] = 10.0f;
    f.gust_strength = 0.5f;
    float p[3] = {0.3f, -0.2f, 0.7f}, a[3], b[3];
    pelt__gust(&f, 5, p, 2.0f, a);
    pelt__gust(&f, 5, p, 2.0f, b);
    CHECK(memcmp(a, b, sizeof a) == 0);
    /* Along the wind: at most strength * |wind|; across: at most half that
     * per axis. */
    CHECK(fabsf(a[0]) <= 5.0f + 1e-4f);
    CHECK(sqrtf(a[1] * a[1] + a[2] * a[2]) <= 0.5f * 5.0f * 1.4143f);
    /* Smooth: a step of 1e-4 gust scales changes it by little. */
    float q[3] = {p[0] + 1e-4f * f.gust_scale, p[1], p[2]};
    pelt__gust(&f, 5, q, 2.0f, b);
    CHECK(fabsf(a[0] - b[0]) + fabsf(a[1] - b[1]) + fabsf(a[2] - b[2]) < 0.01f);
    pelt__gust(&f, 5, p, 2.0f + 1e-4f, b);
    CHECK(fabsf(a[0] - b[0]) + fabsf(a[1] - b[1]) + fabsf(a[2] - b[2]) < 0.01f);
    /* Not in lockstep: over 32 places a few gust scales apart the gust
     * differs, and so it does over time and with the seed. */
    float lo = 1e30f, hi = -1e30f;
    for (int i = 0; i < 32; i++) {
        float r[3] = {p[0] + 2.7f * f.gust_scale * (float)i, p[1], p[2]};
        pelt__gust(&f, 5, r, 2.0f, b);
        lo = fminf(lo, b[0]);
        hi = fmaxf(hi, b[0]);
    }
    CHECK(hi - lo > 1.0f);
    lo = 1e30f, hi = -1e30f;
    for (int i = 0; i < 32; i++) {
        pelt__gust(&f, 5, p, 2.0f + 1.3f * (float)i / f.gust_frequency, b);
        lo = fminf(lo, b[0]);
        hi = fmaxf(hi, b[0]);
    }
    CHECK(hi - lo > 1.0f);
    /* No wind, no gust. */
    f.wind[0] = 0.0f;
    pelt__gust(&f, 5, p, 2.0f, b);
    CHECK(b[0] == 0.0f && b[1] == 0.0f && b[2] == 0.0f);
}

static void strand_cached_gusts_match_fresh_ones(void)
{
    /* A still mesh reuses its gust noise; re-setting the same transform
     * every step forces fresh noise. Both must give the same tips, over
     * several gust time cells. */
    pelt_mesh *m = torus(16, 10);
    pelt__strands *a = m ? strands_default(m) : NULL;
    pelt__strands *b = m ? strands_default(m) : NULL;
    CHECK(a != NULL && b != NULL);
    if (a && b) {
        pelt_forces f = pelt_forces_default();
        f.wind[2] = 30.0f;
        f.gust_strength = 1.0f;
        float identity[16];
        pelt__mat4_identity(identity);
        for (int i = 0; i < 240; i++) {
            CHECK(pelt__strands_set_transform(b, identity));
            pelt__strands_step(a, 1.0f / 60.0f, &f, (float)i / 60.0f);
            pelt__strands_step(b, 1.0f / 60.0f, &f, (float)i / 60.0f);
        }
        size_t n = pelt__strands_count(a);
        CHECK(memcmp(pelt__strands_tip_offsets(a), pelt__strands_tip_offsets(b), 3 * n * sizeof(float)) == 0);
        /* The gusts did something: without them the tips differ. */
        pelt__strands *c = strands_default(m);
        if (c) {
            f.gust_strength = 0.0f;
            for (int i = 0; i < 240; i++) pelt__strands_step(c, 1.0f / 60.0f, &f, (float)i / 60.0f);
            CHECK(memcmp(pelt__strands_tip_offsets(a), pelt__strands_tip_offsets(c), 3 * n * sizeof(float)) != 0);
            pelt__strands_destroy(c);
        }
    }
    pelt__strands_destroy(a);
    pelt__strands_destroy(b);
    pelt_mesh_destroy(m);
}

static void strand_bad_input_is_rejected_or_ignored(void)
{
    pelt__strands *s = NULL;
    pelt_error err = {0};
    CHECK(pelt__strands_create(NULL, NULL, NULL, &s, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(s == NULL);
    CHECK(strstr(err.message, "mesh") != NULL);
    pelt_mesh *m = square(1);
    CHECK(pelt__strands_create(m, NULL, NULL, NULL, NULL) == PELT_ERR_INVALID_ARGUMENT);
    s = m ? strands_default(m) : NULL;
    CHECK(s != NULL);
    if (!s) {
        pelt_mesh_destroy(m);
        return;
    }
    float bad[16];
    pelt__mat4_identity(bad);
    bad[5] = NAN;
    CHECK(!pelt__strands_set_transform(s, bad));
    pelt__mat4_identity(bad);
    bad[0] = 0.0f; /* singular */
    CHECK(!pelt__strands_set_transform(s, bad));
    pelt_forces f = pelt_forces_default();
    f.gravity[0] = NAN;
    f.wind[1] = INFINITY;
    f.gust_scale = -1.0f;
    pelt__strands_step(s, NAN, &f, 0.0f);
    pelt__strands_step(s, -1.0f, &f, 0.0f);
    pelt__strands_step(s, INFINITY, &f, NAN);
    pelt__strands_step(s, 1e30f, NULL, INFINITY);
    for (size_t i = 0; i < pelt__strands_count(s); i++) {
        pelt_vec3 d = offset_of(s, i);
        CHECK(isfinite(d.x) && isfinite(d.y) && isfinite(d.z));
        CHECK(v3_len(d) <= L0_TEST * 1.0001f);
        CHECK(d.y >= 0.0f);
    }
    pelt__strands_destroy(s);
    pelt__strands_destroy(NULL);
    pelt_mesh_destroy(m);
}

static void strand_params_are_checked_not_defaulted(void)
{
    /* The strands take resolved parameters: a zero, negative or not-finite
     * one is an error, not a default (the fur desc has the defaults). */
    pelt_mesh *m = square(1);
    CHECK(m != NULL);
    if (!m) return;
    pelt__strands *s = NULL;
    pelt_error err = {0};
    CHECK(pelt__strands_create(m, NULL, NULL, &s, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(s == NULL && strstr(err.message, "params") != NULL);
    const pelt__strand_params good = fur_defaults(L0_TEST);
    pelt__strand_params bad[6] = {good, good, good, good, good, good};
    bad[0].length = 0.0f;
    bad[1].spring_k = NAN;
    bad[2].mass = -2.0f;
    bad[3].damping = -1.0f;
    bad[4].length = INFINITY;
    memset(&bad[5], 0, sizeof bad[5]);
    for (int i = 0; i < 6; i++) {
        CHECK(pelt__strands_create(m, &bad[i], NULL, &s, &err) == PELT_ERR_INVALID_ARGUMENT);
        CHECK(s == NULL);
    }
    /* No damping at all is allowed; the params come back as given. */
    pelt__strand_params undamped = good;
    undamped.damping = 0.0f;
    undamped.seed = 9;
    CHECK(pelt__strands_create(m, &undamped, NULL, &s, &err) == PELT_OK);
    if (s) {
        pelt__strand_params r = pelt__strands_params(s);
        CHECK(memcmp(&r, &undamped, sizeof r) == 0);
    }
    pelt__strands_destroy(s);
    pelt_mesh_destroy(m);
}

static void strand_rest_offsets_are_length_times_normal_in_mesh_space(void)
{
    /* Even under a scaled, rotated transform the uploaded offsets are
     * mesh-local: L0 n at rest. */
    pelt_mesh *m = torus(10, 6);
    pelt__strand_params p = fur_defaults(0.05f);
    pelt__strands *s = m ? strands_for(m, &p) : NULL;
    CHECK(s != NULL);
    if (!s) {
        pelt_mesh_destroy(m);
        return;
    }
    float model[16];
    pelt__mat4_rotate(model, v3(1, 0, 0), 0.7f);
    for (int i = 0; i < 12; i++) model[i] *= 2.0f; /* uniform scale 2 */
    CHECK(pelt__strands_set_transform(s, model));
    pelt__strands_reset(s);
    for (size_t i = 0; i < pelt__strands_count(s); i++) {
        pelt_vec3 d = offset_of(s, i), e = v3_scale(normal_of(m, i), p.length);
        CHECK(v3_len(v3_sub(d, e)) < 1e-6f);
    }
    pelt__strands_destroy(s);
    pelt_mesh_destroy(m);
}

static void strand_threads_step_the_same_bits_as_one(void)
{
    /* The strands are stepped in parts on several threads; each strand's
     * arithmetic is the same, so the tips are the same to the bit: with the
     * mesh moving (roots jump), gusts refreshed and a local blow. */
    pelt_mesh *m = torus(97, 41); /* a vertex count that is no multiple of a block */
    pelt__strand_params p = fur_defaults(0.1f);
    pelt__strands *one = m ? strands_for(m, &p) : NULL, *many = m ? strands_for(m, &p) : NULL;
    pelt__workers *w = NULL;
    CHECK(pelt__workers_create(3, NULL, NULL, &w, NULL) == PELT_OK);
    CHECK(one && many && w);
    if (!one || !many || !w) goto done;
    CHECK(pelt__workers_threads(w) == 3);
    pelt__strands_set_workers(many, w);
    pelt_forces f = pelt_forces_default();
    f.wind[0] = 6.0f;
    f.blow[1] = 30.0f;
    f.blow_radius = 0.5f;
    float model[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    for (int i = 0; i < 40; i++) {
        model[12] = 0.3f * sinf(0.2f * (float)i);
        CHECK(pelt__strands_set_transform(one, model) && pelt__strands_set_transform(many, model));
        pelt__strands_step(one, 1.0f / 30.0f, &f, (float)i / 30.0f);
        pelt__strands_step(many, 1.0f / 30.0f, &f, (float)i / 30.0f);
    }
    size_t n = pelt__strands_count(one);
    CHECK(n % 32 != 0);
    CHECK(memcmp(pelt__strands_tip_offsets(one), pelt__strands_tip_offsets(many), 3 * n * sizeof(float)) == 0);
    float moved = 0.0f;
    for (size_t i = 0; i < n; i++)
        moved = fmaxf(moved, v3_len(v3_sub(offset_of(many, i), v3_scale(normal_of(m, i), p.length))));
    CHECK(moved > 0.1f * p.length); /* the forces did move the tips */
done:
    pelt__strands_destroy(one);
    pelt__strands_destroy(many);
    pelt__workers_destroy(w);
    pelt_mesh_destroy(m);
}

int main(void)
{
    RUN(strand_params_are_checked_not_defaulted);
    RUN(strand_rest_offsets_are_length_times_normal_in_mesh_space);
    RUN(strand_static_sag_equals_force_over_stiffness);
    RUN(strand_water_weight_doubles_the_sag_and_slows_the_swing);
    RUN(wet_fur_hangs_by_its_wetness);
    RUN(strand_defaults_bend_under_gravity_and_lean_in_wind);
    RUN(strand_returns_to_rest_without_force_when_damped);
    RUN(strand_steady_wind_moves_every_tip_downwind);
    RUN(strand_local_blow_moves_only_the_tips_within_its_radius);
    RUN(strand_tips_lag_behind_translation);
    RUN(strand_tips_lag_behind_turntable);
    RUN(strand_coincident_seam_vertices_get_identical_tips);
    RUN(gust_is_deterministic_smooth_and_varies_in_space_and_time);
    RUN(strand_cached_gusts_match_fresh_ones);
    RUN(strand_bad_input_is_rejected_or_ignored);
    RUN(strand_constraints_hold_after_100000_random_steps);
    RUN(strand_threads_step_the_same_bits_as_one);
    return check_summary();
}
