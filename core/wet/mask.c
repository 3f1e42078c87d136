/* Wetness mask: Silva et al. §3.1 and Alg. 1 as DESIGN.md reads them. */
#define _DEFAULT_SOURCE /* madvise(MADV_HUGEPAGE) */
#include "core/wet/mask.h"

#include "core/base/error.h"
#include "core/base/vec.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#if defined(__linux__)
#include <sys/mman.h>
#endif

/* ---- rectangles {x0, y0, x1, y1}, x1/y1 exclusive, empty when x0 >= x1 */

static void rect_clear(unsigned r[4]) { r[0] = r[1] = r[2] = r[3] = 0; }
static bool rect_empty(const unsigned r[4]) { return r[0] >= r[2] || r[1] >= r[3]; }

static void rect_union(unsigned r[4], const unsigned add[4])
{
    if (rect_empty(add)) return;
    if (rect_empty(r)) {
        memcpy(r, add, 4 * sizeof r[0]);
        return;
    }
    if (add[0] < r[0]) r[0] = add[0];
    if (add[1] < r[1]) r[1] = add[1];
    if (add[2] > r[2]) r[2] = add[2];
    if (add[3] > r[3]) r[3] = add[3];
}

/* Grows r to hold texel (x, y). */
static void rect_add_texel(unsigned r[4], unsigned x, unsigned y)
{
    unsigned one[4] = {x, y, x + 1, y + 1};
    rect_union(r, one);
}

/* Zeroed texel storage. Droplets land at random places, each touching a
 * few rows that lie a whole row (pages) apart, so on a large mask most of
 * their cost is TLB misses: ask for huge pages there (Linux, where the
 * kernel grants them on request). */
static float *alloc_texels(size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    const size_t huge = (size_t)2 << 20;
    if (bytes >= 2 * huge) {
        void *p = NULL;
        if (posix_memalign(&p, huge, bytes) != 0) return NULL;
        madvise(p, bytes, MADV_HUGEPAGE);
        memset(p, 0, bytes);
        return p;
    }
#endif
    return pelt__calloc(bytes, 1);
}

pelt_status pelt__wetness_create(unsigned width, unsigned height,
                                 pelt__wetness **out, pelt_error *err)
{
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "wetness mask: out is NULL");
    *out = NULL;
    if (width == 0) width = PELT__WETNESS_DEFAULT_SIZE;
    if (height == 0) height = PELT__WETNESS_DEFAULT_SIZE;
    /* GL texture sizes are ints; keep index maths in range too. */
    if (width > 65536u || height > 65536u)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "wetness mask: size %ux%u exceeds 65536", width, height);
    pelt__wetness *m = pelt__calloc(1, sizeof *m);
    if (!m) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "wetness mask: out of memory");
    size_t count = (size_t)width * height;
    m->texels = count <= (size_t)-1 / 16 ? alloc_texels(count * 4 * sizeof(float)) : NULL;
    if (!m->texels) {
        free(m);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY,
                          "wetness mask: out of memory for %ux%u texels", width, height);
    }
    m->width = width;
    m->height = height;
    *out = m;
    return PELT_OK;
}

void pelt__wetness_destroy(pelt__wetness *m)
{
    if (!m) return;
    free(m->texels);
    free(m);
}

void pelt__wetness_clear(pelt__wetness *m)
{
    const unsigned *b = m->wet;
    for (unsigned y = b[1]; y < b[3]; y++)
        memset(m->texels + ((size_t)y * m->width + b[0]) * 4, 0,
               (size_t)(b[2] - b[0]) * 4 * sizeof(float));
    rect_union(m->dirty, m->wet);
    rect_clear(m->wet);
}

/* Range of texel indices [*lo, *hi] (inclusive) whose centres (i+0.5)/n may
 * lie within [c - r, c + r], widened by one texel so the exact float test
 * per texel decides at the border. False when the range is empty. */
static bool texel_range(float c, float r, unsigned n, unsigned *lo, unsigned *hi)
{
    double a = ((double)c - r) * n - 0.5 - 1.0;
    double b = ((double)c + r) * n - 0.5 + 1.0;
    if (b < 0.0 || a > (double)n - 1.0) return false;
    a = ceil(a);
    b = floor(b);
    *lo = a < 0.0 ? 0u : (unsigned)a;
    *hi = b > (double)n - 1.0 ? n - 1 : (unsigned)b;
    return *lo <= *hi;
}

/* Alg. 1 for one texel, as pelt reads it (docs/wetness.md). cd = droplet
 * centre, rd = droplet radius, wd = droplet wetness in [-1,1], wd != 0. */
bool pelt__wetness_blend_texel(float *t, const float cd[2], float rd, float wd)
{
    float rho = t[3];
    if (wd < 0.0f) {
        /* A hair dryer only lowers wetness; it never moves or makes a clump
         * (the printed alpha = wd / total would extrapolate c and r). */
        if (!(rho > 0.0f)) return false;
        t[3] = fmaxf(rho + wd, 0.0f);
        return true;
    }
    float dx = t[0] - cd[0], dy = t[1] - cd[1];
    if (rho > 0.0f && dx * dx + dy * dy <= rd * rd) {
        /* Same clump: merge with alpha = rho_drop / rho_total (Alg. 1). */
        float total = clampf(rho + wd, 0.0f, 1.0f);
        float a = clampf(wd / total, 0.0f, 1.0f);
        float n0 = (1.0f - a) * t[0] + a * cd[0], n1 = (1.0f - a) * t[1] + a * cd[1];
        float n2 = (1.0f - a) * t[2] + a * rd;
        bool changed = n0 != t[0] || n1 != t[1] || n2 != t[2] || total != rho;
        t[0] = n0, t[1] = n1, t[2] = n2, t[3] = total;
        return changed;
    }
    /* A dry texel takes the droplet (the printed test on its stale centre
     * would leave it dry); a texel of another clump is overwritten. */
    bool changed = t[0] != cd[0] || t[1] != cd[1] || t[2] != rd || rho != wd;
    t[0] = cd[0], t[1] = cd[1], t[2] = rd, t[3] = wd;
    return changed;
}

static pelt_status check_droplet(const pelt_droplet *d, pelt_error *err)
{
    if (!isfinite(d->center[0]) || !isfinite(d->center[1]) || !isfinite(d->radius) ||
        !isfinite(d->wetness) || d->radius < 0.0f)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "droplet: centre (%g, %g), radius %g, wetness %g must be "
                          "finite with radius >= 0",
                          (double)d->center[0], (double)d->center[1],
                          (double)d->radius, (double)d->wetness);
    return PELT_OK;
}

/* Rows of a large mask lie pages apart: ask for all of a droplet's rows at
 * once so the cache and TLB misses overlap instead of queueing one per
 * row. */
static void prefetch_droplet(const pelt__wetness *m, const pelt_droplet *d)
{
#if defined(__GNUC__)
    unsigned x0, x1, y0, y1;
    if (!texel_range(d->center[0], d->radius, m->width, &x0, &x1) ||
        !texel_range(d->center[1], d->radius, m->height, &y0, &y1))
        return;
    /* Only the rows and chords blend_droplet will touch. */
    float r2 = d->radius * d->radius, inv_h = 1.0f / (float)m->height;
    for (unsigned y = y0; y <= y1; y++) {
        float dy = ((float)y + 0.5f) * inv_h - d->center[1];
        if (dy * dy > r2) continue;
        float half = sqrtf(r2 - dy * dy);
        float fa = floorf((d->center[0] - half) * (float)m->width - 0.5f);
        float fb = ceilf((d->center[0] + half) * (float)m->width - 0.5f);
        unsigned xa = fa > (float)x0 ? (unsigned)fa : x0;
        unsigned xb = fb < (float)x1 ? (fb < (float)x0 ? x0 : (unsigned)fb) : x1;
        const char *p = (const char *)(m->texels + ((size_t)y * m->width + xa) * 4);
        const char *end = (const char *)(m->texels + ((size_t)y * m->width + xb) * 4);
        for (; p <= end + 15; p += 64) __builtin_prefetch(p, 1);
    }
#else
    (void)m;
    (void)d;
#endif
}

/* Alg. 1 over the texels of one checked droplet. */
static void blend_droplet(pelt__wetness *m, const pelt_droplet *d)
{
    float wd = clampf(d->wetness, -1.0f, 1.0f);
    if (wd == 0.0f) return; /* merges with alpha 0: changes nothing */
    float r = d->radius;
    unsigned x0, x1, y0, y1;
    if (!texel_range(d->center[0], r, m->width, &x0, &x1) ||
        !texel_range(d->center[1], r, m->height, &y0, &y1))
        return;
    float inv_w = 1.0f / (float)m->width, inv_h = 1.0f / (float)m->height;
    float r2 = r * r;
    unsigned cx0 = UINT32_MAX, cx1 = 0, cy0 = UINT32_MAX, cy1 = 0; /* changed, inclusive */
    for (unsigned y = y0; y <= y1; y++) {
        float dy = ((float)y + 0.5f) * inv_h - d->center[1];
        if (dy * dy > r2) continue;
        float *row = m->texels + (size_t)y * m->width * 4;
        bool row_changed = false;
        /* This row's chord of the disc, one texel wider each side; the exact
         * test below still decides every texel. */
        unsigned xa = x0, xb = x1;
        float half = sqrtf(r2 - dy * dy);
        float fa = floorf((d->center[0] - half) * (float)m->width - 0.5f);
        float fb = ceilf((d->center[0] + half) * (float)m->width - 0.5f);
        if (fa > (float)xa) xa = (unsigned)fa;
        if (fb < (float)xb) xb = fb < (float)x0 ? x0 : (unsigned)fb;
        for (unsigned x = xa; x <= xb; x++) {
            float dx = ((float)x + 0.5f) * inv_w - d->center[0];
            if (dx * dx + dy * dy > r2) continue;
            if (!pelt__wetness_blend_texel(row + (size_t)x * 4, d->center, r, wd)) continue;
            row_changed = true;
            if (x < cx0) cx0 = x;
            if (x > cx1) cx1 = x;
        }
        if (row_changed) {
            if (y < cy0) cy0 = y;
            cy1 = y;
        }
    }
    unsigned changed[4] = {0, 0, 0, 0};
    if (cy0 <= cy1) {
        changed[0] = cx0;
        changed[1] = cy0;
        changed[2] = cx1 + 1;
        changed[3] = cy1 + 1;
    }
    rect_union(m->dirty, changed);
    if (wd > 0.0f) rect_union(m->wet, changed);
}

pelt_status pelt__wetness_add_droplet(pelt__wetness *m, const pelt_droplet *d,
                                      pelt_error *err)
{
    return pelt__wetness_add_droplets(m, d, 1, err);
}

pelt_status pelt__wetness_add_droplets(pelt__wetness *m, const pelt_droplet *d, size_t n,
                                       pelt_error *err)
{
    if (!m || !d) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "droplet: NULL argument");
    for (size_t i = 0; i < n; i++) {
        pelt_status st = check_droplet(&d[i], err);
        if (st != PELT_OK) return st; /* all checked first: a bad one changes nothing */
    }
    /* Software pipelining: the rows of a droplet a few places ahead are
     * fetched while this one blends, so random droplets overlap their
     * memory latency. */
    enum { AHEAD = 8 };
    for (size_t i = 0; i < n && i < AHEAD; i++) prefetch_droplet(m, &d[i]);
    for (size_t i = 0; i < n; i++) {
        if (i + AHEAD < n) prefetch_droplet(m, &d[i + AHEAD]);
        blend_droplet(m, &d[i]);
    }
    return PELT_OK;
}



void pelt__wetness_dry(pelt__wetness *m, float rate, float dt)
{
    float amount = rate * dt;
    if (!(amount > 0.0f) || !isfinite(amount) || rect_empty(m->wet)) return;
    unsigned still_wet[4] = {0, 0, 0, 0}, changed[4] = {0, 0, 0, 0};
    for (unsigned y = m->wet[1]; y < m->wet[3]; y++) {
        float *row = m->texels + (size_t)y * m->width * 4;
        unsigned first = m->wet[2], last = 0; /* changed texels in this row */
        unsigned wet_first = m->wet[2], wet_last = 0;
        for (unsigned x = m->wet[0]; x < m->wet[2]; x++) {
            float *t = row + (size_t)x * 4;
            if (!(t[3] > 0.0f)) continue;
            /* Linear drying, clamped so it lands on exactly 0 and stays. */
            t[3] = fmaxf(t[3] - amount, 0.0f);
            if (x < first) first = x;
            last = x;
            if (t[3] > 0.0f) {
                if (x < wet_first) wet_first = x;
                wet_last = x;
            }
        }
        if (first <= last) {
            unsigned r[4] = {first, y, last + 1, y + 1};
            rect_union(changed, r);
        }
        if (wet_first <= wet_last) {
            unsigned r[4] = {wet_first, y, wet_last + 1, y + 1};
            rect_union(still_wet, r);
        }
    }
    rect_union(m->dirty, changed);
    memcpy(m->wet, still_wet, sizeof m->wet);
}

bool pelt__wetness_take_dirty(pelt__wetness *m, unsigned rect[4])
{
    if (rect_empty(m->dirty)) return false;
    memcpy(rect, m->dirty, 4 * sizeof rect[0]);
    rect_clear(m->dirty);
    return true;
}

/* splitmix64: small and seedable; hashes the clump grid of a painting. */
static uint64_t rng_next(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1). */
static float rng_unit(uint64_t *s) { return (float)(rng_next(s) >> 40) * (1.0f / 16777216.0f); }

/* ---- painting from a greyscale image ------------------------------------ */

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

/* A hash of a grid cell to [0,1), for the jitter of clump seeds. */
static float cell_hash(int64_t gx, int64_t gy, uint32_t seed, uint32_t salt)
{
    uint64_t s = (uint64_t)gx * 0x9e3779b1ull ^ (uint64_t)gy * 0x85ebca77ull ^
                 ((uint64_t)seed << 32) ^ salt;
    return rng_unit(&s);
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

    uint32_t *region = pelt__calloc(count, sizeof *region); /* 0 = dry */
    size_t *queue = pelt__calloc(count, sizeof *queue);
    paint_key *keys = pelt__calloc(count, sizeof *keys);
    float *rho = pelt__calloc(count, sizeof *rho);
    if (!region || !queue || !keys || !rho) {
        free(region);
        free(queue);
        free(keys);
        free(rho);
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
    rect_clear(m->wet);
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
            rect_add_texel(m->wet, (unsigned)(k % W), (unsigned)(k / W));
        }
        a = b;
    }
    unsigned all[4] = {0, 0, W, H};
    rect_union(m->dirty, all);
    free(region);
    free(queue);
    free(keys);
    free(rho);
    return PELT_OK;
}

/* ---- picture of the mask (Silva Fig. 11 insets) ------------------------- */

void pelt__wetness_to_rgba8(const pelt__wetness *m, uint8_t *rgba)
{
    unsigned W = m->width, H = m->height;
    for (unsigned j = 0; j < H; j++) {
        const float *row = m->texels + (size_t)j * W * 4;
        uint8_t *out = rgba + (size_t)(H - 1 - j) * W * 4;
        float v = ((float)j + 0.5f) / (float)H;
        for (unsigned i = 0; i < W; i++) {
            const float *t = row + (size_t)i * 4;
            uint8_t *o = out + (size_t)i * 4;
            o[0] = o[1] = o[2] = 0;
            o[3] = 255;
            if (!(t[3] > 0.0f)) continue;
            float u = ((float)i + 0.5f) / (float)W;
            float dist = t[2] > 0.0f ? hypotf(u - t[0], v - t[1]) / t[2] : 0.0f;
            float shade = 1.0f - 0.4f * clampf(dist, 0.0f, 1.0f);
            o[2] = (uint8_t)lroundf(255.0f * clampf(t[3], 0.0f, 1.0f) * shade);
        }
    }
}
