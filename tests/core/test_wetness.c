/* Wetness mask: Alg. 1 branches (Silva et al. §3.1 as docs/wetness.md reads it),
 * drying, dirty rectangles, painting and the mask picture. Rain and the
 * ray -> droplet path are in test_rain.c, droplets at surface points in
 * test_surface_droplet.c. */
#include "support/check.h"
#include "core/wet/mask.h"
#include "core/wet/paint.h"
#include "core/wet/picture.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <stb_easy_font.h>
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

static double now_s(void)
{
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static pelt__wetness *make_mask(unsigned w, unsigned h)
{
    pelt__wetness *m = NULL;
    pelt_status st = pelt__wetness_create(w, h, NULL, &m, NULL);
    CHECK(st == PELT_OK && m);
    return m;
}

static float *texel(pelt__wetness *m, unsigned x, unsigned y)
{
    return m->texels + ((size_t)y * m->width + x) * 4;
}

static void drop(pelt__wetness *m, float cx, float cy, float r, float rho)
{
    pelt_droplet d = {{cx, cy}, r, rho};
    CHECK(pelt__wetness_add_droplet(m, &d, NULL) == PELT_OK);
}

static void wetness_default_size_is_256(void)
{
    pelt__wetness *m = make_mask(0, 0);
    CHECK(m->width == 256 && m->height == 256);
    pelt__wetness_destroy(m);
}

static void wetness_dry_texel_takes_droplet(void)
{
    pelt__wetness *m = make_mask(16, 16);
    /* Texel (8,8) centre (0.53125, 0.53125) is 0.044 from the drop. */
    drop(m, 0.5f, 0.5f, 0.1f, 0.7f);
    float *t = texel(m, 8, 8);
    CHECK(t[0] == 0.5f && t[1] == 0.5f && t[2] == 0.1f && t[3] == 0.7f);
    /* Texel (0,0) is far away: untouched. */
    float *f = texel(m, 0, 0);
    CHECK(f[0] == 0.0f && f[1] == 0.0f && f[2] == 0.0f && f[3] == 0.0f);
    pelt__wetness_destroy(m);
}

static void wetness_dry_texel_with_stale_centre_near_drop_takes_droplet(void)
{
    pelt__wetness *m = make_mask(16, 16);
    /* A dried texel whose old centre lies inside the new drop: the printed
     * Alg. 1 would merge with rho 0 and leave it dry. */
    float *t = texel(m, 8, 8);
    t[0] = 0.52f;
    t[1] = 0.5f;
    t[2] = 0.3f;
    t[3] = 0.0f;
    drop(m, 0.5f, 0.5f, 0.1f, 0.6f);
    CHECK(t[0] == 0.5f && t[1] == 0.5f && t[2] == 0.1f && t[3] == 0.6f);
    pelt__wetness_destroy(m);
}

static void wetness_same_clump_merges_with_alpha_weights(void)
{
    pelt__wetness *m = make_mask(16, 16);
    drop(m, 0.5f, 0.5f, 0.2f, 0.4f);
    /* Second drop 0.05 from the stored centre, radius 0.1: same clump.
     * rho_total = 0.6, alpha = 0.2 / 0.6 = 1/3. */
    drop(m, 0.55f, 0.5f, 0.1f, 0.2f);
    float *t = texel(m, 8, 8);
    CHECK_NEAR(t[3], 0.6, 1e-6);
    CHECK_NEAR(t[0], (2.0 / 3.0) * 0.5 + (1.0 / 3.0) * 0.55, 1e-6);
    CHECK_NEAR(t[1], 0.5, 1e-6);
    CHECK_NEAR(t[2], (2.0 / 3.0) * 0.2 + (1.0 / 3.0) * 0.1, 1e-6);
    /* Texel (5,8), centre (0.34375, 0.53125), is 0.16 from the first drop
     * and 0.21 from the second: still the first clump alone. */
    float *o = texel(m, 5, 8);
    CHECK(o[0] == 0.5f && o[2] == 0.2f && o[3] == 0.4f);
    pelt__wetness_destroy(m);
}

static void wetness_merge_clamps_total_and_alpha_uses_clamped_total(void)
{
    pelt__wetness *m = make_mask(16, 16);
    drop(m, 0.5f, 0.5f, 0.2f, 0.8f);
    drop(m, 0.5f, 0.55f, 0.1f, 0.8f);
    float *t = texel(m, 8, 8);
    /* total = clamp(1.6) = 1, alpha = 0.8. */
    CHECK(t[3] == 1.0f);
    CHECK_NEAR(t[1], 0.2 * 0.5 + 0.8 * 0.55, 1e-6);
    CHECK_NEAR(t[2], 0.2 * 0.2 + 0.8 * 0.1, 1e-6);
    pelt__wetness_destroy(m);
}

static void wetness_other_clump_is_overwritten(void)
{
    pelt__wetness *m = make_mask(16, 16);
    drop(m, 0.2f, 0.5f, 0.35f, 0.9f);
    /* Stored centre (0.2, 0.5) is 0.3 from the new drop, beyond its 0.1. */
    drop(m, 0.5f, 0.5f, 0.1f, 0.3f);
    float *t = texel(m, 8, 8);
    CHECK(t[0] == 0.5f && t[1] == 0.5f && t[2] == 0.1f && t[3] == 0.3f);
    pelt__wetness_destroy(m);
}

static void wetness_clamps_to_unit_interval(void)
{
    pelt__wetness *m = make_mask(8, 8);
    drop(m, 0.5f, 0.5f, 0.3f, 5.0f);
    for (unsigned i = 0; i < 64; i++) CHECK(m->texels[i * 4 + 3] >= 0.0f && m->texels[i * 4 + 3] <= 1.0f);
    CHECK(texel(m, 4, 4)[3] == 1.0f);
    drop(m, 0.5f, 0.5f, 0.3f, -7.0f);
    CHECK(texel(m, 4, 4)[3] == 0.0f);
    pelt__wetness_destroy(m);
}

static void wetness_negative_droplet_never_creates_wetness(void)
{
    pelt__wetness *m = make_mask(16, 16);
    unsigned rect[4];
    drop(m, 0.5f, 0.5f, 0.3f, -0.5f);
    for (unsigned i = 0; i < 16 * 16 * 4; i++) CHECK(m->texels[i] == 0.0f);
    CHECK(!pelt__wetness_take_dirty(m, rect));
    pelt__wetness_destroy(m);
}

static void wetness_negative_droplet_dries_without_moving_clump(void)
{
    pelt__wetness *m = make_mask(16, 16);
    drop(m, 0.5f, 0.5f, 0.2f, 0.7f);
    /* Same clump (centre 0.05 away) and another clump's distance (0.3
     * away, radius 0.1 covers texel (8,8)? no: use a large radius). */
    drop(m, 0.55f, 0.5f, 0.1f, -0.3f);
    float *t = texel(m, 8, 8);
    CHECK_NEAR(t[3], 0.4, 1e-6);
    CHECK(t[0] == 0.5f && t[1] == 0.5f && t[2] == 0.2f);
    /* Centre 0.3 away from the stored clump centre: still only dries. */
    drop(m, 0.8f, 0.5f, 0.3f, -0.1f);
    CHECK_NEAR(t[3], 0.3, 1e-6);
    CHECK(t[0] == 0.5f && t[1] == 0.5f && t[2] == 0.2f);
    drop(m, 0.5f, 0.5f, 0.3f, -1.0f);
    CHECK(t[3] == 0.0f);
    pelt__wetness_destroy(m);
}

static void wetness_texel_outside_radius_is_untouched(void)
{
    pelt__wetness *m = make_mask(16, 16);
    /* Texel (10,8) centre x = 0.65625: 0.15625 from x = 0.5 > r = 0.15;
     * texel (9,8) centre 0.59375: 0.09375 away, inside. */
    drop(m, 0.5f, 0.53125f, 0.15f, 0.5f);
    CHECK(texel(m, 10, 8)[3] == 0.0f);
    CHECK(texel(m, 9, 8)[3] == 0.5f);
    pelt__wetness_destroy(m);
}

static void wetness_droplet_wets_exactly_the_texels_within_its_radius(void)
{
    /* Odd, non-square mask; droplets on a dry mask, some over the edges. */
    const unsigned W = 37, H = 53;
    uint64_t s = 777;
    for (int k = 0; k < 300; k++) {
        pelt__wetness *m = make_mask(W, H);
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        double cx = (double)((s >> 40) & 0xffff) / 65536.0 * 1.4 - 0.2;
        double cy = (double)((s >> 20) & 0xffff) / 65536.0 * 1.4 - 0.2;
        double r = 0.005 + 0.3 * (double)((s >> 8) & 0xfff) / 4096.0;
        drop(m, (float)cx, (float)cy, (float)r, 0.5f);
        for (unsigned y = 0; y < H; y++)
            for (unsigned x = 0; x < W; x++) {
                double dist = hypot((x + 0.5) / W - cx, (y + 0.5) / H - cy);
                if (fabs(dist - r) < 1e-5) continue; /* float rounding decides */
                CHECK((texel(m, x, y)[3] == 0.5f) == (dist < r));
            }
        pelt__wetness_destroy(m);
    }
}

static void wetness_bad_droplet_is_rejected_and_changes_nothing(void)
{
    pelt__wetness *m = make_mask(8, 8);
    pelt_error err = {0};
    pelt_droplet d = {{NAN, 0.5f}, 0.1f, 0.5f};
    CHECK(pelt__wetness_add_droplet(m, &d, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "droplet") != NULL);
    pelt_droplet neg = {{0.5f, 0.5f}, -0.1f, 0.5f};
    CHECK(pelt__wetness_add_droplet(m, &neg, NULL) == PELT_ERR_INVALID_ARGUMENT);
    for (unsigned i = 0; i < 8 * 8 * 4; i++) CHECK(m->texels[i] == 0.0f);
    /* Entirely off the mask: fine, nothing changes. */
    drop(m, 3.0f, -2.0f, 0.5f, 1.0f);
    for (unsigned i = 0; i < 8 * 8 * 4; i++) CHECK(m->texels[i] == 0.0f);
    pelt__wetness_destroy(m);
}

static void wetness_drying_reaches_exactly_zero_and_stops(void)
{
    pelt__wetness *m = make_mask(16, 16);
    unsigned rect[4];
    drop(m, 0.5f, 0.5f, 0.1f, 0.5f);
    pelt__wetness_take_dirty(m, rect);
    pelt__wetness_dry(m, 0.1f, 1.0f);
    CHECK_NEAR(texel(m, 8, 8)[3], 0.4, 1e-6);
    for (int i = 0; i < 5; i++) pelt__wetness_dry(m, 0.1f, 1.0f);
    for (unsigned i = 0; i < 16 * 16; i++) CHECK(m->texels[i * 4 + 3] == 0.0f);
    /* The clump's centre and radius stay; only rho dried. */
    CHECK(texel(m, 8, 8)[0] == 0.5f && texel(m, 8, 8)[2] == 0.1f);
    CHECK(m->wet[0] >= m->wet[2]); /* wet box empty */
    CHECK(pelt__wetness_take_dirty(m, rect));
    pelt__wetness_dry(m, 0.1f, 1.0f);
    CHECK(!pelt__wetness_take_dirty(m, rect));
    /* Negative or NaN amounts do nothing. */
    drop(m, 0.5f, 0.5f, 0.1f, 0.5f);
    pelt__wetness_dry(m, -1.0f, 1.0f);
    pelt__wetness_dry(m, NAN, 1.0f);
    CHECK(texel(m, 8, 8)[3] == 0.5f);
    pelt__wetness_destroy(m);
}

/* Bounding box {x0,y0,x1,y1} of texels that differ between a and b. */
static bool diff_box(const float *a, const float *b, unsigned w, unsigned h, unsigned box[4])
{
    bool any = false;
    box[0] = w;
    box[1] = h;
    box[2] = box[3] = 0;
    for (unsigned y = 0; y < h; y++)
        for (unsigned x = 0; x < w; x++) {
            size_t k = ((size_t)y * w + x) * 4;
            if (memcmp(a + k, b + k, 4 * sizeof(float)) == 0) continue;
            any = true;
            if (x < box[0]) box[0] = x;
            if (y < box[1]) box[1] = y;
            if (x + 1 > box[2]) box[2] = x + 1;
            if (y + 1 > box[3]) box[3] = y + 1;
        }
    return any;
}

static void wetness_dirty_rect_covers_exactly_the_changed_texels(void)
{
    const unsigned W = 64, H = 48;
    pelt__wetness *m = make_mask(W, H);
    float *before = malloc((size_t)W * H * 4 * sizeof(float));
    uint64_t s = 12345;
    for (int step = 0; step < 200; step++) {
        unsigned rect[4], box[4];
        memcpy(before, m->texels, (size_t)W * H * 4 * sizeof(float));
        int kind = step % 5;
        if (kind == 4) {
            pelt__wetness_dry(m, 0.3f, 0.1f);
        } else {
            for (int k = 0; k <= kind; k++) {
                s = s * 6364136223846793005ull + 1442695040888963407ull;
                float cx = (float)((s >> 40) & 0xffff) / 65536.0f * 1.2f - 0.1f;
                float cy = (float)((s >> 20) & 0xffff) / 65536.0f * 1.2f - 0.1f;
                float r = 0.01f + 0.1f * (float)((s >> 8) & 0xff) / 256.0f;
                float rho = (kind == 3) ? -0.4f : 0.3f + 0.2f * (float)k;
                drop(m, cx, cy, r, rho);
            }
        }
        bool any = diff_box(before, m->texels, W, H, box);
        bool got = pelt__wetness_take_dirty(m, rect);
        CHECK(any == got);
        if (any && got)
            CHECK(rect[0] == box[0] && rect[1] == box[1] && rect[2] == box[2] && rect[3] == box[3]);
    }
    free(before);
    pelt__wetness_destroy(m);
}

static void wetness_small_droplet_touches_only_its_footprint(void)
{
    const unsigned N = 2048;
    pelt__wetness *m = make_mask(N, N);
    unsigned rect[4];
    drop(m, 0.8f, 0.2f, 0.01f, 0.9f); /* something wet far away */
    pelt__wetness_take_dirty(m, rect);
    size_t bytes = (size_t)N * N * 4 * sizeof(float);
    float *before = malloc(bytes);
    memcpy(before, m->texels, bytes);
    float r = 4.0f / (float)N, cx = 0.3f, cy = 0.7f;
    drop(m, cx, cy, r, 0.8f);
    CHECK(pelt__wetness_take_dirty(m, rect));
    /* Texel centres within r of the drop: index range from the drop's box. */
    double x0 = floor((cx - r) * N), x1 = ceil((cx + r) * N);
    double y0 = floor((cy - r) * N), y1 = ceil((cy + r) * N);
    CHECK(rect[0] >= x0 && rect[2] <= x1 && rect[1] >= y0 && rect[3] <= y1);
    CHECK(rect[2] - rect[0] <= 9 && rect[3] - rect[1] <= 9);
    /* Outside the dirty rect every texel is bitwise unchanged. */
    unsigned box[4];
    CHECK(diff_box(before, m->texels, N, N, box));
    CHECK(box[0] >= rect[0] && box[2] <= rect[2] && box[1] >= rect[1] && box[3] <= rect[3]);

    /* Informational (tests never assert on time): 10,000 droplets. The
     * mask's pages are made resident first, as in a running renderer;
     * otherwise the first write to each calloc'd page is what gets timed. */
    memset(m->texels, 0, bytes);
    uint64_t s = 99;
    double t0 = now_s();
    for (int i = 0; i < 10000; i++) {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        drop(m, (float)(s >> 40) / 16777216.0f, (float)((s >> 16) & 0xffffff) / 16777216.0f,
             r, 0.7f);
    }
    double t1 = now_s();
    printf("info: 10000 droplets of radius 4 texels into %ux%u: %.2f ms\n", N, N,
           (t1 - t0) * 1e3);
    free(before);
    pelt__wetness_destroy(m);
}

/* Draws two vertical bars ("II") in a w x h image. */
static uint8_t *two_bars(unsigned w, unsigned h)
{
    uint8_t *g = calloc((size_t)w * h, 1);
    for (unsigned y = h / 8; y < h - h / 8; y++)
        for (unsigned x = 0; x < w; x++)
            if ((x >= w / 8 && x < w / 4) || (x >= w / 2 && x < w / 2 + w / 8))
                g[(size_t)y * w + x] = 255;
    return g;
}

static void wetness_painted_word_becomes_clumps_along_strokes(void)
{
    const unsigned W = 128, H = 128, iw = 64, ih = 64;
    pelt__wetness *m = make_mask(W, H);
    uint8_t *g = two_bars(iw, ih);
    pelt__paint_desc pd = {.clump_size = 0.08f, .seed = 5};
    CHECK(pelt__wetness_paint_image(m, g, iw, ih, &pd, NULL) == PELT_OK);
    /* Bars span u in [1/8, 1/4) and [1/2, 5/8), v in (1/8, 7/8). */
    CHECK(texel(m, 24, 64)[3] == 1.0f);
    CHECK(texel(m, 72, 64)[3] == 1.0f);
    CHECK(texel(m, 48, 64)[3] == 0.0f);
    CHECK(texel(m, 24, 4)[3] == 0.0f);
    int clumps_left = 0;
    float seen[64][2];
    for (unsigned y = 0; y < H; y++)
        for (unsigned x = 0; x < W; x++) {
            float *t = texel(m, x, y);
            if (t[3] == 0.0f) continue;
            float u = (x + 0.5f) / W, v = (y + 0.5f) / H;
            /* Alg. 2 must not discard a texel of its own clump. */
            CHECK(hypotf(u - t[0], v - t[1]) <= t[2]);
            /* No clump straddles the two bars: its centre is in this bar. */
            bool left = u < 0.375f;
            CHECK(left ? (t[0] > 0.1f && t[0] < 0.26f) : (t[0] > 0.49f && t[0] < 0.63f));
            if (left) {
                bool known = false;
                for (int k = 0; k < clumps_left; k++)
                    if (seen[k][0] == t[0] && seen[k][1] == t[1]) known = true;
                if (!known && clumps_left < 64) {
                    seen[clumps_left][0] = t[0];
                    seen[clumps_left][1] = t[1];
                    clumps_left++;
                }
            }
        }
    /* A bar 0.75 long with clump spacing 0.08 splits into several clumps. */
    CHECK(clumps_left >= 5);
    unsigned rect[4];
    CHECK(pelt__wetness_take_dirty(m, rect));
    CHECK(rect[0] == 0 && rect[1] == 0 && rect[2] == W && rect[3] == H);
    free(g);
    pelt__wetness_destroy(m);
}

/* Rasterises `text` with stb_easy_font, scaled by `scale`, into a w x h
 * 8-bit image: ink 255, paper 0. */
static uint8_t *text_image(const char *text, unsigned w, unsigned h, float scale, float x0, float y0)
{
    static char buf[64 * 1024]; /* 16-byte vertices, 4 per quad */
    char copy[64];
    snprintf(copy, sizeof copy, "%s", text);
    int quads = stb_easy_font_print(0.0f, 0.0f, copy, NULL, buf, (int)sizeof buf);
    uint8_t *g = calloc((size_t)w * h, 1);
    for (int q = 0; q < quads; q++) {
        const float *v0 = (const float *)(buf + (size_t)q * 64);
        const float *v2 = (const float *)(buf + (size_t)q * 64 + 32);
        int ax = (int)(x0 + v0[0] * scale), ay = (int)(y0 + v0[1] * scale);
        int bx = (int)(x0 + v2[0] * scale), by = (int)(y0 + v2[1] * scale);
        for (int y = ay; y < by; y++)
            for (int x = ax; x < bx; x++)
                if (x >= 0 && y >= 0 && (unsigned)x < w && (unsigned)y < h) g[(size_t)y * w + x] = 255;
    }
    return g;
}

static void wetness_word_written_in_water_becomes_clumps_along_letters(void)
{
    /* Silva Fig. 12c: "CGI10" written in water on a square. */
    const unsigned W = 256, iw = 256, ih = 256;
    uint8_t *g = text_image("CGI10", iw, ih, 8.0f, 12.0f, 90.0f);
    pelt__wetness *m = make_mask(W, W);
    CHECK(pelt__wetness_paint_image(m, g, iw, ih, NULL, NULL) == PELT_OK);
    /* Count distinct clumps and their sizes. */
    enum { MAXC = 4096 };
    static float cent[MAXC][3];
    int clumps = 0;
    size_t wet = 0, inked = 0;
    float max_r = 0.0f;
    for (unsigned y = 0; y < W; y++)
        for (unsigned x = 0; x < W; x++) {
            float *t = texel(m, x, y);
            if (t[3] == 0.0f) continue;
            wet++;
            float u = (x + 0.5f) / W, v = (y + 0.5f) / W;
            CHECK(hypotf(u - t[0], v - t[1]) <= t[2]);
            /* Ink under the wet texel (image row 0 is v = 1). */
            unsigned ix = (unsigned)(u * iw), iy = (unsigned)((1.0f - v) * ih);
            inked += g[(size_t)iy * iw + ix] > 0;
            max_r = fmaxf(max_r, t[2]);
            int k = 0;
            while (k < clumps && !(cent[k][0] == t[0] && cent[k][1] == t[1])) k++;
            if (k == clumps && clumps < MAXC) {
                cent[clumps][0] = t[0];
                cent[clumps][1] = t[1];
                clumps++;
            }
        }
    /* The word is wet, split into many small clumps (default spacing
     * 0.03): five glyphs of several strokes each, none a giant clump. */
    CHECK(wet > 2000);
    CHECK(inked == wet); /* same size image: resampling is exact */
    CHECK(clumps >= 5 * 6);
    CHECK(max_r < 0.06f);
    uint8_t *px = malloc((size_t)W * W * 4);
    pelt__wetness_to_rgba8(m, px);
    char path[512];
    snprintf(path, sizeof path, "%s/wetness_word_mask.png", PELT_TEST_OUT);
    CHECK(stbi_write_png(path, (int)W, (int)W, 4, px, (int)W * 4) != 0);
    printf("info: %zu wet texels in %d clumps, largest radius %.4f; mask picture %s\n", wet,
           clumps, (double)max_r, path);
    free(px);
    free(g);
    pelt__wetness_destroy(m);
}

static void wetness_painted_image_top_row_is_v_one(void)
{
    pelt__wetness *m = make_mask(4, 4);
    uint8_t g[4] = {255, 255, 0, 0}; /* 2x2: top row wet */
    CHECK(pelt__wetness_paint_image(m, g, 2, 2, NULL, NULL) == PELT_OK);
    CHECK(texel(m, 0, 3)[3] == 1.0f && texel(m, 3, 3)[3] == 1.0f);
    CHECK(texel(m, 0, 0)[3] == 0.0f && texel(m, 3, 0)[3] == 0.0f);
    CHECK(pelt__wetness_paint_image(m, g, 0, 2, NULL, NULL) == PELT_ERR_INVALID_ARGUMENT);
    pelt__wetness_destroy(m);
}

static void wetness_picture_is_black_dry_and_blue_wet(void)
{
    pelt__wetness *m = make_mask(4, 4);
    /* Texel (0,0) only: centre (0.125, 0.125), radius 0.1 reaches no other. */
    drop(m, 0.125f, 0.125f, 0.1f, 1.0f);
    uint8_t px[4 * 4 * 4];
    pelt__wetness_to_rgba8(m, px);
    /* Texel (0,0) (v = 0) is the bottom-left pixel of the picture. */
    const uint8_t *w = px + (size_t)3 * 4 * 4;
    CHECK(w[0] == 0 && w[1] == 0 && w[2] == 255 && w[3] == 255);
    const uint8_t *d = px; /* top-left: texel (0,3), dry */
    CHECK(d[0] == 0 && d[1] == 0 && d[2] == 0 && d[3] == 255);
    /* Half as wet: half as bright at the clump centre. */
    drop(m, 0.125f, 0.125f, 0.1f, -0.5f);
    pelt__wetness_to_rgba8(m, px);
    CHECK(w[2] == 128);
    pelt__wetness_destroy(m);
}

int main(void)
{
    RUN(wetness_default_size_is_256);
    RUN(wetness_dry_texel_takes_droplet);
    RUN(wetness_dry_texel_with_stale_centre_near_drop_takes_droplet);
    RUN(wetness_same_clump_merges_with_alpha_weights);
    RUN(wetness_merge_clamps_total_and_alpha_uses_clamped_total);
    RUN(wetness_other_clump_is_overwritten);
    RUN(wetness_clamps_to_unit_interval);
    RUN(wetness_negative_droplet_never_creates_wetness);
    RUN(wetness_negative_droplet_dries_without_moving_clump);
    RUN(wetness_texel_outside_radius_is_untouched);
    RUN(wetness_droplet_wets_exactly_the_texels_within_its_radius);
    RUN(wetness_bad_droplet_is_rejected_and_changes_nothing);
    RUN(wetness_drying_reaches_exactly_zero_and_stops);
    RUN(wetness_dirty_rect_covers_exactly_the_changed_texels);
    RUN(wetness_small_droplet_touches_only_its_footprint);
    RUN(wetness_painted_word_becomes_clumps_along_strokes);
    RUN(wetness_word_written_in_water_becomes_clumps_along_letters);
    RUN(wetness_painted_image_top_row_is_v_one);
    RUN(wetness_picture_is_black_dry_and_blue_wet);
    return check_summary();
}
