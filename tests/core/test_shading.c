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

int main(void)
{
    RUN(kajiya_kay_diffuse_is_the_sine_of_tangent_and_light);
    RUN(kajiya_kay_specular_peaks_on_the_mirror_cone);
    RUN(shadow_factor_darkens_the_roots);
    return check_summary();
}
