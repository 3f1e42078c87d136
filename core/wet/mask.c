/* Wetness mask: texels, droplets blended by Silva et al. Alg. 1 (§3.1), drying, dirty rect. */
#define _DEFAULT_SOURCE /* madvise(MADV_HUGEPAGE) */
#include "core/wet/mask.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/vec.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#if defined(__linux__)
#include <sys/mman.h>
#endif

/* Zeroed texel storage. Droplets land at random places, each touching a
 * few rows that lie a whole row (pages) apart, so on a large mask most of
 * their cost is TLB misses: ask for huge pages there (Linux, where the
 * kernel grants them on request). A caller's allocator is used as it is:
 * its memory is its own to place. */
static bool huge_pages(const pelt_allocator *a, size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    return !a->alloc && bytes >= ((size_t)4 << 20);
#else
    (void)a, (void)bytes;
    return false;
#endif
}

static float *alloc_texels(const pelt_allocator *a, size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    const size_t huge = (size_t)2 << 20;
    if (huge_pages(a, bytes)) {
        void *p = NULL;
        if (posix_memalign(&p, huge, bytes) != 0) return NULL;
        madvise(p, bytes, MADV_HUGEPAGE);
        memset(p, 0, bytes);
        return p;
    }
#endif
    return pelt__alloc_zero(a, bytes, 1);
}

/* posix_memalign memory goes back to free(), the rest to the allocator. */
static void free_texels(const pelt_allocator *a, pelt__wetness *m)
{
    if (huge_pages(a, (size_t)m->width * m->height * 4 * sizeof(float)))
        free(m->texels);
    else
        pelt__free(a, m->texels);
}

pelt_status pelt__wetness_create(unsigned width, unsigned height,
                                 const pelt_allocator *a, pelt__wetness **out, pelt_error *err)
{
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "wetness mask: out is NULL");
    *out = NULL;
    if (width == 0) width = PELT__WETNESS_DEFAULT_SIZE;
    if (height == 0) height = PELT__WETNESS_DEFAULT_SIZE;
    /* GL texture sizes are ints; keep index maths in range too. */
    if (width > 65536u || height > 65536u)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "wetness mask: size %ux%u exceeds 65536", width, height);
    pelt__wetness *m = pelt__alloc_zero(a, 1, sizeof *m);
    if (!m) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "wetness mask: out of memory");
    size_t count = (size_t)width * height;
    if (a) m->alloc = *a;
    m->texels = count <= (size_t)-1 / 16 ? alloc_texels(&m->alloc, count * 4 * sizeof(float)) : NULL;
    if (!m->texels) {
        pelt__free(a, m);
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
    pelt_allocator alloc = m->alloc;
    free_texels(&alloc, m);
    pelt__free(&alloc, m);
}

void pelt__wetness_clear(pelt__wetness *m)
{
    const unsigned *b = m->wet;
    for (unsigned y = b[1]; y < b[3]; y++)
        memset(m->texels + ((size_t)y * m->width + b[0]) * 4, 0,
               (size_t)(b[2] - b[0]) * 4 * sizeof(float));
    pelt__rect_union(m->dirty, m->wet);
    pelt__rect_clear(m->wet);
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
    pelt__rect_union(m->dirty, changed);
    if (wd > 0.0f) pelt__rect_union(m->wet, changed);
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
    if (!(amount > 0.0f) || !isfinite(amount) || pelt__rect_empty(m->wet)) return;
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
            pelt__rect_union(changed, r);
        }
        if (wet_first <= wet_last) {
            unsigned r[4] = {wet_first, y, wet_last + 1, y + 1};
            pelt__rect_union(still_wet, r);
        }
    }
    pelt__rect_union(m->dirty, changed);
    memcpy(m->wet, still_wet, sizeof m->wet);
}

bool pelt__wetness_take_dirty(pelt__wetness *m, unsigned rect[4])
{
    if (pelt__rect_empty(m->dirty)) return false;
    memcpy(rect, m->dirty, 4 * sizeof rect[0]);
    pelt__rect_clear(m->dirty);
    return true;
}
