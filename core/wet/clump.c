/* Clump displacement: Silva et al. Eq. 5 and Alg. 2, see docs/wetness.md. */
#include "core/wet/clump.h"

#include "core/base/rng.h"
#include "core/base/vec.h"

#include <math.h>
#include <string.h>

void pelt__ringlet_levels(float rho, float levels, float stride, float out[3])
{
    out[0] = out[1] = out[2] = 0.0f;
    if (!(levels > 1.0f)) return;
    float t = fminf(fmaxf(rho, 0.0f), 1.0f) * (levels - 1.0f);
    float k = fminf(floorf(t), levels - 2.0f);
    out[0] = k * stride;
    out[1] = (k + 1.0f) * stride;
    out[2] = t - k;
}

float pelt__clump_profile(float h, float w, float n_layers)
{
    if (!(n_layers > 1.0f)) return 1.0f;
    if (!(h > 0.0f)) return 0.0f;
    float first = 1.0f / n_layers;
    /* Linear part rescaled so it, like the log part, is 0 at h = 1/N. */
    float lin = (h - first) / (1.0f - first);
    /* Silva Eq. 5 with k = ln N (the printed -ln N reverses the profile). */
    float lg = 1.0f + logf(h) / logf(n_layers);
    return clampf((1.0f - w) * lin + w * lg, 0.0f, 1.0f);
}

float pelt__clump_tuft_profile(float h, float w, float n_layers)
{
    if (!(n_layers > 1.0f)) return 1.0f;
    float first = 1.0f / n_layers;
    float t = clampf((h - PELT__CLUMP_BASE) / (1.0f - PELT__CLUMP_BASE), 0.0f, 1.0f);
    return pelt__clump_profile(first + (1.0f - first) * t, w, n_layers);
}

float pelt__clump_tuft_slope(float h, float w, float n_layers)
{
    float half_step = 0.5f / fmaxf(n_layers, 1.0f);
    return (pelt__clump_tuft_profile(h + half_step, w, n_layers) - pelt__clump_tuft_profile(h - half_step, w, n_layers)) /
           (2.0f * half_step);
}

bool pelt__clump_below_tufts(float h, float n_layers)
{
    return h + 0.5f / fmaxf(n_layers, 1.0f) <= PELT__CLUMP_BASE;
}

unsigned pelt__clump_sub_shells(float h_below, float h, float w, float n_layers, float sweep_px)
{
    float px = sweep_px * (pelt__clump_tuft_profile(h, w, n_layers) - pelt__clump_tuft_profile(h_below, w, n_layers));
    if (!(px > PELT__CLUMP_SUB_PX)) return 1;
    float k = ceilf(px / PELT__CLUMP_SUB_PX);
    return k >= (float)PELT__CLUMP_SUB_MAX ? PELT__CLUMP_SUB_MAX : (unsigned)k;
}

float pelt__sub_shell_layer(float layer, float part, float k, float step)
{
    return layer - (k - 1.0f - part) / k * step;
}

float pelt__sub_shell_alpha(float a, float k)
{
    return k > 1.0f ? 1.0f - powf(fmaxf(1.0f - a, 0.0f), 1.0f / k) : a;
}

void pelt__tuft_dots(const float l[3], const float e[3], const float g[4], float m, const float to_centre[2],
                     float slope, float out[2])
{
    float cx = to_centre[0] * slope, cy = to_centre[1] * slope;
    float tl = l[0] + cx * l[1] + cy * l[2], te = e[0] + cx * e[1] + cy * e[2];
    float len2 = 1.0f + 2.0f * (cx * g[0] + cy * g[1]) + cx * cx * g[2] + cy * cy * g[3] + 2.0f * cx * cy * m;
    float inv = len2 > 1e-30f ? 1.0f / sqrtf(len2) : 0.0f;
    out[0] = inv > 0.0f ? tl * inv : l[0];
    out[1] = inv > 0.0f ? te * inv : e[0];
}

bool pelt__clump_stray(float id, float share)
{
    /* A multiple of the id, so the strays are not the hairs that a thinned
     * groom (which keeps ids below its density) drops first or last. */
    float x = id * 7.31f;
    return x - floorf(x) < share;
}

static unsigned nearest_index(float uv, unsigned size)
{
    float x = floorf(uv * (float)size);
    /* Clamp in float first: NaN and huge values must not reach the cast. */
    if (!(x > 0.0f)) return 0;
    if (x > (float)(size - 1)) return size - 1;
    return (unsigned)x;
}

const float *pelt__clump_texel(const float *mask, unsigned width,
                               unsigned height, const float uv[2])
{
    unsigned x = nearest_index(uv[0], width), y = nearest_index(uv[1], height);
    return mask + ((size_t)y * width + x) * 4;
}

float pelt__clump_tag(float r, uint32_t key)
{
    uint32_t bits;
    memcpy(&bits, &r, sizeof bits);
    bits = (bits & ~255u) | (pelt__hash32(key) & 255u);
    memcpy(&r, &bits, sizeof r);
    return r;
}

void pelt__clump_lean(const float texel[4], float amount, float out[2])
{
    uint32_t bits;
    memcpy(&bits, &texel[2], sizeof bits);
    float a = amount * texel[2];
    out[0] = a * ((float)(bits & 15u) / 7.5f - 1.0f);
    out[1] = a * ((float)((bits >> 4) & 15u) / 7.5f - 1.0f);
}

pelt__clump_result pelt__clump_lookup(const float *mask, unsigned width,
                                      unsigned height, const float p[2],
                                      float h, float w, float n_layers,
                                      float s, float q[2])
{
    const float none[2] = {0.0f, 0.0f};
    return pelt__clump_lookup_lean(mask, width, height, p, h, w, n_layers, s, none, q);
}

pelt__clump_result pelt__clump_lookup_lean(const float *mask, unsigned width, unsigned height,
                                           const float p[2], float h, float w, float n_layers, float s,
                                           const float lean[2], float q[2])
{
    q[0] = p[0];
    q[1] = p[1];
    const float *t = pelt__clump_texel(mask, width, height, p);
    float rho = t[3];
    if (!(rho > 0.0f)) return PELT__CLUMP_KEEP; /* Alg. 2: dry, not in a clump */
    float ox = p[0] - t[0], oy = p[1] - t[1];
    if (sqrtf(ox * ox + oy * oy) > t[2]) return PELT__CLUMP_DISCARD; /* another clump */
    float pull = clampf(s * rho * pelt__clump_tuft_profile(h, w, n_layers), 0.0f,
                        PELT__CLUMP_MAX_PULL);
    ox -= pull * lean[0];
    oy -= pull * lean[1];
    /* Inverse of the strand map root q -> c + (q - c)(1 - pull) + pull lean (docs/wetness.md). */
    float k = 1.0f / (1.0f - pull);
    q[0] = t[0] + ox * k;
    q[1] = t[1] + oy * k;
    /* The root must lie in this clump: strands from beyond its radius
     * belong to a neighbour, so the clump narrows towards its tip. */
    if (sqrtf(ox * ox + oy * oy) * k > t[2]) return PELT__CLUMP_DISCARD;
    const float *tq = pelt__clump_texel(mask, width, height, q);
    if (!(tq[3] > 0.0f)) return PELT__CLUMP_DISCARD; /* root lies in dry fur */
    return PELT__CLUMP_DISPLACED;
}

float pelt__clump_coverage(float a, float k)
{
    return 1.0f - powf(fmaxf(1.0f - a, 0.0f), 1.0f / k);
}

float pelt__clump_bundle_squeeze(float squeeze, float lod)
{
    return 1.0f + (squeeze - 1.0f) * clampf(lod - PELT__CLUMP_RESOLVED_LOD, 0.0f, 1.0f);
}

float pelt__clump_fin_shift(const float d[2], const float dir[2])
{
    float len2 = dir[0] * dir[0] + dir[1] * dir[1];
    return len2 > 1e-20f ? (d[0] * dir[0] + d[1] * dir[1]) / len2 : 0.0f;
}
