/* Fur shape references (core/fur/fur_shape.c): Silva et al. Eq. 1 (Bezier bend),
 * Eq. 4 (curl) and the tangent of the displaced curve. */
#include "support/check.h"

#include "core/fur/fur_shape.h"
#include "pelt/params.h"

#include <math.h>
#include <string.h>

#define TWO_PI 6.28318530717958647692f

static float dist(pelt_vec3 a, pelt_vec3 b) { return v3_len(v3_sub(a, b)); }

static void fur_bend_at_rest_spaces_layers_evenly(void)
{
    /* tip = L0 n: 2h(1-h) L0/2 + h^2 L0 = h L0, along n, for every h. */
    pelt_vec3 n = v3_norm_or(v3(0.3f, 0.8f, -0.5f), v3(0, 1, 0));
    const float L0 = 0.07f;
    for (int layer = 0; layer <= 32; layer++) {
        float h = (float)layer / 32.0f;
        pelt_vec3 b = pelt__fur_bend(n, L0, v3_scale(n, L0), h);
        CHECK(dist(b, v3_scale(n, h * L0)) < 1e-7f);
    }
}

static void fur_bend_hand_computed_point(void)
{
    /* n = +y, L0 = 2, tip = (1, 1, 0), h = 0.5:
     * 2 * 0.5 * 0.5 * (0, 1, 0) + 0.25 * (1, 1, 0) = (0.25, 0.75, 0). */
    pelt_vec3 b = pelt__fur_bend(v3(0, 1, 0), 2.0f, v3(1, 1, 0), 0.5f);
    CHECK_NEAR(b.x, 0.25, 1e-7);
    CHECK_NEAR(b.y, 0.75, 1e-7);
    CHECK_NEAR(b.z, 0.0, 1e-7);
}

static void fur_bend_starts_at_root_and_ends_at_tip(void)
{
    pelt_vec3 n = v3(0, 0, 1), tip = v3(0.02f, -0.01f, 0.05f);
    pelt_vec3 a = pelt__fur_bend(n, 0.06f, tip, 0.0f), b = pelt__fur_bend(n, 0.06f, tip, 1.0f);
    CHECK(v3_len(a) == 0.0f);
    CHECK(dist(b, tip) < 1e-8f);
    /* And it leaves the skin along n: dB/dh(0) = L0 n. */
    pelt_vec3 t = pelt__fur_tangent(n, 0.06f, tip, v3(1, 0, 0), v3(0, 1, 0), 0.0f, 0.0f, 0.0f, 0.0f);
    CHECK(dist(t, n) < 1e-6f);
}

static void fur_curl_radius_is_K_h_times_one_minus_rho(void)
{
    /* Silva Eq. 4: |phi(h)| = (1 - rho) K h and its angle in (u, v) is omega h. */
    pelt_vec3 u = v3(1, 0, 0), v = v3(0, 0, -1);
    const float K = 0.03f, omega = 9.0f;
    const float rhos[] = {0.0f, 0.25f, 0.8f};
    for (int r = 0; r < 3; r++) {
        for (int i = 1; i <= 16; i++) {
            float h = (float)i / 16.0f;
            pelt_vec3 phi = pelt__fur_curl(u, v, omega, K, rhos[r], h);
            CHECK_NEAR(v3_len(phi), (1.0f - rhos[r]) * K * h, 1e-7);
            float angle = atan2f(v3_dot(phi, v), v3_dot(phi, u));
            float expected = remainderf(omega * h, TWO_PI);
            CHECK_NEAR(remainderf(angle - expected, TWO_PI), 0.0, 1e-4);
            CHECK_NEAR(phi.y, 0.0, 1e-9); /* stays in the tangent plane */
        }
    }
}

static void fur_curl_vanishes_when_wet_or_at_root(void)
{
    pelt_vec3 u = v3(1, 0, 0), v = v3(0, 1, 0);
    CHECK(v3_len(pelt__fur_curl(u, v, 20.0f, 0.05f, 1.0f, 0.7f)) == 0.0f);
    CHECK(v3_len(pelt__fur_curl(u, v, 20.0f, 0.05f, 0.0f, 0.0f)) == 0.0f);
    CHECK(v3_len(pelt__fur_curl(u, v, 20.0f, 0.0f, 0.0f, 0.7f)) == 0.0f);
}

/* Central difference of beta + phi, normalised. */
static pelt_vec3 numeric_tangent(pelt_vec3 n, float L0, pelt_vec3 tip, pelt_vec3 u, pelt_vec3 v,
                                 float omega, float K, float rho, float h)
{
    const double e = 1e-3;
    double p[2][3];
    for (int k = 0; k < 2; k++) {
        /* Evaluate in double by hand to keep the difference accurate. */
        double hh = h + (k ? e : -e);
        double a = 2.0 * hh * (1.0 - hh) * 0.5 * L0, b = hh * hh;
        double al = (1.0 - rho) * K * hh, c = cos(omega * hh), s = sin(omega * hh);
        p[k][0] = n.x * a + tip.x * b + al * (c * u.x + s * v.x);
        p[k][1] = n.y * a + tip.y * b + al * (c * u.y + s * v.y);
        p[k][2] = n.z * a + tip.z * b + al * (c * u.z + s * v.z);
    }
    pelt_vec3 d = v3((float)((p[1][0] - p[0][0]) / (2 * e)), (float)((p[1][1] - p[0][1]) / (2 * e)),
                     (float)((p[1][2] - p[0][2]) / (2 * e)));
    return v3_norm_or(d, n);
}

static void fur_tangent_equals_finite_difference_of_displaced_curve(void)
{
    pelt_vec3 n = v3(0, 1, 0), u = v3(1, 0, 0), v = v3(0, 0, 1);
    const pelt_vec3 tips[] = {v3(0, 0.1f, 0), v3(0.06f, 0.07f, -0.02f), v3(-0.09f, 0.01f, 0.03f)};
    const float omegas[] = {0.0f, 6.0f, 37.0f};
    const float Ks[] = {0.0f, 0.01f, 0.04f};
    float worst = 0.0f;
    for (int t = 0; t < 3; t++)
        for (int o = 0; o < 3; o++)
            for (int k = 0; k < 3; k++)
                for (int i = 1; i < 10; i++) {
                    float h = (float)i / 10.0f;
                    pelt_vec3 a = pelt__fur_tangent(n, 0.1f, tips[t], u, v, omegas[o], Ks[k], 0.3f, h);
                    pelt_vec3 b = numeric_tangent(n, 0.1f, tips[t], u, v, omegas[o], Ks[k], 0.3f, h);
                    CHECK_NEAR(v3_len(a), 1.0, 1e-5);
                    worst = fmaxf(worst, dist(a, b));
                }
    CHECK_NEAR(worst, 0.0, 2e-3);
}

static void fur_tangent_falls_back_to_normal_when_derivative_vanishes(void)
{
    pelt_vec3 n = v3(0, 0, -1);
    pelt_vec3 t = pelt__fur_tangent(n, 0.0f, v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0), 3.0f, 0.0f, 0.0f, 0.5f);
    CHECK(t.x == n.x && t.y == n.y && t.z == n.z);
}

static void fur_tangent_of_straight_rest_fur_is_normal(void)
{
    pelt_vec3 n = v3_norm_or(v3(1, 1, 0), v3(0, 1, 0));
    for (int i = 0; i <= 8; i++) {
        float h = (float)i / 8.0f;
        pelt_vec3 t = pelt__fur_tangent(n, 0.05f, v3_scale(n, 0.05f), v3(0, 0, 1), v3(1, -1, 0), 7.0f, 0.0f,
                                        0.0f, h);
        CHECK(dist(t, n) < 1e-6f);
    }
}

static void curl_presets_cover_fig7_and_differ(void)
{
    const char *names[] = {"straight", "wavy", "few-large-curls", "many-small-curls"};
    float om[4], rad[4];
    for (int i = 0; i < 4; i++) {
        CHECK(pelt__curl_preset(names[i], &om[i], &rad[i]));
        const char *listed = pelt_curl_preset_names[i];
        CHECK(listed != NULL && strcmp(listed, names[i]) == 0);
        CHECK(pelt_curl_preset_index(names[i]) == i);
        CHECK(rad[i] >= 0.0f && rad[i] < 1.0f);
    }
    CHECK(pelt_curl_preset_names[4] == NULL);
    CHECK(pelt_curl_preset_index("curly") == -1 && pelt_curl_preset_index(NULL) == -1);
    CHECK(rad[0] == 0.0f);                     /* straight: no curl */
    CHECK(rad[1] < rad[2] && om[1] < om[2]);   /* wavy: slow and small */
    CHECK(rad[2] > rad[3] && om[2] < om[3]);   /* few large vs many small */
    CHECK(om[3] > 2.0f * TWO_PI);              /* "many": more than two turns */
    /* The short aliases give the same looks. */
    float ao, ar;
    CHECK(pelt__curl_preset("large_curls", &ao, &ar) && ao == om[2] && ar == rad[2]);
    CHECK(pelt__curl_preset("small_curls", &ao, &ar) && ao == om[3] && ar == rad[3]);
    float keep_o = 123.0f, keep_r = 456.0f;
    CHECK(!pelt__curl_preset("curly", &keep_o, &keep_r));
    CHECK(!pelt__curl_preset(NULL, &keep_o, &keep_r));
    CHECK(keep_o == 123.0f && keep_r == 456.0f);
}

/* The ringlet's tangent lit from dots (what the shells' fragment stage
 * gets from the vertex stage) is the tangent itself dotted with the two
 * directions, on frames that are neither orthogonal nor the same; so is
 * the hair's tangent bent by the texture's own curl. */
static void ringlet_dots_are_the_tangent_dotted(void)
{
    double worst = 0.0;
    int turned = 0;
    for (int i = 0; i < 2000; i++) {
        float x = (float)i;
        pelt_vec3 t = v3_norm_or(v3(sinf(x), 1.0f + 0.3f * cosf(1.3f * x), 0.4f * sinf(0.7f * x)), v3(0, 1, 0));
        pelt_vec3 u = v3_norm_or(v3(1.0f, 0.2f * sinf(2.1f * x), 0.5f * cosf(x)), v3(1, 0, 0));
        pelt_vec3 v = v3_norm_or(v3(0.3f * cosf(0.9f * x), 0.25f * sinf(x), 1.0f), v3(0, 0, 1));
        pelt_vec3 a = v3_norm_or(v3(0.5f, 1.0f, 0.8f * sinf(0.3f * x)), v3(0, 1, 0));
        pelt_vec3 b = v3_norm_or(v3(cosf(0.2f * x), -0.4f, sinf(0.2f * x)), v3(1, 0, 0));
        float k = 0.05f + 0.5f * (float)(i % 7) / 6.0f, omega = 3.0f + (float)(i % 11), h = (float)(i % 13) / 12.0f;
        float psi = 6.2831853f * (float)(i % 17) / 17.0f;
        pelt_vec3 T = pelt__ringlet_tangent(t, u, v, k, omega, h, psi);
        const float ta[3] = {v3_dot(t, a), v3_dot(u, a), v3_dot(v, a)};
        const float tb[3] = {v3_dot(t, b), v3_dot(u, b), v3_dot(v, b)};
        const float gram[3] = {v3_dot(t, u), v3_dot(t, v), v3_dot(u, v)};
        float d[2], e[2], none[2] = {0.0f, 0.0f};
        pelt__ringlet_dots(ta, tb, gram, k, omega, h, psi, none, d);
        worst = fmax(worst, fmax(fabs(d[0] - v3_dot(T, a)), fabs(d[1] - v3_dot(T, b))));
        turned += v3_dot(T, t) < 0.95f;
        /* The texture's own curl alone: t plus its slope along u and v. */
        float slope[2];
        pelt__strand_curl_slope(0.02f * (float)(i % 5), 6.2831853f * (float)(1 + i % 3), i % 2 == 0, h, psi, slope);
        pelt_vec3 S = v3_norm_or(v3_add(t, v3_add(v3_scale(u, slope[0]), v3_scale(v, slope[1]))), t);
        pelt__ringlet_dots(ta, tb, gram, 0.0f, omega, h, psi, slope, e);
        worst = fmax(worst, fmax(fabs(e[0] - v3_dot(S, a)), fabs(e[1] - v3_dot(S, b))));
    }
    printf("  %d of 2000 tangents turned by their curl; worst |dots - tangent . direction| = %.3g\n", turned, worst);
    CHECK(turned > 500);
    CHECK(worst < 1e-5);
}

static void wet_fur_lies_further_along_its_comb(void)
{
    /* Dry fur keeps its comb exactly; water raises the comb's angle by
     * lie * rho, growing with the wetness, up to 75 degrees. */
    const float deg = 3.14159265f / 180.0f, t20 = tanf(20.0f * deg);
    CHECK(pelt__fur_wet_slant(t20, 40.0f * deg, 0.0f) == t20);
    CHECK(pelt__fur_wet_slant(t20, 0.0f, 1.0f) == t20);
    CHECK_NEAR(pelt__fur_wet_slant(0.0f, 40.0f * deg, 1.0f), tanf(40.0f * deg), 1e-5);
    CHECK_NEAR(pelt__fur_wet_slant(t20, 40.0f * deg, 0.5f), tanf(40.0f * deg), 1e-5);
    CHECK_NEAR(pelt__fur_wet_slant(tanf(50.0f * deg), 40.0f * deg, 1.0f), tanf(75.0f * deg), 1e-4);
    float last = 0.0f;
    for (int i = 0; i <= 10; i++) {
        float s = pelt__fur_wet_slant(0.0f, 60.0f * deg, 0.1f * (float)i);
        CHECK(s >= last);
        last = s;
    }
    CHECK(last > 1.7f); /* soaked: 60 degrees */
}

int main(void)
{
    RUN(fur_bend_at_rest_spaces_layers_evenly);
    RUN(fur_bend_hand_computed_point);
    RUN(fur_bend_starts_at_root_and_ends_at_tip);
    RUN(fur_curl_radius_is_K_h_times_one_minus_rho);
    RUN(fur_curl_vanishes_when_wet_or_at_root);
    RUN(fur_tangent_equals_finite_difference_of_displaced_curve);
    RUN(fur_tangent_falls_back_to_normal_when_derivative_vanishes);
    RUN(fur_tangent_of_straight_rest_fur_is_normal);
    RUN(curl_presets_cover_fig7_and_differ);
    RUN(ringlet_dots_are_the_tangent_dotted);
    RUN(wet_fur_lies_further_along_its_comb);
    return check_summary();
}
