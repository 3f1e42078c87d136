/* How far a shell picture is from the strand reference (pelt/compare.h):
 * SSIM, mean error, the silhouette profile, the stripe energy, the
 * outline's grain, luminance. */
#include "core/base/image_compare.h"

#include "core/base/error.h"
#include "core/base/hooks.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

double pelt__luma(const uint8_t *px)
{
    /* Y = 0.299 R + 0.587 G + 0.114 B (ITU-R BT.601). */
    return 0.299 * px[0] + 0.587 * px[1] + 0.114 * px[2];
}

bool pelt__pixel_differs(const uint8_t *px, const uint8_t background[3])
{
    for (int c = 0; c < 3; c++)
        if (abs((int)px[c] - (int)background[c]) > PELT__COVERAGE_THRESHOLD) return true;
    return false;
}

/* ---- SSIM ---------------------------------------------------------------- */

/* Wang, Bovik, Sheikh, Simoncelli 2004, "Image quality assessment: from
 * error visibility to structural similarity", Eq. 13 and §III-C:
 *   SSIM = (2 mu_x mu_y + C1)(2 sigma_xy + C2) /
 *          ((mu_x^2 + mu_y^2 + C1)(sigma_x^2 + sigma_y^2 + C2)),
 * the moments weighted by an 11x11 circular Gaussian (sigma 1.5, sum 1),
 * C1 = (0.01 * 255)^2, C2 = (0.03 * 255)^2, averaged over every window
 * inside the picture. As the authors' reference code does for large
 * pictures, the luminance is first averaged over 2x2 pixels. */
#define SSIM_WINDOW 11

double pelt__image_ssim(const uint8_t *a, const uint8_t *b, unsigned w, unsigned h,
                        const pelt_allocator *alloc, bool *out_of_memory)
{
    *out_of_memory = false;
    size_t hw = w / 2, hh = h / 2;
    if (hw < SSIM_WINDOW || hh < SSIM_WINDOW) return NAN;
    size_t ow = hw - SSIM_WINDOW + 1, oh = hh - SSIM_WINDOW + 1;
    /* Two half-size luminance planes, then five moments filtered along x. */
    float *lum = pelt__alloc_zero(alloc, 2 * hw * hh + 5 * ow * hh, sizeof *lum);
    if (!lum) {
        *out_of_memory = true;
        return NAN;
    }
    float *la = lum, *lb = lum + hw * hh, *mx = lum + 2 * hw * hh;
    for (size_t y = 0; y < hh; y++)
        for (size_t x = 0; x < hw; x++) {
            double sa = 0.0, sb = 0.0;
            for (size_t dy = 0; dy < 2; dy++)
                for (size_t dx = 0; dx < 2; dx++) {
                    size_t i = ((2 * y + dy) * w + 2 * x + dx) * 4;
                    sa += pelt__luma(a + i);
                    sb += pelt__luma(b + i);
                }
            la[y * hw + x] = (float)(sa * 0.25);
            lb[y * hw + x] = (float)(sb * 0.25);
        }
    double g[SSIM_WINDOW], gsum = 0.0;
    for (int i = 0; i < SSIM_WINDOW; i++) {
        double d = i - SSIM_WINDOW / 2;
        g[i] = exp(-d * d / (2.0 * 1.5 * 1.5));
        gsum += g[i];
    }
    for (int i = 0; i < SSIM_WINDOW; i++) g[i] /= gsum;
    /* Along x: mu_a, mu_b, E[a^2], E[b^2], E[ab] per row. */
    for (size_t y = 0; y < hh; y++)
        for (size_t x = 0; x < ow; x++) {
            double m[5] = {0};
            for (int i = 0; i < SSIM_WINDOW; i++) {
                double pa = la[y * hw + x + i], pb = lb[y * hw + x + i];
                m[0] += g[i] * pa;
                m[1] += g[i] * pb;
                m[2] += g[i] * pa * pa;
                m[3] += g[i] * pb * pb;
                m[4] += g[i] * pa * pb;
            }
            for (int k = 0; k < 5; k++) mx[(k * hh + y) * ow + x] = (float)m[k];
        }
    const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
    double total = 0.0;
    for (size_t y = 0; y < oh; y++)
        for (size_t x = 0; x < ow; x++) {
            double m[5] = {0};
            for (int i = 0; i < SSIM_WINDOW; i++)
                for (int k = 0; k < 5; k++) m[k] += g[i] * mx[(k * hh + y + i) * ow + x];
            double va = m[2] - m[0] * m[0], vb = m[3] - m[1] * m[1], cab = m[4] - m[0] * m[1];
            total += (2.0 * m[0] * m[1] + c1) * (2.0 * cab + c2) /
                     ((m[0] * m[0] + m[1] * m[1] + c1) * (va + vb + c2));
        }
    pelt__free(alloc, lum);
    return total / (double)(ow * oh);
}

double pelt__image_mae(const uint8_t *a, const uint8_t *b, unsigned w, unsigned h)
{
    size_t n = (size_t)w * h;
    if (n == 0) return NAN;
    uint64_t sum = 0;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) sum += (uint64_t)abs((int)a[i * 4 + c] - (int)b[i * 4 + c]);
    return (double)sum / (3.0 * (double)n);
}

/* ---- Distance transform --------------------------------------------------- */

/* Felzenszwalb and Huttenlocher 2012, "Distance Transforms of Sampled
 * Functions", Algorithm 1: the lower envelope of the parabolas
 * (q - v)^2 + f(v), d(q) = min_v (q - v)^2 + f(v); along the columns, then
 * along the rows of the columns' result, gives the exact squared Euclidean
 * distance. arg[q] is the v of the minimum. v, z: n and n + 1 scratch. */
/* Where the parabolas of q and p cross. */
static double intersection(const double *f, size_t q, size_t p)
{
    double dq = (double)q, dp = (double)p;
    return ((f[q] + dq * dq) - (f[p] + dp * dp)) / (2.0 * dq - 2.0 * dp);
}

static void distance_1d(const double *f, size_t n, double *d, uint32_t *arg, uint32_t *v,
                        double *z)
{
    size_t k = 0;
    v[0] = 0;
    z[0] = -HUGE_VAL;
    z[1] = HUGE_VAL;
    for (size_t q = 1; q < n; q++) {
        double s = intersection(f, q, v[k]);
        while (s <= z[k]) /* z[0] = -inf ends it */
            s = intersection(f, q, v[--k]);
        k++;
        v[k] = (uint32_t)q;
        z[k] = s;
        z[k + 1] = HUGE_VAL;
    }
    k = 0;
    for (size_t q = 0; q < n; q++) {
        while (z[k + 1] < (double)q) k++;
        double dq = (double)q - v[k];
        d[q] = dq * dq + f[v[k]];
        arg[q] = v[k];
    }
}

bool pelt__distance_outside(const uint8_t *mask, unsigned w, unsigned h, float *dist,
                            uint32_t *nearest, const pelt_allocator *alloc)
{
    size_t n = (size_t)w > h ? w : h;
    const double far = 1e20; /* finite: no inf - inf inside the envelope */
    size_t pixels = (size_t)w * h;
    /* Per pixel: the column pass's squared distance and row; per line: f,
     * d, z (n + 1) and arg, v. */
    double *col = pelt__alloc_zero(alloc, pixels + 3 * n + 1, sizeof *col);
    uint32_t *rows = pelt__alloc_zero(alloc, pixels + 2 * n, sizeof *rows);
    if (!col || !rows) {
        pelt__free(alloc, col);
        pelt__free(alloc, rows);
        return false;
    }
    double *f = col + pixels, *d = f + n, *z = d + n;
    uint32_t *arg = rows + pixels, *v = arg + n;
    for (size_t x = 0; x < w; x++) {
        for (size_t y = 0; y < h; y++) f[y] = mask[y * w + x] ? 0.0 : far;
        distance_1d(f, h, d, arg, v, z);
        for (size_t y = 0; y < h; y++) {
            col[y * w + x] = d[y];
            rows[y * w + x] = arg[y];
        }
    }
    for (size_t y = 0; y < h; y++) {
        distance_1d(col + y * w, w, d, arg, v, z);
        for (size_t x = 0; x < w; x++) {
            bool none = d[x] >= far * 0.5;
            dist[y * w + x] = none ? PELT__FAR : (float)sqrt(d[x]);
            if (nearest)
                nearest[y * w + x] =
                    none ? PELT__NO_PIXEL : (uint32_t)(rows[y * w + arg[x]] * w + arg[x]);
        }
    }
    pelt__free(alloc, col);
    pelt__free(alloc, rows);
    return true;
}

/* ---- Silhouette profile --------------------------------------------------- */

void pelt__silhouette_profile(const uint8_t *rgba, unsigned w, unsigned h, const float *dist,
                              const uint8_t background[3],
                              double coverage[PELT_COMPARE_BANDS])
{
    size_t count[PELT_COMPARE_BANDS] = {0}, hit[PELT_COMPARE_BANDS] = {0};
    for (size_t i = 0; i < (size_t)w * h; i++) {
        float d = dist[i];
        if (!(d > 0.0f) || d > (float)(1u << (PELT_COMPARE_BANDS - 1))) continue;
        int k = 0; /* band k: (2^(k-1), 2^k] */
        while (d > (float)(1u << k)) k++;
        count[k]++;
        hit[k] += pelt__pixel_differs(rgba + i * 4, background);
    }
    for (int k = 0; k < PELT_COMPARE_BANDS; k++)
        coverage[k] = count[k] ? (double)hit[k] / (double)count[k] : NAN;
}

float pelt__fur_extent(const uint8_t *rgba, unsigned w, unsigned h, const float *dist,
                       const uint8_t background[3])
{
    /* Pixel counts of the bands [d, d + 1) and how many of them are fur. */
    static const size_t bands = PELT__MAX_FUR_PX;
    uint32_t count[PELT__MAX_FUR_PX] = {0}, hit[PELT__MAX_FUR_PX] = {0};
    for (size_t i = 0; i < (size_t)w * h; i++) {
        if (!(dist[i] >= 1.0f) || dist[i] >= (float)bands) continue;
        size_t d = (size_t)dist[i];
        count[d]++;
        hit[d] += pelt__pixel_differs(rgba + i * 4, background);
    }
    for (size_t d = 1; d < bands; d++)
        if (count[d] && 2 * (uint64_t)hit[d] < count[d]) return (float)(d - 1);
    return 0.0f;
}

/* ---- Stripe energy -------------------------------------------------------- */

/* Luminance at a point between pixel centres (bilinear); false outside. */
static bool luma_at(const uint8_t *rgba, unsigned w, unsigned h, double x, double y, double *out)
{
    if (!(x >= 0.0 && y >= 0.0 && x <= w - 1.0 && y <= h - 1.0)) return false;
    size_t x0 = (size_t)x, y0 = (size_t)y;
    size_t x1 = x0 + 1 < w ? x0 + 1 : x0, y1 = y0 + 1 < h ? y0 + 1 : y0;
    double fx = x - x0, fy = y - y0;
    double top = pelt__luma(rgba + (y0 * w + x0) * 4) * (1 - fx) + pelt__luma(rgba + (y0 * w + x1) * 4) * fx;
    double bot = pelt__luma(rgba + (y1 * w + x0) * 4) * (1 - fx) + pelt__luma(rgba + (y1 * w + x1) * 4) * fx;
    *out = top * (1 - fy) + bot * fy;
    return true;
}

#define STRIPE_MAX_SAMPLES PELT__MAX_FUR_PX
#define STRIPE_BAND_LOW 0.25

/* One profile's power at `freq`: the luminance x_t at t = 1..n pixels out,
 * its least-squares line removed (the fur thins out along the profile),
 * under a Hann window w_t, as the periodogram
 *   P = |sum_t w_t x_t exp(-2 pi i f t)|^2 / (sum_t w_t)^2. */
static double profile_power(const double *x, size_t n, double freq)
{
    double st = 0, sx = 0, stt = 0, stx = 0;
    for (size_t t = 0; t < n; t++) {
        st += t;
        sx += x[t];
        stt += (double)t * t;
        stx += t * x[t];
    }
    double den = n * stt - st * st;
    double slope = den != 0.0 ? (n * stx - st * sx) / den : 0.0;
    double icpt = (sx - slope * st) / n;
    double re = 0, im = 0, ws = 0;
    for (size_t t = 0; t < n; t++) {
        double s = sin(PI * (t + 0.5) / n);
        double wt = s * s, r = x[t] - (icpt + slope * t);
        re += wt * r * cos(2.0 * PI * freq * t);
        im -= wt * r * sin(2.0 * PI * freq * t);
        ws += wt;
    }
    return (re * re + im * im) / (ws * ws);
}

double pelt__stripe_energy(const uint8_t *rgba, unsigned w, unsigned h, const float *dist,
                           const uint32_t *nearest, float fur_px, double low)
{
    size_t n = fur_px >= 1.0f && 2.0f * fur_px < STRIPE_MAX_SAMPLES ? (size_t)fur_px : 0;
    if (n < 4 || !(low >= 0.0) || low > 0.5) return NAN;
    /* The band's periodogram bins, k / 2n cycles per pixel; at least two
     * cycles over the profile (a slower wave is the fur's own shading). */
    size_t k_lo = (size_t)ceil(low * 2.0 * (double)n);
    if (k_lo < 2) k_lo = 2;
    double x[STRIPE_MAX_SAMPLES];
    double total = 0.0;
    size_t profiles = 0;
    /* One profile per pixel at the band's outer edge, d in [fur_px, fur_px + 1):
     * along the line from it through its nearest skin pixel (the normal), on
     * through the fur seen at a grazing angle just inside the outline, where
     * shells show as stripes: 2 n samples, fur_px out to fur_px in. */
    for (size_t i = 0; i < (size_t)w * h; i++) {
        if (!(dist[i] >= fur_px && dist[i] < fur_px + 1.0f) || nearest[i] == PELT__NO_PIXEL)
            continue;
        double fx = (double)(nearest[i] % w), fy = (double)(nearest[i] / w);
        double ux = ((double)(i % w) - fx) / dist[i], uy = ((double)(i / w) - fy) / dist[i];
        bool inside = true;
        for (size_t t = 0; t < 2 * n && inside; t++) {
            double along = (double)n - (double)t; /* n pixels out .. n - 1 in */
            inside = luma_at(rgba, w, h, fx + ux * along, fy + uy * along, &x[t]);
        }
        if (!inside) continue;
        for (size_t k = k_lo; k <= n; k++) total += profile_power(x, 2 * n, (double)k / (2.0 * n));
        profiles++;
    }
    return profiles ? total / (double)profiles : NAN;
}

double pelt__outline_grain(const uint8_t *rgba, unsigned w, unsigned h, const float *dist,
                           const uint32_t *nearest, float fur_px, double *band_luminance,
                           double *along_normal)
{
    double grain = 0.0, luma = 0.0, radial = 0.0;
    size_t count = 0;
    /* Every pixel of the band outside the outline, d in [1, fur_px]: its
     * step to the next pixel along the outline (across the normal from its
     * nearest skin pixel), where hairs crossing the outline stand side by
     * side and a smooth band has none. */
    for (size_t i = 0; fur_px >= 1.0f && i < (size_t)w * h; i++) {
        if (!(dist[i] >= 1.0f && dist[i] <= fur_px) || nearest[i] == PELT__NO_PIXEL) continue;
        double x = (double)(i % w), y = (double)(i / w);
        double tx = -(y - (double)(nearest[i] / w)) / dist[i];
        double ty = (x - (double)(nearest[i] % w)) / dist[i];
        double here = pelt__luma(rgba + i * 4), next, out;
        if (!luma_at(rgba, w, h, x + tx, y + ty, &next) || !luma_at(rgba, w, h, x + ty, y - tx, &out))
            continue;
        grain += fabs(next - here);
        radial += fabs(out - here);
        luma += here;
        count++;
    }
    if (band_luminance) *band_luminance = count ? luma / (double)count : NAN;
    if (along_normal) *along_normal = count ? radial / (double)count : NAN;
    return count ? grain / (double)count : NAN;
}

double pelt__mean_luminance(const uint8_t *rgba, unsigned w, unsigned h, const uint8_t *mask)
{
    double sum = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < (size_t)w * h; i++)
        if (!mask || mask[i]) {
            sum += pelt__luma(rgba + i * 4);
            count++;
        }
    return count ? sum / (double)count : NAN;
}

/* ---- All of them ---------------------------------------------------------- */

static bool image_ok(const pelt_image *im) { return im->rgba && im->width && im->height; }

pelt_status pelt_compare_images(const pelt_compare_desc *desc, pelt_compare_result *out,
                                pelt_error *err)
{
    if (!desc || !out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "compare: no desc or result");
    const pelt_image *a = &desc->shells, *b = &desc->strands, *s = &desc->skin;
    if (!image_ok(a) || !image_ok(b))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "compare: a picture is missing");
    unsigned w = a->width, h = a->height;
    if (b->width != w || b->height != h || (s->rgba && (s->width != w || s->height != h)))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "compare: the pictures differ in size (%ux%u, %ux%u, skin %ux%u)", w,
                          h, b->width, b->height, s->width, s->height);
    if (w < 2 * SSIM_WINDOW || h < 2 * SSIM_WINDOW)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "compare: %ux%u is smaller than 22x22 (SSIM's window at half size)", w, h);
    if (!(desc->fur_px >= 0.0f) || !isfinite(desc->fur_px))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "compare: fur_px %g is not >= 0",
                          (double)desc->fur_px);
    const pelt_allocator *alloc = &desc->allocator;
    memset(out, 0, sizeof *out);
    bool oom = false;
    out->ssim = pelt__image_ssim(a->rgba, b->rgba, w, h, alloc, &oom);
    if (oom) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "compare: no memory for SSIM");
    out->mae = pelt__image_mae(a->rgba, b->rgba, w, h);
    size_t pixels = (size_t)w * h;
    uint8_t *mask = pelt__alloc_zero(alloc, pixels, 1);
    float *dist = pelt__alloc_zero(alloc, pixels, sizeof *dist);
    uint32_t *nearest = pelt__alloc_zero(alloc, pixels, sizeof *nearest);
    if (!mask || !dist || !nearest) {
        pelt__free(alloc, mask);
        pelt__free(alloc, dist);
        pelt__free(alloc, nearest);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "compare: no memory for %ux%u masks", w, h);
    }
    /* The subject: what either picture draws over the background. */
    for (size_t i = 0; i < pixels; i++)
        mask[i] = pelt__pixel_differs(a->rgba + i * 4, desc->background) ||
                  pelt__pixel_differs(b->rgba + i * 4, desc->background);
    out->luminance_shells = pelt__mean_luminance(a->rgba, w, h, mask);
    out->luminance_strands = pelt__mean_luminance(b->rgba, w, h, mask);
    for (int k = 0; k < PELT_COMPARE_BANDS; k++) {
        out->silhouette_px[k] = (float)(1u << k);
        out->silhouette_shells[k] = out->silhouette_strands[k] = NAN;
    }
    out->stripe_shells = out->stripe_strands = out->stripe_energy_ratio = NAN;
    out->stripe_frequency = NAN;
    out->outline_grain_shells = out->outline_grain_strands = out->outline_grain_ratio = NAN;
    out->outline_luminance_shells = out->outline_luminance_strands = NAN;
    out->outline_radial_shells = out->outline_radial_strands = NAN;
    pelt_status st = PELT_OK;
    if (s->rgba) {
        for (size_t i = 0; i < pixels; i++)
            mask[i] = pelt__pixel_differs(s->rgba + i * 4, desc->background);
        if (!pelt__distance_outside(mask, w, h, dist, nearest, alloc)) {
            st = pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "compare: no memory for the distances");
        } else {
            pelt__silhouette_profile(a->rgba, w, h, dist, desc->background, out->silhouette_shells);
            pelt__silhouette_profile(b->rgba, w, h, dist, desc->background, out->silhouette_strands);
            out->extent_shells_px = pelt__fur_extent(a->rgba, w, h, dist, desc->background);
            out->extent_strands_px = pelt__fur_extent(b->rgba, w, h, dist, desc->background);
            out->fur_px = desc->fur_px > 0.0f ? desc->fur_px : out->extent_strands_px;
            out->outline_grain_shells = pelt__outline_grain(a->rgba, w, h, dist, nearest, out->fur_px,
                                                            &out->outline_luminance_shells,
                                                            &out->outline_radial_shells);
            out->outline_grain_strands = pelt__outline_grain(b->rgba, w, h, dist, nearest, out->fur_px,
                                                             &out->outline_luminance_strands,
                                                             &out->outline_radial_strands);
            out->outline_grain_ratio = out->outline_grain_shells / out->outline_grain_strands;
            if (out->fur_px > 0.0f && desc->layers > 0) {
                /* The band: from the shells' own spacing (folded into what
                 * pixels hold) or 0.25 cycles a pixel, whichever is lower,
                 * up to 0.5: rows 2 to 4 pixels apart are what shells
                 * closer than the pixels alias into. */
                double f = desc->layers / (double)out->fur_px;
                f -= floor(f);
                if (f > 0.5) f = 1.0 - f;
                out->stripe_frequency = f < STRIPE_BAND_LOW ? f : STRIPE_BAND_LOW;
                out->stripe_shells = pelt__stripe_energy(a->rgba, w, h, dist, nearest,
                                                         out->fur_px, out->stripe_frequency);
                out->stripe_strands = pelt__stripe_energy(b->rgba, w, h, dist, nearest,
                                                          out->fur_px, out->stripe_frequency);
                if (isnan(out->stripe_shells)) out->stripe_frequency = NAN;
                out->stripe_energy_ratio = out->stripe_shells / out->stripe_strands;
            }
        }
    }
    pelt__free(alloc, mask);
    pelt__free(alloc, dist);
    pelt__free(alloc, nearest);
    return st;
}
