/* Fins (Lengyel et al. 2001 §2.3): the edge list and the references the
 * fin shader mirrors. */
#include "core/fur/fins.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/rng.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int cmp_u64(const void *x, const void *y)
{
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return (a > b) - (a < b);
}

pelt_status pelt__fin_edges_build(const uint32_t *indices, size_t triangle_count, uint32_t seed,
                                  const pelt_allocator *alloc, pelt__fin_edge **out, size_t *count,
                                  pelt_error *err)
{
    *out = NULL;
    *count = 0;
    size_t n = 3 * triangle_count;
    uint64_t *keys = pelt__alloc(alloc, (n ? n : 1) * sizeof *keys);
    if (!keys) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for %zu fin edges", n);
    for (size_t t = 0; t < triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            uint64_t a = indices[3 * t + (size_t)k], b = indices[3 * t + (size_t)(k + 1) % 3];
            keys[3 * t + (size_t)k] = a < b ? a << 32 | b : b << 32 | a;
        }
    qsort(keys, n, sizeof *keys, cmp_u64);
    size_t unique = 0;
    for (size_t i = 0; i < n; i++)
        if (i == 0 || keys[i] != keys[i - 1]) keys[unique++] = keys[i];
    pelt__fin_edge *e = pelt__alloc(alloc, (unique ? unique : 1) * sizeof *e);
    if (!e) {
        pelt__free(alloc, keys);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for %zu fins", unique);
    }
    for (size_t i = 0; i < unique; i++) {
        e[i].a = (uint32_t)(keys[i] >> 32);
        e[i].b = (uint32_t)keys[i];
        /* Random per edge, independent of the order edges are found in. */
        e[i].start = (float)(pelt__hash32((uint32_t)keys[i] * 2654435761u ^ (uint32_t)(keys[i] >> 32) ^ seed) >> 8) /
                     16777216.0f;
    }
    pelt__free(alloc, keys);
    *out = e;
    *count = unique;
    return PELT_OK;
}

pelt_vec3 pelt__fin_normal(pelt_vec3 pa, pelt_vec3 pb, pelt_vec3 na, pelt_vec3 nb)
{
    return v3_norm_or(v3_cross(v3_sub(pb, pa), v3_add(na, nb)), na);
}

float pelt__fin_fade(pelt_vec3 fin_normal, pelt_vec3 view_dir)
{
    return fmaxf(0.0f, 2.0f * fabsf(v3_dot(fin_normal, view_dir)) - 1.0f);
}

float pelt__fin_spacing_opacity(float edge, float slab)
{
    if (!(slab > 0.0f) || !(edge < slab)) return 1.0f;
    return edge > 0.0f ? edge / slab : 0.0f;
}

void pelt__fin_normals(const pelt__fin_edge *edges, size_t count, const float *positions, const float *normals,
                       float *out)
{
    for (size_t i = 0; i < count; i++) {
        size_t a = edges[i].a, b = edges[i].b;
        pelt_vec3 n = pelt__fin_normal(v3_load(positions + 3 * a), v3_load(positions + 3 * b),
                                       v3_load(normals + 3 * a), v3_load(normals + 3 * b));
        v3_store(out + 3 * i, n);
    }
}

uint32_t pelt__outline_seed(uint32_t a, uint32_t b, uint32_t k)
{
    return pelt__hash32(a * 0x27d4eb2du ^ pelt__hash32(b ^ (k * 0x165667b1u)));
}

float pelt__outline_random(uint32_t seed, uint32_t i)
{
    return (float)(pelt__hash32(seed + i * 0x9e3779b9u) >> 8) * (1.0f / 16777216.0f);
}

static float clamp01(float x)
{
    return x < 0.0f ? 0.0f : x > 1.0f ? 1.0f : x;
}

float pelt__outline_alpha(float k, float count, float fade, float show)
{
    float more = count / (float)PELT__OUTLINE_HAIRS_MAX;
    return clamp01(count - k) * clamp01((fade - show) * 4.0f) * (more > 1.0f ? more : 1.0f);
}

float pelt__outline_reach(float hair_px)
{
    float in = clamp01((hair_px - PELT__OUTLINE_LOW_PX) / PELT__OUTLINE_LOW_PX);
    return in * clamp01((PELT__OUTLINE_NONE_PX - hair_px) / (PELT__OUTLINE_NONE_PX - PELT__OUTLINE_FULL_PX));
}

float pelt__outline_share(float hair_px, float wetness)
{
    return pelt__outline_reach(hair_px) * (1.0f - clamp01(wetness));
}

float pelt__outline_lean(float r)
{
    return (r - 0.5f) * 2.0f;
}

void pelt__outline_shape(pelt_vec3 root, pelt_vec3 p, pelt_vec3 along, float r_len, float r_lean, float h,
                         float out[4])
{
    float share = 0.6f + 0.4f * r_len;
    pelt_vec3 lean = v3_scale(along, pelt__outline_lean(r_lean) * h);
    pelt_vec3 q = v3_add(v3_add(root, v3_scale(v3_sub(p, root), share)), lean);
    out[0] = q.x, out[1] = q.y, out[2] = q.z, out[3] = share;
}

float pelt__outline_fade(pelt_vec3 a, pelt_vec3 b, pelt_vec3 na, pelt_vec3 nb, pelt_vec3 eye, float tiles_per_unit,
                         float slab)
{
    pelt_vec3 ray = v3_norm_or(v3_sub(v3_scale(v3_add(a, b), 0.5f), eye), v3(0.0f, 0.0f, 0.0f));
    float fade = pelt__fin_fade(pelt__fin_normal(a, b, na, nb), ray);
    return fade * pelt__fin_spacing_opacity(v3_len(v3_sub(b, a)) * tiles_per_unit, slab);
}

/* m (column-major) times (x, y, z, w). */
static void mat4_times(const float m[16], const float p[4], float out[4])
{
    for (int i = 0; i < 4; i++) out[i] = m[i] * p[0] + m[4 + i] * p[1] + m[8 + i] * p[2] + m[12 + i] * p[3];
}

/* Where the middle of (a, b) lands in normalised device coordinates. */
static void outline_ndc(const pelt__outline_frame *f, const float *a, const float *b, float ndc[2])
{
    float p[4] = {0.5f * (a[0] + b[0]), 0.5f * (a[1] + b[1]), 0.5f * (a[2] + b[2]), 1.0f}, w[4], c[4];
    mat4_times(f->model, p, w);
    mat4_times(f->view_proj, w, c);
    float cw = c[3] > 1e-6f ? c[3] : 1e-6f;
    ndc[0] = c[0] / cw, ndc[1] = c[1] / cw;
}

float pelt__outline_hair_px(const pelt__outline_frame *f, const float *va, const float *vb)
{
    float r[2], t[2];
    outline_ndc(f, va, vb, r);
    outline_ndc(f, va + f->top, vb + f->top, t);
    float dx = 0.5f * f->viewport[0] * (t[0] - r[0]), dy = 0.5f * f->viewport[1] * (t[1] - r[1]);
    return sqrtf(dx * dx + dy * dy);
}

/* The outline's reach is 0 at and below PELT__OUTLINE_LOW_PX and at and
 * above PELT__OUTLINE_NONE_PX: a fin is left out only clearly beyond
 * either, so that the vertex stage's own rounding never disagrees. */
static bool outline_out_of_reach(const pelt__outline_frame *f, const float *va, const float *vb)
{
    if (!f->view_proj || !f->model) return false;
    float px = pelt__outline_hair_px(f, va, vb);
    return px < PELT__OUTLINE_LOW_PX * 0.999f || px > PELT__OUTLINE_NONE_PX * 1.001f;
}

size_t pelt__outline_hairs(const uint32_t *fins, size_t count, const pelt__outline_frame *f, uint32_t *out,
                           size_t cap)
{
    size_t n = 0;
    for (size_t i = 0; i < count && n < cap; i++) {
        const uint32_t *fin = fins + 4 * i;
        const float *va = f->vertices + (size_t)fin[0] * f->stride, *vb = f->vertices + (size_t)fin[1] * f->stride;
        pelt_vec3 a = v3_load(va), b = v3_load(vb);
        float fade = pelt__outline_fade(a, b, v3_load(va + f->normal), v3_load(vb + f->normal), v3_load(f->eye),
                                        f->tiles_per_unit, f->slab);
        if (!(fade >= f->least) || outline_out_of_reach(f, va, vb)) continue;
        float want = ceilf(v3_len(v3_sub(b, a)) * f->tiles_per_unit * f->hairs);
        uint32_t k_end = !(want > 0.0f)                             ? 0u
                         : want > (float)PELT__OUTLINE_HAIRS_MAX ? PELT__OUTLINE_HAIRS_MAX
                                                                 : (uint32_t)want;
        for (uint32_t k = 0; k < k_end && n < cap; k++) {
            /* A hair that shows only from a stronger fade than its fin's
             * (pelt__outline_alpha is 0) is left out: the same tests as
             * the vertex stage's (outline_vs.glsl), on the same bits, for
             * no vertex work. */
            uint32_t seed = pelt__outline_seed(fin[0], fin[1], k);
            if (!(fade > pelt__outline_random(seed, 3u))) continue;
            /* ... nor one grooming thins away (groomed density at a). */
            if (pelt__outline_random(seed, 5u) > va[f->normal + 3]) continue;
            uint32_t *h = out + 4 * n++;
            h[0] = fin[0], h[1] = fin[1], h[2] = k;
            memcpy(&h[3], &fade, sizeof fade);
        }
    }
    return n;
}
