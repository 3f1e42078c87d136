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

int main(void)
{
    RUN(kajiya_kay_diffuse_is_the_sine_of_tangent_and_light);
    RUN(kajiya_kay_specular_peaks_on_the_mirror_cone);
    RUN(shadow_factor_darkens_the_roots);
    RUN(wet_highlight_grows_sharper_and_stronger);
    return check_summary();
}
