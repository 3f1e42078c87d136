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

float pelt__wet_skin_sheen(float n_dot_h, float rho, float p, float sharpness, float gloss)
{
    float p_wet, gain;
    pelt__wet_shine(rho, p, sharpness, gloss, &p_wet, &gain);
    return fminf(fmaxf(rho, 0.0f), 1.0f) * gain * powf(fminf(fmaxf(n_dot_h, 0.0f), 1.0f), p_wet * sharpness);
}

pelt_vec3 pelt__wet_color(pelt_vec3 c, float rho, float darken)
{
    float r = fminf(fmaxf(rho, 0.0f), 1.0f);
    float top = fmaxf(fmaxf(c.x, c.y), fmaxf(c.z, 1e-6f));
    float e = 1.0f + PELT__WET_SATURATION * r, k = top * (1.0f - darken * r);
    return v3(k * powf(fmaxf(c.x, 0.0f) / top, e), k * powf(fmaxf(c.y, 0.0f) / top, e),
              k * powf(fmaxf(c.z, 0.0f) / top, e));
}

/* Silva et al. Eq. 6: darkens the lower part of the fur. */
float pelt__shadow_factor(float k_shadow, float h) { return (k_shadow - 1.0f + h) / k_shadow; }

static float mixf(float a, float b, float t) { return a * (1.0f - t) + b * t; }

/* The groom's colours are sRGB bytes; the look's colours come decoded. */
pelt_vec3 pelt__groom_root_color(pelt_vec3 color, const float c[4])
{
    pelt_vec3 g = pelt__srgb_decode3(v3(c[0], c[1], c[2]));
    return v3(mixf(color.x, g.x, c[3]), mixf(color.y, g.y, c[3]), mixf(color.z, g.z, c[3]));
}

pelt_vec3 pelt__groom_tip_color(pelt_vec3 color, pelt_vec3 tip, const float c[4])
{
    pelt_vec3 g = pelt__srgb_decode3(v3(c[0], c[1], c[2]));
    const float col[3] = {color.x, color.y, color.z}, tp[3] = {tip.x, tip.y, tip.z}, gc[3] = {g.x, g.y, g.z};
    float r[3];
    for (int k = 0; k < 3; k++)
        r[k] = mixf(tp[k], fminf(gc[k] * tp[k] / fmaxf(col[k], 0.01f), 1.0f), c[3]);
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

float pelt__inter_shadow_view_fade(float n_dot_v)
{
    float t = (fabsf(n_dot_v) - PELT__INTER_SHADOW_SIDE_ON) / (PELT__INTER_SHADOW_FACE_ON - PELT__INTER_SHADOW_SIDE_ON);
    t = fminf(fmaxf(t, 0.0f), 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

float pelt__srgb_decode(float c)
{
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

float pelt__srgb_encode(float l)
{
    l = fminf(fmaxf(l, 0.0f), 1.0f);
    float s1 = sqrtf(l), s2 = sqrtf(s1), s3 = sqrtf(s2);
    float fit = 0.662002687f * s1 + 0.684122060f * s2 - 0.323583601f * s3 - 0.0225411470f * l;
    return l <= 0.0031308f ? 12.92f * l : fit;
}

float pelt__shade_decode(float c) { return c * (c * (0.305306011f * c + 0.682171111f) + 0.012522878f); }

pelt_vec3 pelt__srgb_decode3(pelt_vec3 c)
{
    return v3(pelt__srgb_decode(c.x), pelt__srgb_decode(c.y), pelt__srgb_decode(c.z));
}

/* Narkowicz's ACES fit (2015), his constants. */
float pelt__aces(float x) { return x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f); }

float pelt__tone(float x, float exposure, int tone)
{
    float v = fmaxf(x * exposure, 0.0f);
    if (tone != 0) return fminf(v, 1.0f);
    return fminf(fmaxf(pelt__aces(PELT__TONE_BIAS * v), 0.0f), 1.0f);
}

/* scripts/display_fit.c's output: p1..p5, q1..q4, v_max; display_color's
 * DISPLAY_* constants (gl/shaders/shading.glsl). */
static const float display_fit[2][10] = {
    {-0.0576929201f, 3.39692282f, -35.8013261f, 146.612241f, 2.03500454f, -12.7071925f, 60.9314706f, -69.6605025f,
     158.831435f, 12.0694f},
    {0.0326068422f, 3.15541583f, 363.172133f, 0.0f, 0.0f, -2.93838857f, 323.863771f, 44.6805545f, 0.0f, 1.0f},
};

float pelt__display(float x, float exposure, int tone)
{
    const float *c = display_fit[tone != 0];
    float s = sqrtf(fminf(fmaxf(x * exposure, 0.0f), c[9]));
    float p = s * (c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * c[4]))));
    float q = 1.0f + s * (c[5] + s * (c[6] + s * (c[7] + s * c[8])));
    return fminf(fmaxf(p / q, 0.0f), 1.0f);
}

pelt_vec3 pelt__shift_tangent(pelt_vec3 t, pelt_vec3 n, float shift)
{
    return v3_norm_or(v3_add(t, v3_scale(n, shift)), t);
}

static float smoothstepf(float e0, float e1, float x)
{
    float t = fminf(fmaxf((x - e0) / (e1 - e0), 0.0f), 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

float pelt__strand_specular(pelt_vec3 t, pelt_vec3 h, float p)
{
    float u = v3_dot(t, h);
    return smoothstepf(-1.0f, 0.0f, u) * powf(fmaxf(0.0f, 1.0f - u * u), 0.5f * p);
}

float pelt__hair_transmission(pelt_vec3 t, pelt_vec3 l, pelt_vec3 e, float p)
{
    float tl = v3_dot(t, l), te = v3_dot(t, e);
    float sin_tl = sqrtf(fmaxf(0.0f, 1.0f - tl * tl));
    float sin_te = sqrtf(fmaxf(0.0f, 1.0f - te * te));
    float cone = powf(fmaxf(0.0f, tl * te + sin_tl * sin_te), p);
    float cos_phi = (v3_dot(l, e) - tl * te) / fmaxf(sin_tl * sin_te, 1e-4f);
    return cone * powf(fminf(fmaxf(cos_phi, 0.0f), 1.0f), PELT__HAIR_TT_AZIMUTH);
}

void pelt__hair_lobes(pelt_vec3 t, pelt_vec3 n, pelt_vec3 l, pelt_vec3 e, float p, float out[4])
{
    float tl = v3_dot(t, l);
    /* The half vector between L and the direction towards the eye, -E. */
    pelt_vec3 h = v3_norm_or(v3_sub(l, e), n);
    out[0] = sqrtf(fmaxf(0.0f, 1.0f - tl * tl));
    out[1] = pelt__strand_specular(pelt__shift_tangent(t, n, PELT__HAIR_SHIFT_PRIMARY), h, p);
    out[2] = pelt__strand_specular(pelt__shift_tangent(t, n, PELT__HAIR_SHIFT_SECONDARY), h,
                                   p * PELT__HAIR_SECONDARY_WIDTH);
    out[3] = pelt__hair_transmission(t, l, e, p * PELT__HAIR_TT_WIDTH);
}

float pelt__fur_occlusion(float depth, float h) { return expf(-depth * (1.0f - h)); }

float pelt__occlusion_depth(float density, float strand_radius, unsigned texture_size)
{
    float size = (float)(texture_size ? texture_size : 1u);
    float c = density * 3.14159265f * strand_radius * strand_radius / (size * size);
    c = fminf(fmaxf(c, 0.0f), 0.95f);
    return -PELT__OCCLUSION_SLICES * logf(1.0f - c);
}
