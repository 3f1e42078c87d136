/* Wetness painted from a greyscale image, cut into clumps (Silva et al. Fig. 12c). */
#include "core/wet/paint.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/rng.h"
#include "core/base/vec.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Bilinear grey level in [0,1] at image pixel coordinates (x, y), edges
 * clamped. */
static float grey_at(const uint8_t *g, unsigned w, unsigned h, float x, float y)
{
    x = clampf(x, 0.0f, (float)(w - 1));
    y = clampf(y, 0.0f, (float)(h - 1));
    unsigned x0 = (unsigned)x, y0 = (unsigned)y;
    unsigned x1 = x0 + 1 < w ? x0 + 1 : x0, y1 = y0 + 1 < h ? y0 + 1 : y0;
    float fx = x - (float)x0, fy = y - (float)y0;
    float a = g[(size_t)y0 * w + x0] * (1.0f - fx) + g[(size_t)y0 * w + x1] * fx;
    float b = g[(size_t)y1 * w + x0] * (1.0f - fx) + g[(size_t)y1 * w + x1] * fx;
    return (a * (1.0f - fy) + b * fy) * (1.0f / 255.0f);
}

/* A grid cell hashed to [0,1), for the jitter of clump seeds: the one
 * lattice hash of core/base/rng.h, one axis at a time. */
static float cell_hash(int64_t gx, int64_t gy, uint32_t seed, uint32_t salt)
{
    uint32_t h = pelt__hash32(seed ^ salt * 0x9e3779b9u);
    h = pelt__hash_axis(h, (int32_t)gx, 0x85ebca77u);
    h = pelt__hash_axis(h, (int32_t)gy, 0xc2b2ae3du);
    return (float)(h >> 8) * (1.0f / 16777216.0f);
}

typedef struct paint_key {
    uint64_t key; /* cell * region_count + region */
    size_t texel;
} paint_key;

static int paint_key_cmp(const void *a, const void *b)
{
    const paint_key *p = a, *q = b;
    if (p->key != q->key) return p->key < q->key ? -1 : 1;
    return p->texel < q->texel ? -1 : (p->texel > q->texel);
}

pelt_status pelt__wetness_paint_image(pelt__wetness *m, const uint8_t *grey,
                                      unsigned w, unsigned h,
                                      const pelt__paint_desc *desc,
                                      pelt_error *err)
{
    if (!m || !grey || w == 0 || h == 0)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "wetness image: %ux%u image or NULL pointer", w, h);
    pelt__paint_desc d = desc ? *desc : (pelt__paint_desc){0};
    if (d.clump_size == 0.0f) d.clump_size = 0.03f;
    if (d.threshold == 0.0f) d.threshold = 0.1f;
    if (d.seed == 0) d.seed = 1;
    if (!(d.clump_size > 0.0f) || !isfinite(d.clump_size) || !isfinite(d.threshold))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "wetness image: clump_size %g must be > 0 and threshold %g finite",
                          (double)d.clump_size, (double)d.threshold);
    unsigned W = m->width, H = m->height;
    /* Keep the clump grid at least one texel and at most 4096 cells wide. */
    float min_cell = fmaxf(1.0f / (float)(W > H ? W : H), 1.0f / 4096.0f);
    float cs = fmaxf(d.clump_size, min_cell);
    size_t count = (size_t)W * H;

    uint32_t *region = pelt__alloc_zero(&m->alloc, count, sizeof *region); /* 0 = dry */
    size_t *queue = pelt__alloc_zero(&m->alloc, count, sizeof *queue);
    paint_key *keys = pelt__alloc_zero(&m->alloc, count, sizeof *keys);
    float *rho = pelt__alloc_zero(&m->alloc, count, sizeof *rho);
    if (!region || !queue || !keys || !rho) {
        pelt__free(&m->alloc, region);
        pelt__free(&m->alloc, queue);
        pelt__free(&m->alloc, keys);
        pelt__free(&m->alloc, rho);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY,
                          "wetness image: out of memory for a %ux%u mask", W, H);
    }

    /* Resample: mask row j sits at v = (j+0.5)/H, image row 0 at v = 1. */
    for (unsigned j = 0; j < H; j++) {
        float yi = (1.0f - ((float)j + 0.5f) / (float)H) * (float)h - 0.5f;
        for (unsigned i = 0; i < W; i++) {
            float xi = ((float)i + 0.5f) / (float)W * (float)w - 0.5f;
            float g = grey_at(grey, w, h, xi, yi);
            rho[(size_t)j * W + i] = (g >= d.threshold && g > 0.0f) ? g : 0.0f;
        }
    }

    /* Connected wet regions (4-neighbours), labelled 1.. by flood fill. */
    uint32_t regions = 0;
    for (size_t s = 0; s < count; s++) {
        if (rho[s] <= 0.0f || region[s]) continue;
        regions++;
        size_t head = 0, tail = 0;
        queue[tail++] = s;
        region[s] = regions;
        while (head < tail) {
            size_t k = queue[head++];
            unsigned x = (unsigned)(k % W), y = (unsigned)(k / W);
            size_t nb[4];
            int nn = 0;
            if (x > 0) nb[nn++] = k - 1;
            if (x + 1 < W) nb[nn++] = k + 1;
            if (y > 0) nb[nn++] = k - W;
            if (y + 1 < H) nb[nn++] = k + W;
            for (int e = 0; e < nn; e++)
                if (rho[nb[e]] > 0.0f && !region[nb[e]]) {
                    region[nb[e]] = regions;
                    queue[tail++] = nb[e];
                }
        }
    }

    /* Each wet texel joins the nearest jittered seed of the clump grid; the
     * key (cell, region) names its clump. */
    int64_t cols = (int64_t)ceilf(1.0f / cs) + 2;
    size_t wet = 0;
    for (size_t k = 0; k < count; k++) {
        if (!region[k]) continue;
        float u = ((float)(k % W) + 0.5f) / (float)W, v = ((float)(k / W) + 0.5f) / (float)H;
        int64_t gx = (int64_t)floorf(u / cs), gy = (int64_t)floorf(v / cs);
        int64_t best = 0;
        float best_d = INFINITY;
        for (int64_t oy = -1; oy <= 1; oy++)
            for (int64_t ox = -1; ox <= 1; ox++) {
                int64_t cx = gx + ox, cy = gy + oy;
                float sx = ((float)cx + 0.5f + 0.8f * (cell_hash(cx, cy, d.seed, 1) - 0.5f)) * cs;
                float sy = ((float)cy + 0.5f + 0.8f * (cell_hash(cx, cy, d.seed, 2) - 0.5f)) * cs;
                float dd = (sx - u) * (sx - u) + (sy - v) * (sy - v);
                if (dd < best_d) {
                    best_d = dd;
                    best = (cy + 1) * cols + (cx + 1);
                }
            }
        keys[wet].key = (uint64_t)best * (regions + 1ull) + region[k];
        keys[wet].texel = k;
        wet++;
    }
    qsort(keys, wet, sizeof *keys, paint_key_cmp);

    /* Write the mask: every piece gets its centroid and covering radius
     * (plus half a texel diagonal, since fragments lie anywhere in a texel). */
    memset(m->texels, 0, count * 4 * sizeof(float));
    float half_diag = 0.5f * sqrtf(1.0f / ((float)W * W) + 1.0f / ((float)H * H));
    pelt__rect_clear(m->wet);
    for (size_t a = 0; a < wet;) {
        size_t b = a;
        double su = 0.0, sv = 0.0;
        while (b < wet && keys[b].key == keys[a].key) {
            size_t k = keys[b].texel;
            su += ((double)(k % W) + 0.5) / W;
            sv += ((double)(k / W) + 0.5) / H;
            b++;
        }
        float cu = (float)(su / (double)(b - a)), cv = (float)(sv / (double)(b - a));
        float r = 0.0f;
        for (size_t e = a; e < b; e++) {
            size_t k = keys[e].texel;
            float du = ((float)(k % W) + 0.5f) / (float)W - cu;
            float dv = ((float)(k / W) + 0.5f) / (float)H - cv;
            r = fmaxf(r, sqrtf(du * du + dv * dv));
        }
        r += half_diag;
        for (size_t e = a; e < b; e++) {
            size_t k = keys[e].texel;
            float *t = m->texels + k * 4;
            t[0] = cu;
            t[1] = cv;
            t[2] = r;
            t[3] = clampf(rho[k], 0.0f, 1.0f);
            pelt__rect_add_texel(m->wet, (unsigned)(k % W), (unsigned)(k / W));
        }
        a = b;
    }
    unsigned all[4] = {0, 0, W, H};
    pelt__rect_union(m->dirty, all);
    pelt__free(&m->alloc, region);
    pelt__free(&m->alloc, queue);
    pelt__free(&m->alloc, keys);
    pelt__free(&m->alloc, rho);
    return PELT_OK;
}
