/* C references of the shading (Silva et al. Eq. 6), hand-computed cases. */
#include "support/check.h"

#include "core/fur/shading.h"

static void kajiya_kay_diffuse_is_the_sine_of_tangent_and_light(void)
{
    float d, s;
    pelt__kajiya_kay(v3(0, 1, 0), v3(1, 0, 0), v3(0, 0, -1), 10.0f, &d, &s);
    CHECK_NEAR(d, 1.0, 1e-6); /* hair across the light: fully lit */
    pelt__kajiya_kay(v3(0, 1, 0), v3(0, 1, 0), v3(0, 0, -1), 10.0f, &d, &s);
    CHECK_NEAR(d, 0.0, 1e-6); /* hair along the light */
    const float c = 0.5f, sn = sqrtf(0.75f);
    pelt__kajiya_kay(v3(0, 1, 0), v3(sn, c, 0), v3(0, 0, -1), 10.0f, &d, &s);
    CHECK_NEAR(d, sn, 1e-6);
}

/* The highlight peaks on the cone of mirror directions: light arriving
 * along -L leaves at the same angle to T, so with E the direction from the
 * eye to the point the peak is at T.E = T.L (Eq. 6 is cos(theta_L -
 * theta_E)). */
static void kajiya_kay_specular_peaks_on_the_mirror_cone(void)
{
    float d, s;
    pelt_vec3 t = v3(0, 1, 0), l = v3(0.8f, 0.6f, 0); /* T.L = 0.6, sin 0.8 */
    pelt__kajiya_kay(t, l, v3(0, 0.6f, 0.8f), 20.0f, &d, &s); /* on the cone */
    CHECK_NEAR(s, 1.0, 1e-5);
    pelt__kajiya_kay(t, l, v3(0, -0.6f, 0.8f), 20.0f, &d, &s); /* -0.36 + 0.64 */
    CHECK_NEAR(s, powf(0.28f, 20.0f), 1e-9);
    pelt__kajiya_kay(t, l, v3(0, 1, 0), 20.0f, &d, &s); /* along the hair: 0.6 + 0 */
    CHECK_NEAR(s, powf(0.6f, 20.0f), 1e-7);
    pelt__kajiya_kay(t, l, v3(0, -1, 0), 20.0f, &d, &s); /* -0.6 clamps to 0 */
    CHECK_NEAR(s, 0.0, 0.0);
}

static void shadow_factor_darkens_the_roots(void)
{
    CHECK_NEAR(pelt__shadow_factor(2.0f, 0.0f), 0.5, 1e-7);
    CHECK_NEAR(pelt__shadow_factor(2.0f, 1.0f), 1.0, 1e-7);
    CHECK_NEAR(pelt__shadow_factor(1.0f, 0.25f), 0.25, 1e-7);
    CHECK_NEAR(pelt__shadow_factor(4.0f, 0.5f), 3.5 / 4.0, 1e-7);
}

/* Specular of wet fur at eye angle `a` (radians) off the mirror cone:
 * T = +Y, L at 53 degrees from T, E swept in the plane through T. */
static float wet_specular(float rho, float a)
{
    float p, gain, d, s;
    pelt__wet_shine(rho, 20.0f, 4.0f, 2.0f, &p, &gain);
    pelt_vec3 t = v3(0, 1, 0), l = v3(0.8f, 0.6f, 0);
    float th = acosf(0.6f) + a; /* the mirror cone is at T.E = T.L */
    pelt__kajiya_kay(t, l, v3(0, cosf(th), sinf(th)), p, &d, &s);
    return gain * s;
}

/* Wet shine: as the wetness rises the highlight's peak rises and its lobe
 * narrows (the angle at which it falls to half its peak), and rho outside
 * [0, 1] is clamped. */
static void wet_highlight_grows_sharper_and_stronger(void)
{
    float last_peak = 0.0f, last_width = 10.0f;
    for (int k = 0; k <= 4; k++) {
        float rho = 0.25f * (float)k;
        float peak = wet_specular(rho, 0.0f), width = 0.0f;
        while (wet_specular(rho, width) > 0.5f * peak && width < 3.0f) width += 1e-4f;
        printf("  rho %.2f: peak %.3f, half width %.2f degrees\n", (double)rho, (double)peak,
               (double)(width * 180.0f / 3.14159265f));
        CHECK(peak > last_peak);
        CHECK(width < last_width);
        last_peak = peak, last_width = width;
    }
    CHECK_NEAR(wet_specular(0.0f, 0.0f), 1.0, 1e-5);  /* dry: Kajiya-Kay as it was */
    CHECK_NEAR(wet_specular(1.0f, 0.0f), 2.0, 1e-5);  /* fully wet: the gloss */
    float p, gain;
    pelt__wet_shine(3.0f, 20.0f, 4.0f, 2.0f, &p, &gain);
    CHECK_NEAR(p, 80.0, 1e-4);
    CHECK_NEAR(gain, 2.0, 1e-6);
    pelt__wet_shine(-1.0f, 20.0f, 4.0f, 2.0f, &p, &gain);
    CHECK_NEAR(p, 20.0, 1e-6);
    CHECK_NEAR(gain, 1.0, 1e-6);
}

/* Kenwright's shadow drawn whole face-on, not at all from the side, more
 * the more the eye faces the surface, from either side of it. */
static void inter_shadow_fades_from_the_side(void)
{
    CHECK(pelt__inter_shadow_view_fade(1.0f) == 1.0f);
    CHECK(pelt__inter_shadow_view_fade(-PELT__INTER_SHADOW_FACE_ON) == 1.0f);
    CHECK(pelt__inter_shadow_view_fade(0.0f) == 0.0f);
    CHECK(pelt__inter_shadow_view_fade(PELT__INTER_SHADOW_SIDE_ON) == 0.0f);
    float prev = -1.0f;
    for (int i = 0; i <= 20; i++) {
        float f = pelt__inter_shadow_view_fade(0.05f * (float)i);
        CHECK(f >= prev && f == pelt__inter_shadow_view_fade(-0.05f * (float)i));
        prev = f;
    }
    float mid = 0.5f * (PELT__INTER_SHADOW_SIDE_ON + PELT__INTER_SHADOW_FACE_ON);
    CHECK_NEAR(pelt__inter_shadow_view_fade(mid), 0.5f, 1e-6);
}

static void srgb_round_trips_every_byte(void)
{
    double worst = 0.0;
    for (int i = 0; i < 256; i++) {
        float c = (float)i / 255.0f;
        worst = fmax(worst, fabs(pelt__srgb_encode(pelt__srgb_decode(c)) - c));
        if (i > 0) CHECK(pelt__srgb_decode(c) > pelt__srgb_decode((float)(i - 1) / 255.0f));
    }
    CHECK(worst < 0.3 / 255.0); /* the encoding is Taylor's fit */
    CHECK(fabsf(pelt__srgb_decode(0.5f) - 0.21404f) < 1e-4f); /* IEC 61966-2-1 */
    /* The fits against the power laws they stand for. */
    double enc = 0.0, shade = 0.0;
    for (int i = 0; i <= 10000; i++) {
        float l = (float)i / 10000.0f;
        float exact = l <= 0.0031308f ? 12.92f * l : 1.055f * powf(l, 1.0f / 2.4f) - 0.055f;
        enc = fmax(enc, fabs(pelt__srgb_encode(l) - exact));
        shade = fmax(shade, fabs(pelt__shade_decode(l) - pelt__srgb_decode(l)));
    }
    printf("  encoding within %.3f / 255 of the power, shade within %.4f of the decoding\n", 255.0 * enc, shade);
    CHECK(enc < 0.26 / 255.0);
    CHECK(shade < 0.002);
    CHECK(pelt__srgb_encode(-1.0f) == 0.0f);
    CHECK_NEAR(pelt__srgb_encode(2.0f), 1.0, 1e-6);
}

static void tone_curves_are_monotone_and_start_at_black(void)
{
    for (int tone = 0; tone < 2; tone++) {
        float prev = pelt__tone(0.0f, 1.0f, tone);
        CHECK(prev >= 0.0f && prev < 1e-6f);
        for (int i = 1; i <= 4000; i++) {
            float x = (float)i * 0.005f, y = pelt__tone(x, 1.0f, tone);
            CHECK(y >= prev && y <= 1.0f);
            prev = y;
        }
    }
    /* The filmic curve keeps rising where clamping has long clipped. */
    CHECK(pelt__tone(3.0f, 1.0f, 0) < pelt__tone(4.0f, 1.0f, 0));
    CHECK(pelt__tone(3.0f, 1.0f, 1) == 1.0f);
    /* Exposure multiplies first. */
    CHECK(fabsf(pelt__tone(0.2f, 2.0f, 0) - pelt__tone(0.4f, 1.0f, 0)) < 1e-6f);
}

/* The display mapping's one fit per curve against the curve then the exact
 * sRGB power, over eight decades of exposed light: within 0.22 / 255,
 * monotone, black at 0 and white where the curve reaches it. */
static void display_fit_follows_the_curve_and_the_encoding(void)
{
    for (int tone = 0; tone < 2; tone++) {
        double worst = 0.0;
        float prev = 0.0f;
        CHECK(pelt__display(0.0f, 1.0f, tone) == 0.0f);
        CHECK(pelt__display(-1.0f, 1.0f, tone) == 0.0f);
        for (int i = 0; i <= 80000; i++) {
            float x = powf(10.0f, -6.0f + 8.0f * (float)i / 80000.0f);
            float t = pelt__tone(x, 1.0f, tone);
            double exact = t <= 0.0031308f ? 12.92 * t : 1.055 * pow(t, 1.0 / 2.4) - 0.055;
            float y = pelt__display(x, 1.0f, tone);
            worst = fmax(worst, fabs(y - exact));
            CHECK(y >= prev - 1e-6f && y <= 1.0f);
            prev = y;
        }
        printf("  %s: within %.3f / 255 of the curve's sRGB encoding\n", tone ? "none" : "filmic", 255.0 * worst);
        CHECK(worst < 0.22 / 255.0);
        CHECK(255.0f * pelt__display(100.0f, 1.0f, tone) > 254.5f); /* white, written as 255 */
        /* Exposure multiplies first. */
        CHECK(fabsf(pelt__display(0.2f, 2.0f, tone) - pelt__display(0.4f, 1.0f, tone)) < 1e-6f);
    }
}

/* The brightest colour the hair models light at the default look and light
 * (white hair, ambient 0.25, light 1, K_s (0.9, 0.85, 0.8), fully
 * wet: specular gain 2), each lobe at its peak of 1, stays below white
 * after the filmic curve at exposure 1: no clipped highlight. */
static void white_highlight_stays_below_clipping(void)
{
    /* look.specular's (a gain, not decoded) and wet.gloss's defaults
       (tests/core/test_fur_defaults.c). */
    float ks = 0.9f, gain = 2.0f;
    float marschner = 0.25f + (1.0f + PELT__HAIR_SECONDARY_GAIN * gain * ks + PELT__HAIR_TT_GAIN) + gain * ks;
    float kajiya = 0.25f + 1.0f + gain * ks;
    float brightest = fmaxf(marschner, kajiya);
    printf("  brightest %.3f -> %.4f (encoded %.1f / 255)\n", brightest, pelt__tone(brightest, 1.0f, 0),
           255.0f * pelt__display(brightest, 1.0f, 0));
    CHECK(pelt__tone(brightest, 1.0f, 0) < 1.0f);
    CHECK(255.0f * pelt__display(brightest, 1.0f, 0) < 254.5f); /* not written as 255 */
    /* Clamping alone clips it. */
    CHECK(pelt__tone(brightest, 1.0f, 1) == 1.0f);
}

static void hair_lobes_peak_where_the_model_says(void)
{
    pelt_vec3 n = v3(0, 1, 0), t = v3(1, 0, 0);
    float lobes[4];
    /* Lit from above, seen from above: transmission is nil. */
    pelt__hair_lobes(t, n, v3(0, 1, 0), v3(0, -1, 0), 20.0f, lobes);
    for (int k = 0; k < 4; k++) CHECK(lobes[k] >= 0.0f && lobes[k] <= 1.0f);
    CHECK(lobes[3] < 1e-6f);
    /* Backlit: the light straight behind the hair as seen from the eye. */
    pelt_vec3 e = v3(0, 0, 1);
    pelt__hair_lobes(t, n, e, e, 20.0f, lobes);
    CHECK(lobes[3] > 0.99f);
    /* Shifted tangents move the highlights' peaks apart: the primary peaks
       for a half vector leaning towards the root, which on a body curving
       away from the eye lies further towards the tips (the highlight moves
       tipwards); the secondary's the other way. */
    float best_p = -1, at_p = 0, best_s = -1, at_s = 0;
    for (int i = -60; i <= 60; i++) {
        float a = (float)i * 0.5f * 3.14159265f / 180.0f;
        pelt_vec3 h = v3(sinf(a), cosf(a), 0); /* a > 0: towards the tip (+t) */
        float p = pelt__strand_specular(pelt__shift_tangent(t, n, PELT__HAIR_SHIFT_PRIMARY), h, 40.0f);
        float s = pelt__strand_specular(pelt__shift_tangent(t, n, PELT__HAIR_SHIFT_SECONDARY), h, 40.0f);
        if (p > best_p) best_p = p, at_p = a;
        if (s > best_s) best_s = s, at_s = a;
    }
    CHECK(at_p < 0.0f && at_s > 0.0f);
    /* The fur's density darkens its roots; none at the tips. */
    float depth = pelt__occlusion_depth(3000.0f, 1.6f, 256);
    CHECK(fabsf(pelt__fur_occlusion(depth, 0.0f) - 0.5f) < 0.03f);
    CHECK(pelt__fur_occlusion(depth, 1.0f) == 1.0f);
    CHECK(pelt__occlusion_depth(6000.0f, 1.6f, 256) > depth);
}

int main(void)
{
    RUN(kajiya_kay_diffuse_is_the_sine_of_tangent_and_light);
    RUN(kajiya_kay_specular_peaks_on_the_mirror_cone);
    RUN(shadow_factor_darkens_the_roots);
    RUN(wet_highlight_grows_sharper_and_stronger);
    RUN(inter_shadow_fades_from_the_side);
    RUN(srgb_round_trips_every_byte);
    RUN(tone_curves_are_monotone_and_start_at_black);
    RUN(display_fit_follows_the_curve_and_the_encoding);
    RUN(white_highlight_stays_below_clipping);
    RUN(hair_lobes_peak_where_the_model_says);
    return check_summary();
}
