/* The measures of pelt compare (core/base/image_compare.c) on synthetic
 * pictures: SSIM and mean error, the distance transform, the silhouette
 * profile, the stripe energy, the outline's grain, luminance, and
 * pelt_compare_images. */
#include "support/check.h"

#include "core/base/image_compare.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 96
#define H 80

static const uint8_t bg[3] = {20, 30, 40};

static void fill(uint8_t *rgba, unsigned w, unsigned h, uint8_t r, uint8_t g, uint8_t b)
{
    for (size_t i = 0; i < (size_t)w * h; i++) {
        rgba[i * 4 + 0] = r;
        rgba[i * 4 + 1] = g;
        rgba[i * 4 + 2] = b;
        rgba[i * 4 + 3] = 255;
    }
}

/* A disc of radius r about (cx, cy) in colour c over the background. */
static void disc(uint8_t *rgba, float cx, float cy, float r, uint8_t c)
{
    fill(rgba, W, H, bg[0], bg[1], bg[2]);
    for (unsigned y = 0; y < H; y++)
        for (unsigned x = 0; x < W; x++)
            if (hypotf(x - cx, y - cy) <= r) memset(rgba + (y * W + x) * 4, c, 3);
}

static void identical_pictures_have_ssim_1_and_mae_0(void)
{
    static uint8_t a[W * H * 4];
    for (size_t i = 0; i < sizeof a; i++) a[i] = (uint8_t)((i * 37u) ^ (i >> 5));
    bool oom = true;
    CHECK_NEAR(pelt__image_ssim(a, a, W, H, NULL, &oom), 1.0, 1e-9);
    CHECK(!oom);
    CHECK(pelt__image_mae(a, a, W, H) == 0.0);
}

static void ssim_of_two_flat_pictures_is_the_luminance_term(void)
{
    /* Flat pictures: sigma = 0, so SSIM = (2 mu_a mu_b + C1) / (mu_a^2 + mu_b^2 + C1). */
    static uint8_t a[W * H * 4], b[W * H * 4];
    fill(a, W, H, 100, 100, 100);
    fill(b, W, H, 140, 140, 140);
    double c1 = (0.01 * 255) * (0.01 * 255);
    double expected = (2.0 * 100 * 140 + c1) / (100.0 * 100 + 140.0 * 140 + c1);
    bool oom;
    CHECK_NEAR(pelt__image_ssim(a, b, W, H, NULL, &oom), expected, 1e-5);
    CHECK_NEAR(pelt__image_mae(a, b, W, H), 40.0, 1e-12);
    /* A checkerboard of 2x2 blocks (still there at half size) with the
     * same mean lowers the contrast and structure terms too. */
    for (size_t i = 0; i < (size_t)W * H; i++)
        memset(b + i * 4, (i % W / 2 + i / W / 2) % 2 ? 180 : 100, 3);
    CHECK(pelt__image_ssim(a, b, W, H, NULL, &oom) < expected);
    /* Too small for the window at half size. */
    CHECK(isnan(pelt__image_ssim(a, b, 21, 21, NULL, &oom)) && !oom);
}

/* SSIM straight from Wang et al.'s definition: for every 11x11 window of
 * the 2x2-averaged luminance, the weighted moments summed in two
 * dimensions at once (the module filters along x, then along y). */
static double ssim_by_definition(const uint8_t *a, const uint8_t *b, int w, int h)
{
    int hw = w / 2, hh = h / 2;
    static double la[64 * 64], lb[64 * 64];
    for (int y = 0; y < hh; y++)
        for (int x = 0; x < hw; x++) {
            double sa = 0, sb = 0;
            for (int k = 0; k < 4; k++) {
                int i = ((2 * y + k / 2) * w + 2 * x + k % 2) * 4;
                sa += pelt__luma(a + i);
                sb += pelt__luma(b + i);
            }
            la[y * hw + x] = sa / 4;
            lb[y * hw + x] = sb / 4;
        }
    double g[11][11], gs = 0;
    for (int i = 0; i < 11; i++)
        for (int j = 0; j < 11; j++) gs += g[i][j] = exp(-((i - 5) * (i - 5) + (j - 5) * (j - 5)) / 4.5);
    double c1 = 6.5025, c2 = 58.5225, total = 0;
    int windows = 0;
    for (int y = 0; y + 11 <= hh; y++)
        for (int x = 0; x + 11 <= hw; x++) {
            double ma = 0, mb = 0, va = 0, vb = 0, cab = 0;
            for (int i = 0; i < 11; i++)
                for (int j = 0; j < 11; j++) {
                    double wt = g[i][j] / gs, pa = la[(y + i) * hw + x + j], pb = lb[(y + i) * hw + x + j];
                    ma += wt * pa;
                    mb += wt * pb;
                }
            for (int i = 0; i < 11; i++)
                for (int j = 0; j < 11; j++) {
                    double wt = g[i][j] / gs, pa = la[(y + i) * hw + x + j] - ma, pb = lb[(y + i) * hw + x + j] - mb;
                    va += wt * pa * pa;
                    vb += wt * pb * pb;
                    cab += wt * pa * pb;
                }
            total += (2 * ma * mb + c1) * (2 * cab + c2) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
            windows++;
        }
    return total / windows;
}

static void ssim_equals_its_definition_on_noise(void)
{
    enum { w = 70, h = 52 };
    static uint8_t a[w * h * 4], b[w * h * 4];
    uint32_t s = 12345u;
    for (size_t i = 0; i < sizeof a; i++) {
        s = s * 1664525u + 1013904223u;
        a[i] = (uint8_t)(s >> 24);
        b[i] = (uint8_t)(a[i] / 2 + 40 + ((s >> 8) & 31)); /* related, not equal */
    }
    bool oom;
    double seen = pelt__image_ssim(a, b, w, h, NULL, &oom);
    CHECK_NEAR(seen, ssim_by_definition(a, b, w, h), 1e-5);
    CHECK(seen > 0.05 && seen < 0.95);
}

static void distance_transform_is_exact_euclidean(void)
{
    enum { w = 41, h = 33 };
    static uint8_t mask[w * h];
    static float dist[w * h];
    static uint32_t nearest[w * h];
    for (size_t i = 0; i < sizeof mask; i++) mask[i] = (i * 2654435761u >> 13) % 97 == 0;
    mask[5 * w + 7] = 1;
    CHECK(pelt__distance_outside(mask, w, h, dist, nearest, NULL));
    double worst = 0.0;
    bool nearest_ok = true;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double best = 1e9;
            for (int j = 0; j < w * h; j++)
                if (mask[j]) best = fmin(best, hypot(x - j % w, y - j / w));
            worst = fmax(worst, fabs(dist[y * w + x] - best));
            uint32_t n = nearest[y * w + x];
            nearest_ok &= n < (uint32_t)(w * h) && mask[n] &&
                          fabs(hypot(x - (int)(n % w), y - (int)(n / w)) - best) < 1e-4;
        }
    CHECK_NEAR(worst, 0.0, 1e-4);
    CHECK(nearest_ok);
    /* No mask pixel: far everywhere. */
    memset(mask, 0, sizeof mask);
    CHECK(pelt__distance_outside(mask, w, h, dist, nearest, NULL));
    CHECK(dist[0] == PELT__FAR && nearest[w * h - 1] == PELT__NO_PIXEL);
}

static void disc_grown_by_3_px_covers_1_and_2_not_8(void)
{
    static uint8_t skin[W * H * 4], fur[W * H * 4], mask[W * H];
    static float dist[W * H];
    disc(skin, 48, 40, 20, 200);
    disc(fur, 48, 40, 23, 200);
    for (size_t i = 0; i < (size_t)W * H; i++) mask[i] = pelt__pixel_differs(skin + i * 4, bg);
    CHECK(pelt__distance_outside(mask, W, H, dist, NULL, NULL));
    double cov[PELT_COMPARE_BANDS];
    pelt__silhouette_profile(fur, W, H, dist, bg, cov);
    CHECK_NEAR(cov[0], 1.0, 1e-12); /* (0, 1] px */
    CHECK_NEAR(cov[1], 1.0, 1e-12); /* (1, 2] */
    CHECK(cov[2] > 0.2 && cov[2] < 0.8); /* (2, 4]: half of it */
    CHECK(cov[3] == 0.0);           /* (4, 8] */
    CHECK(cov[4] == 0.0);
    /* The skin alone covers no band; a faint colour (within the threshold) neither. */
    pelt__silhouette_profile(skin, W, H, dist, bg, cov);
    CHECK(cov[0] == 0.0 && cov[1] == 0.0);
    disc(fur, 48, 40, 23, 200);
    for (size_t i = 0; i < (size_t)W * H; i++)
        if (!mask[i]) memcpy(fur + i * 4, (uint8_t[3]){bg[0] + 8, bg[1], bg[2]}, 3);
    pelt__silhouette_profile(fur, W, H, dist, bg, cov);
    CHECK(cov[3] == 0.0);
}

/* Skin on the left (x < 20), fur over it and out to x = 60 whose
 * luminance is `amp` * cos at the given period along x (the outline's
 * normal), over a falling ramp (the fur thinning out). */
static void rim(uint8_t *rgba, uint8_t *mask, double period, double amp)
{
    fill(rgba, W, H, bg[0], bg[1], bg[2]);
    for (unsigned y = 0; y < H; y++)
        for (unsigned x = 0; x < W; x++) {
            uint8_t *p = rgba + (y * W + x) * 4;
            mask[y * W + x] = x < 20;
            if (x < 60) {
                double t = x - 19.0;
                double v = 150.0 - 2.0 * t + amp * cos(2.0 * 3.14159265358979 * t / period);
                memset(p, (uint8_t)lround(v), 3);
            }
        }
}

static void striped_rim_has_more_stripe_energy_than_smooth(void)
{
    static uint8_t img[W * H * 4], mask[W * H];
    static float dist[W * H];
    static uint32_t nearest[W * H];
    const float fur_px = 16.0f; /* 16 px out to 15 px in: x = 35 .. 4 */
    rim(img, mask, 4.0, 30.0); /* a stripe every 4 px: 0.25 cycles a pixel */
    CHECK(pelt__distance_outside(mask, W, H, dist, nearest, NULL));
    double striped = pelt__stripe_energy(img, W, H, dist, nearest, fur_px, 0.25);
    rim(img, mask, 4.0, 0.0);
    double smooth = pelt__stripe_energy(img, W, H, dist, nearest, fur_px, 0.25);
    CHECK(striped > 20.0 * smooth);
    /* Rows 2 px apart (1-pixel alternating rows) count the same way. */
    rim(img, mask, 2.0, 30.0);
    double rows = pelt__stripe_energy(img, W, H, dist, nearest, fur_px, 0.25);
    CHECK(rows > 20.0 * smooth);
    /* A cosine of amplitude A over part of the profile: at most (A/2)^2
     * times the Hann window's 1.5 (main bin and its two neighbours). */
    CHECK(striped < 1.5 * 15.0 * 15.0);
    /* Slow waves below the band hardly count. */
    rim(img, mask, 9.0, 30.0);
    CHECK(pelt__stripe_energy(img, W, H, dist, nearest, fur_px, 0.25) < 0.25 * striped);
    /* ... unless the band reaches down to them. */
    CHECK(pelt__stripe_energy(img, W, H, dist, nearest, fur_px, 0.1) > 0.25 * striped);
    /* Too short a profile or a band outside what pixels hold: not measured. */
    CHECK(isnan(pelt__stripe_energy(img, W, H, dist, nearest, 3.0f, 0.25)));
    CHECK(isnan(pelt__stripe_energy(img, W, H, dist, nearest, fur_px, 0.6)));
}

/* Skin a disc of radius 20 about the centre, fur out to radius 30 whose
 * luminance is `level`, plus `amp` in one of three patterns: hairs
 * crossing the outline (alternating with the angle, 4 px apart at radius
 * 25), rings along it (alternating with the radius) or none. */
enum band_pattern { BAND_SMOOTH, BAND_HAIRS, BAND_RINGS };

static void furred_disc(uint8_t *rgba, uint8_t *mask, enum band_pattern pattern, double level, double amp)
{
    fill(rgba, W, H, bg[0], bg[1], bg[2]);
    for (unsigned y = 0; y < H; y++)
        for (unsigned x = 0; x < W; x++) {
            double dx = x - 48.0, dy = y - 40.0, r = hypot(dx, dy);
            mask[y * W + x] = r <= 20.0;
            if (r > 30.0) continue;
            double v = level;
            double hairs = cos(atan2(dy, dx) * 2.0 * 3.14159265358979 * 25.0 / 4.0);
            if (pattern == BAND_HAIRS) v += amp * (hairs > 0.0 ? 1 : -1);
            if (pattern == BAND_RINGS) v += amp * (cos(r * 3.14159265358979) > 0.0 ? 1 : -1);
            memset(rgba + (y * W + x) * 4, (uint8_t)lround(v), 3);
        }
}

static void outline_grain_sees_hairs_across_the_outline(void)
{
    static uint8_t img[W * H * 4], mask[W * H];
    static float dist[W * H];
    static uint32_t nearest[W * H];
    double luma, radial;
    furred_disc(img, mask, BAND_SMOOTH, 150.0, 0.0);
    CHECK(pelt__distance_outside(mask, W, H, dist, nearest, NULL));
    double smooth = pelt__outline_grain(img, W, H, dist, nearest, 8.0f, &luma, &radial);
    CHECK(smooth < 0.5 && radial < 0.5);
    CHECK_NEAR(luma, 150.0, 1e-9); /* the band's mean */
    /* Hairs crossing the outline: a step along it, little across it. */
    furred_disc(img, mask, BAND_HAIRS, 150.0, 40.0);
    double hairs = pelt__outline_grain(img, W, H, dist, nearest, 8.0f, &luma, &radial);
    CHECK(hairs > 20.0 && hairs > 2.0 * radial);
    CHECK(fabs(luma - 150.0) < 10.0);
    /* Rows along the outline (shells seen edge-on): the other way round. */
    furred_disc(img, mask, BAND_RINGS, 150.0, 40.0);
    double rings = pelt__outline_grain(img, W, H, dist, nearest, 8.0f, NULL, &radial);
    CHECK(radial > 40.0 && rings < 0.5 * radial);
    /* No band to measure. */
    CHECK(isnan(pelt__outline_grain(img, W, H, dist, nearest, 0.5f, &luma, &radial)));
    CHECK(isnan(luma) && isnan(radial));
}

static void fur_extent_is_the_last_half_covered_distance(void)
{
    static uint8_t img[W * H * 4], mask[W * H];
    static float dist[W * H];
    rim(img, mask, 4.0, 0.0); /* skin x < 20, fur x = 20..59: 40 px */
    CHECK(pelt__distance_outside(mask, W, H, dist, NULL, NULL));
    CHECK(pelt__fur_extent(img, W, H, dist, bg) == 40.0f);
    /* Fur on only the top third of the rows: under half at every distance. */
    for (unsigned y = H / 3; y < H; y++)
        for (unsigned x = 20; x < W; x++) memcpy(img + (y * W + x) * 4, bg, 3);
    CHECK(pelt__fur_extent(img, W, H, dist, bg) == 0.0f);
}

static void mean_luminance_uses_bt601_weights_and_the_mask(void)
{
    static uint8_t img[W * H * 4], mask[W * H];
    fill(img, W, H, 255, 0, 0);
    CHECK_NEAR(pelt__mean_luminance(img, W, H, NULL), 0.299 * 255, 1e-9);
    memset(img, 0, 4); /* pixel 0 black */
    mask[0] = 1;
    CHECK_NEAR(pelt__mean_luminance(img, W, H, mask), 0.0, 1e-12);
    memset(mask, 0, sizeof mask);
    CHECK(isnan(pelt__mean_luminance(img, W, H, mask)));
}

static void compare_images_measures_shells_against_strands(void)
{
    static uint8_t skin[W * H * 4], shells[W * H * 4], strands[W * H * 4];
    disc(skin, 48, 40, 20, 200);
    disc(shells, 48, 40, 23, 200);
    disc(strands, 48, 40, 30, 100);
    pelt_compare_desc d = {.shells = {shells, W, H}, .strands = {strands, W, H},
                           .skin = {skin, W, H}, .background = {bg[0], bg[1], bg[2]},
                           .fur_px = 10.0f, .layers = 4};
    pelt_compare_result r;
    pelt_error err = {0};
    CHECK(pelt_compare_images(&d, &r, &err) == PELT_OK);
    CHECK(r.ssim < 1.0 && r.mae > 0.0);
    CHECK(r.silhouette_px[0] == 1.0f && r.silhouette_px[3] == 8.0f);
    CHECK(r.silhouette_shells[3] == 0.0 && r.silhouette_strands[3] == 1.0);
    CHECK(r.luminance_shells > r.luminance_strands);
    CHECK(isfinite(r.stripe_shells) && isfinite(r.stripe_strands));
    CHECK_NEAR(r.stripe_frequency, 0.25, 1e-9); /* 4 layers / 10 px = 0.4, above the band's 0.25 */
    /* The strands' flat disc covers the band (its luminance); the shells'
     * ends inside it: an edge along the outline, which steps across it more
     * than along it, and more than the strands' at the band's end. */
    CHECK(r.outline_radial_shells > 2.0 * r.outline_grain_shells);
    CHECK_NEAR(r.outline_luminance_strands, 100.0, 1e-9);
    CHECK(r.outline_grain_shells > r.outline_grain_strands);
    CHECK_NEAR(r.outline_grain_ratio, r.outline_grain_shells / r.outline_grain_strands, 1e-12);
    /* The same picture twice. */
    d.strands = d.shells;
    CHECK(pelt_compare_images(&d, &r, &err) == PELT_OK);
    CHECK_NEAR(r.ssim, 1.0, 1e-9);
    CHECK(r.mae == 0.0 && r.luminance_shells == r.luminance_strands);
    CHECK(r.outline_luminance_shells == r.outline_luminance_strands);
    /* No skin picture: no silhouette, no stripes. */
    d.skin.rgba = NULL;
    CHECK(pelt_compare_images(&d, &r, &err) == PELT_OK);
    CHECK(isnan(r.silhouette_shells[0]) && isnan(r.stripe_energy_ratio) && isnan(r.outline_grain_ratio));
    CHECK(isnan(r.outline_radial_shells) && isnan(r.outline_luminance_strands));
    /* Bad input names the problem. */
    d.strands.width = W - 1;
    CHECK(pelt_compare_images(&d, &r, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "size") != NULL);
    d.strands = (pelt_image){NULL, W, H};
    CHECK(pelt_compare_images(&d, &r, &err) == PELT_ERR_INVALID_ARGUMENT);
    d.shells = d.strands = (pelt_image){shells, 21, 40};
    CHECK(pelt_compare_images(&d, &r, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "22x22") != NULL);
}

/* An allocator that refuses every allocation after the first `budget`,
 * and counts what is still out. */
typedef struct budget {
    int budget, live;
} budget;

static void *budget_alloc(size_t size, void *user)
{
    budget *b = user;
    if (b->budget-- <= 0) return NULL;
    b->live++;
    return malloc(size);
}

static void budget_free(void *ptr, void *user)
{
    budget *b = user;
    if (ptr) b->live--;
    free(ptr);
}

static void compare_images_fails_cleanly_without_memory(void)
{
    static uint8_t skin[W * H * 4], shells[W * H * 4];
    disc(skin, 48, 40, 20, 200);
    disc(shells, 48, 40, 23, 200);
    int ok_at = -1;
    for (int n = 0; n < 16 && ok_at < 0; n++) {
        budget b = {n, 0};
        pelt_compare_desc d = {.shells = {shells, W, H}, .strands = {shells, W, H},
                               .skin = {skin, W, H}, .fur_px = 10.0f, .layers = 4,
                               .allocator = {budget_alloc, budget_free, &b}};
        memcpy(d.background, bg, 3);
        pelt_compare_result r;
        pelt_error err = {0};
        pelt_status st = pelt_compare_images(&d, &r, &err);
        CHECK(st == PELT_OK || (st == PELT_ERR_OUT_OF_MEMORY && strstr(err.message, "memory")));
        CHECK(b.live == 0);
        if (st == PELT_OK) ok_at = n;
    }
    CHECK(ok_at > 0); /* it does allocate, through the hooks, and then succeeds */
}

int main(void)
{
    RUN(identical_pictures_have_ssim_1_and_mae_0);
    RUN(ssim_of_two_flat_pictures_is_the_luminance_term);
    RUN(ssim_equals_its_definition_on_noise);
    RUN(distance_transform_is_exact_euclidean);
    RUN(disc_grown_by_3_px_covers_1_and_2_not_8);
    RUN(striped_rim_has_more_stripe_energy_than_smooth);
    RUN(outline_grain_sees_hairs_across_the_outline);
    RUN(fur_extent_is_the_last_half_covered_distance);
    RUN(mean_luminance_uses_bt601_weights_and_the_mask);
    RUN(compare_images_measures_shells_against_strands);
    RUN(compare_images_fails_cleanly_without_memory);
    return check_summary();
}
