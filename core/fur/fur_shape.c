/* Fur shape references: Silva et al. Eq. 1 (bend) and Eq. 4 (curl), and the
 * tangent of the displaced curve used by Kajiya-Kay (Eq. 6). */
#include "core/fur/fur_shape.h"
#include "pelt/params.h"

#include "pelt/fur.h"

#include <math.h>
#include <string.h>

/* Silva Eq. 1, beta(h) with control point n L0 / 2 (docs/dynamics.md). */
pelt_vec3 pelt__fur_bend(pelt_vec3 n, float L0, pelt_vec3 tip, float h)
{
    float a = 2.0f * h * (1.0f - h) * (0.5f * L0);
    return v3_add(v3_scale(n, a), v3_scale(tip, h * h));
}

/* Silva Eq. 4, phi(h) = (1 - rho) K h (cos(omega h) u + sin(omega h) v). */
pelt_vec3 pelt__fur_curl(pelt_vec3 u, pelt_vec3 v, float omega, float K, float rho, float h)
{
    return pelt__fur_curl_phase(u, v, omega, K, rho, h, 0.0f);
}

/* Ringlets: Eq. 4 with the strand's own phase psi. */
pelt_vec3 pelt__fur_curl_phase(pelt_vec3 u, pelt_vec3 v, float omega, float K, float rho, float h,
                               float psi)
{
    float alpha = (1.0f - rho) * K * h;
    float c = cosf(omega * h + psi), s = sinf(omega * h + psi);
    return v3_add(v3_scale(u, alpha * c), v3_scale(v, alpha * s));
}

float pelt__ringlet_phase(float id)
{
    float x = 3.0f * id;
    return 6.2831853f * (x - floorf(x));
}

pelt_vec3 pelt__ringlet_tangent(pelt_vec3 t, pelt_vec3 u, pelt_vec3 v, float k, float omega, float h,
                                float psi)
{
    float c = cosf(omega * h + psi), s = sinf(omega * h + psi);
    pelt_vec3 d = v3_add(t, v3_add(v3_scale(u, k * (c - omega * h * s)), v3_scale(v, k * (s + omega * h * c))));
    float len2 = v3_dot(d, d);
    return len2 > 1e-30f ? v3_scale(d, 1.0f / sqrtf(len2)) : t;
}

void pelt__strand_curl_slope(float radius, float omega, bool wave, float h, float psi, float out[2])
{
    float c = cosf(omega * h + psi), s = sinf(omega * h + psi);
    out[0] = wave ? radius * omega * c : -radius * omega * s;
    out[1] = wave ? 0.0f : radius * omega * c;
}

void pelt__ringlet_dots(const float ta[3], const float tb[3], const float gram[3], float k, float omega, float h,
                        float psi, const float extra[2], float out[2])
{
    float c = cosf(omega * h + psi), s = sinf(omega * h + psi);
    float a = k * (c - omega * h * s) + extra[0], b = k * (s + omega * h * c) + extra[1];
    /* |t + a u + b v|^2 with t, u, v unit */
    float len2 = 1.0f + a * a + b * b + 2.0f * (a * gram[0] + b * gram[1] + a * b * gram[2]);
    if (!(len2 > 1e-30f)) {
        out[0] = ta[0], out[1] = tb[0];
        return;
    }
    float inv = 1.0f / sqrtf(len2);
    out[0] = (ta[0] + a * ta[1] + b * ta[2]) * inv;
    out[1] = (tb[0] + a * tb[1] + b * tb[2]) * inv;
}

pelt_vec3 pelt__fur_tangent(pelt_vec3 n, float L0, pelt_vec3 tip, pelt_vec3 u, pelt_vec3 v,
                            float omega, float K, float rho, float h)
{
    return pelt__fur_tangent_combed(n, L0, tip, u, v, u, omega, K, rho, 0.0f, h);
}

/* Lengyel et al. §3, hair direction: a shear along the comb direction u. */
pelt_vec3 pelt__fur_comb(pelt_vec3 u, float L0, float slant, float h)
{
    return v3_scale(u, h * L0 * slant);
}

float pelt__fur_wet_slant(float slant, float lie, float rho)
{
    float add = lie * rho;
    if (!(add > 0.0f)) return slant;
    return tanf(fminf(atanf(slant) + add, PELT__WET_LIE_MAX));
}

pelt_vec3 pelt__fur_groom_shear(pelt_vec3 comb, float slant, pelt_vec3 u, pelt_vec3 v,
                                const float lean[2])
{
    return v3_add(v3_scale(comb, slant), v3_add(v3_scale(u, lean[0]), v3_scale(v, lean[1])));
}

pelt_vec3 pelt__fur_tangent_combed(pelt_vec3 n, float L0, pelt_vec3 tip, pelt_vec3 u, pelt_vec3 v,
                                   pelt_vec3 comb, float omega, float K, float rho, float slant,
                                   float h)
{
    /* dB/dh = (1 - 2h) L0 n + 2h tip. */
    pelt_vec3 db = v3_add(v3_scale(n, (1.0f - 2.0f * h) * L0), v3_scale(tip, 2.0f * h));
    /* dphi/dh = (1-rho) K [(cos - omega h sin) u + (sin + omega h cos) v]. */
    float k = (1.0f - rho) * K;
    float c = cosf(omega * h), s = sinf(omega * h);
    pelt_vec3 dphi = v3_add(v3_scale(u, k * (c - omega * h * s)), v3_scale(v, k * (s + omega * h * c)));
    /* d(comb)/dh = L0 slant u. */
    pelt_vec3 d = v3_mad(v3_add(db, dphi), comb, L0 * slant);
    float len2 = v3_dot(d, d);
    /* Same threshold as fur_shape.glsl, so the two agree near zero too. */
    return len2 > 1e-30f ? v3_scale(d, 1.0f / sqrtf(len2)) : n;
}

/* Silva Fig. 7: (a) straight, (b) wavy, (c) few large curls, (d) many
 * small curls. Radius K is the curl radius at the tip, relative to L0. The
 * one list of their names is pelt_curl_preset_names; the scene file also
 * takes a second spelling of two of them (same index). */
const char *const pelt_curl_preset_names[] = {"straight", "wavy", "few-large-curls", "many-small-curls", NULL};
static const char *const preset_aliases[] = {"straight", "wavy", "large_curls", "small_curls"};
static const struct {
    float omega;  /* radians over the length: turns * 2 pi */
    float radius; /* fraction of L0 */
} presets[] = {
    {0.0f, 0.0f},
    {6.2831853f, 0.08f},  /* one slow turn, small sway */
    {12.566371f, 0.35f},  /* two wide turns */
    {37.699112f, 0.12f},  /* six tight turns */
};

int pelt_curl_preset_index(const char *name)
{
    for (int i = 0; name && i < (int)(sizeof presets / sizeof presets[0]); i++)
        if (strcmp(name, pelt_curl_preset_names[i]) == 0 || strcmp(name, preset_aliases[i]) == 0) return i;
    return -1;
}

bool pelt__curl_preset(const char *name, float *omega, float *radius_fraction)
{
    int i = pelt_curl_preset_index(name);
    if (i < 0) return false;
    if (omega) *omega = presets[i].omega;
    if (radius_fraction) *radius_fraction = presets[i].radius;
    return true;
}

bool pelt_fur_curl_look(const char *name, float *omega, float *radius_fraction)
{
    return name && pelt__curl_preset(name, omega, radius_fraction);
}
