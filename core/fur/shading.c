#include "core/fur/shading.h"

/* Silva et al. Eq. 6. E points from the eye to the point, so the mirror
 * cone of the light around T is where (T.L)(T.E) + sin sin peaks. */
void pelt__kajiya_kay(pelt_vec3 t, pelt_vec3 l, pelt_vec3 e, float p, float *diffuse,
                      float *specular)
{
    float tl = v3_dot(t, l), te = v3_dot(t, e);
    float sin_tl = sqrtf(fmaxf(0.0f, 1.0f - tl * tl));
    float sin_te = sqrtf(fmaxf(0.0f, 1.0f - te * te));
    *diffuse = sin_tl;
    *specular = powf(fmaxf(0.0f, tl * te + sin_tl * sin_te), p);
}

void pelt__wet_shine(float rho, float p, float sharpness, float gloss, float *p_wet, float *gain)
{
    float r = fminf(fmaxf(rho, 0.0f), 1.0f);
    *p_wet = p * (1.0f + (sharpness - 1.0f) * r);
    *gain = 1.0f + (gloss - 1.0f) * r;
}

/* Silva et al. Eq. 6: darkens the lower part of the fur. */
float pelt__shadow_factor(float k_shadow, float h) { return (k_shadow - 1.0f + h) / k_shadow; }

static float mixf(float a, float b, float t) { return a * (1.0f - t) + b * t; }

pelt_vec3 pelt__groom_root_color(pelt_vec3 color, const float c[4])
{
    return v3(mixf(color.x, c[0], c[3]), mixf(color.y, c[1], c[3]), mixf(color.z, c[2], c[3]));
}

pelt_vec3 pelt__groom_tip_color(pelt_vec3 color, pelt_vec3 tip, const float c[4])
{
    const float col[3] = {color.x, color.y, color.z}, tp[3] = {tip.x, tip.y, tip.z};
    float r[3];
    for (int k = 0; k < 3; k++)
        r[k] = mixf(tp[k], fminf(c[k] * tp[k] / fmaxf(col[k], 0.01f), 1.0f), c[3]);
    return v3(r[0], r[1], r[2]);
}

bool pelt__groom_keeps(float id, float density) { return density >= 1.0f || id < density; }

void pelt__lengyel_lighting(float u, float v, float pd, float ps, float *diffuse, float *specular)
{
    *diffuse = powf(fmaxf(0.0f, 1.0f - u * u), 0.5f * pd);
    *specular = powf(fmaxf(0.0f, 1.0f - v * v), 0.5f * ps);
}

void pelt__lengyel_table(float pd, float ps, float out[PELT__LIGHT_TABLE * PELT__LIGHT_TABLE * 2])
{
    for (int j = 0; j < PELT__LIGHT_TABLE; j++)
        for (int i = 0; i < PELT__LIGHT_TABLE; i++) {
            float u = 2.0f * ((float)i + 0.5f) / PELT__LIGHT_TABLE - 1.0f;
            float v = 2.0f * ((float)j + 0.5f) / PELT__LIGHT_TABLE - 1.0f;
            float *t = out + 2 * (j * PELT__LIGHT_TABLE + i);
            pelt__lengyel_lighting(u, v, pd, ps, &t[0], &t[1]);
        }
}

void pelt__inter_shadow_offset(pelt_vec3 l, pelt_vec3 u, pelt_vec3 v, float step, float out[2])
{
    out[0] = v3_dot(l, u) * step;
    out[1] = v3_dot(l, v) * step;
}
