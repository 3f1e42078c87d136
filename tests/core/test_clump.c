/* Clump displacement reference: Silva et al. Eq. 5 profile and Alg. 2 with
 * the inverse mapping, as docs/wetness.md reads them. */
#include "support/check.h"
#include "core/wet/clump.h"

#include <stdlib.h>
#include <string.h>

static void clump_profile_is_zero_at_first_layer_and_one_at_tip(void)
{
    const float ws[3] = {0.0f, 1.0f, 0.5f};
    const unsigned ns[4] = {2, 4, 16, 64};
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 4; b++) {
            float N = (float)ns[b];
            CHECK_NEAR(pelt__clump_profile(1.0f / N, ws[a], N), 0.0, 1e-6);
            CHECK_NEAR(pelt__clump_profile(1.0f, ws[a], N), 1.0, 1e-6);
        }
}

static void clump_profile_is_monotone_in_height(void)
{
    for (int wi = 0; wi <= 4; wi++) {
        float w = 0.25f * (float)wi, N = 16.0f, prev = -1.0f;
        for (int n = 0; n < 16; n++) {
            float f = pelt__clump_profile((1.0f + (float)n) / N, w, N);
            CHECK(f >= prev);
            CHECK(f >= 0.0f && f <= 1.0f);
            prev = f;
        }
    }
}

static void clump_profile_w0_is_rescaled_linear_and_w1_is_log(void)
{
    /* N = 4, n = 1: h = 0.5; h' = (0.5 - 0.25) / 0.75 = 1/3;
     * 1 + ln 0.5 / ln 4 = 1 - 1/2 = 1/2. */
    CHECK_NEAR(pelt__clump_profile(0.5f, 0.0f, 4.0f), 1.0 / 3.0, 1e-6);
    CHECK_NEAR(pelt__clump_profile(0.5f, 1.0f, 4.0f), 0.5, 1e-6);
    CHECK_NEAR(pelt__clump_profile(0.5f, 0.5f, 4.0f), 0.5 / 3.0 + 0.25, 1e-6);
    /* The log profile rises faster low down: fur bends in toward the clump
     * along its length (Fig. 9 c, d). */
    CHECK(pelt__clump_profile(0.25f, 1.0f, 16.0f) > pelt__clump_profile(0.25f, 0.0f, 16.0f));
}

static void clump_profile_single_layer_is_one_and_bad_h_is_zero(void)
{
    CHECK(pelt__clump_profile(1.0f, 0.0f, 1.0f) == 1.0f);
    CHECK(pelt__clump_profile(1.0f, 1.0f, 1.0f) == 1.0f);
    CHECK(pelt__clump_profile(0.0f, 1.0f, 16.0f) == 0.0f);
    CHECK(pelt__clump_profile(-1.0f, 0.0f, 16.0f) == 0.0f);
}

static void clump_texel_matches_gl_nearest(void)
{
    float mask[4 * 4 * 4];
    for (int i = 0; i < 16; i++) mask[i * 4] = (float)i; /* R = index */
    struct { float u, v; int x, y; } cases[] = {
        {0.0f, 0.0f, 0, 0},   {0.2499f, 0.0f, 0, 0}, {0.25f, 0.0f, 1, 0},
        {0.99f, 0.5f, 3, 2},  {1.0f, 1.0f, 3, 3},    {-0.3f, 7.0f, 0, 3},
        {1e30f, -1e30f, 3, 0}, {0.5f, 0.74f, 2, 2},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        float uv[2] = {cases[k].u, cases[k].v};
        const float *t = pelt__clump_texel(mask, 4, 4, uv);
        CHECK(t[0] == (float)(cases[k].y * 4 + cases[k].x));
    }
}

/* A width x width mask holding one disc-shaped clump (centre c, radius r,
 * wetness rho) and dry elsewhere. */
static float *disc_mask(unsigned width, float cx, float cy, float r, float rho)
{
    float *m = calloc((size_t)width * width * 4, sizeof(float));
    for (unsigned y = 0; y < width; y++)
        for (unsigned x = 0; x < width; x++) {
            float u = (x + 0.5f) / width, v = (y + 0.5f) / width;
            if (hypotf(u - cx, v - cy) > r) continue;
            float *t = m + ((size_t)y * width + x) * 4;
            t[0] = cx;
            t[1] = cy;
            t[2] = r;
            t[3] = rho;
        }
    return m;
}

static void clump_dry_texel_keeps_p_undisplaced(void)
{
    float *m = disc_mask(16, 0.5f, 0.5f, 0.2f, 1.0f);
    float p[2] = {0.05f, 0.05f}, q[2] = {-1, -1};
    CHECK(pelt__clump_lookup(m, 16, 16, p, 1.0f, 0.0f, 16.0f, 1.0f, q) == PELT__CLUMP_KEEP);
    CHECK(q[0] == p[0] && q[1] == p[1]);
    free(m);
}

static void clump_displaced_root_is_hand_computed(void)
{
    /* Whole mask wet, c = (0.5, 0.5), r = 1. At the tip (f = 1) with
     * s = 0.5, rho = 1: pull 0.5, q = c + (p - c) / 0.5. */
    float *m = disc_mask(8, 0.5f, 0.5f, 1.0f, 1.0f);
    float p[2] = {0.6f, 0.45f}, q[2];
    CHECK(pelt__clump_lookup(m, 8, 8, p, 1.0f, 0.0f, 16.0f, 0.5f, q) == PELT__CLUMP_DISPLACED);
    CHECK_NEAR(q[0], 0.7, 1e-6);
    CHECK_NEAR(q[1], 0.4, 1e-6);
    /* rho = 0.5 halves the pull: 1 / (1 - 0.25). */
    float *h = disc_mask(8, 0.5f, 0.5f, 1.0f, 0.5f);
    CHECK(pelt__clump_lookup(h, 8, 8, p, 1.0f, 0.0f, 16.0f, 0.5f, q) == PELT__CLUMP_DISPLACED);
    CHECK_NEAR(q[0], 0.5 + 0.1 / 0.75, 1e-6);
    free(m);
    free(h);
}

static void clump_first_layer_is_not_displaced(void)
{
    float *m = disc_mask(8, 0.5f, 0.5f, 1.0f, 1.0f);
    float p[2] = {0.6f, 0.45f}, q[2];
    CHECK(pelt__clump_lookup(m, 8, 8, p, 1.0f / 16.0f, 1.0f, 16.0f, 1.0f, q) ==
          PELT__CLUMP_DISPLACED);
    CHECK_NEAR(q[0], 0.6, 1e-6);
    CHECK_NEAR(q[1], 0.45, 1e-6);
    free(m);
}

static void clump_pull_is_capped_below_one(void)
{
    float *m = disc_mask(8, 0.5f, 0.5f, 1.0f, 1.0f);
    float p[2] = {0.51f, 0.5f}, q[2];
    CHECK(pelt__clump_lookup(m, 8, 8, p, 1.0f, 0.0f, 16.0f, 1.0f, q) == PELT__CLUMP_DISPLACED);
    CHECK_NEAR(q[0], 0.5 + 0.01 / (1.0 - PELT__CLUMP_MAX_PULL), 1e-5);
    /* Negative tightness never pushes roots inward. */
    CHECK(pelt__clump_lookup(m, 8, 8, p, 1.0f, 0.0f, 16.0f, -3.0f, q) == PELT__CLUMP_DISPLACED);
    CHECK(q[0] == p[0]);
    free(m);
}

static void clump_texel_of_another_clump_is_discarded(void)
{
    /* Texel (8,8) says its clump is centred at (0.1, 0.1) with radius 0.05:
     * the fragment at p is outside that clump. */
    float *m = disc_mask(16, 0.5f, 0.5f, 0.3f, 1.0f);
    float *t = m + ((size_t)8 * 16 + 8) * 4;
    t[0] = 0.1f;
    t[1] = 0.1f;
    t[2] = 0.05f;
    float p[2] = {0.53f, 0.53f}, q[2];
    CHECK(pelt__clump_lookup(m, 16, 16, p, 0.5f, 0.0f, 16.0f, 1.0f, q) == PELT__CLUMP_DISCARD);
    free(m);
}

static void clump_root_in_dry_fur_is_discarded(void)
{
    /* Disc r = 0.25; p 0.2 from the centre at the tip with pull 0.5 maps to
     * a root 0.4 away: dry. */
    float *m = disc_mask(32, 0.5f, 0.5f, 0.25f, 1.0f);
    float p[2] = {0.7f, 0.5f}, q[2];
    CHECK(pelt__clump_lookup(m, 32, 32, p, 1.0f, 0.0f, 16.0f, 0.5f, q) == PELT__CLUMP_DISCARD);
    CHECK_NEAR(q[0], 0.9, 1e-5);
    /* Low in the fur the root stays inside the clump. */
    CHECK(pelt__clump_lookup(m, 32, 32, p, 2.0f / 16.0f, 0.0f, 16.0f, 0.5f, q) ==
          PELT__CLUMP_DISPLACED);
    free(m);
}

/* A tuft's coverage is raised by its bundle's density only where the
 * squeezed read averages its hairs: none where a pixel spans at most 2
 * texels, the full squeeze from 4, never beyond it, and more the coarser
 * the level. */
static void bundle_density_counts_where_the_read_averages(void)
{
    const float k = 0.3f;
    CHECK(pelt__clump_bundle_squeeze(k, -2.0f) == 1.0f);
    CHECK(pelt__clump_bundle_squeeze(k, PELT__CLUMP_RESOLVED_LOD) == 1.0f);
    CHECK(fabsf(pelt__clump_bundle_squeeze(k, PELT__CLUMP_RESOLVED_LOD + 1.0f) - k) < 1e-6f);
    CHECK(fabsf(pelt__clump_bundle_squeeze(k, 9.0f) - k) < 1e-6f);
    float prev = 2.0f;
    for (int i = 0; i <= 10; i++) {
        float b = pelt__clump_bundle_squeeze(k, PELT__CLUMP_RESOLVED_LOD + 0.1f * (float)i);
        CHECK(b <= prev && b >= k && b <= 1.0f);
        prev = b;
    }
    /* So a resolved tuft keeps the texture's coverage, an averaged one is
     * as opaque as its bundle. */
    CHECK(pelt__clump_coverage(0.3f, pelt__clump_bundle_squeeze(k, 0.0f)) == 0.3f);
    CHECK(pelt__clump_coverage(0.3f, pelt__clump_bundle_squeeze(k, 3.0f)) > 0.6f);
}

/* Sub shells: where a tuft gathers its hairs (just above its base, the
 * log term of Eq. 5's profile), a layer's wet shells are drawn as k sub
 * shells, so that a hair at a tuft's rim moves at most PELT__CLUMP_SUB_PX
 * pixels from one drawn shell to the next; elsewhere, and where the tuft
 * is small on screen, one shell a layer. */
static void sub_shells_follow_the_tufts_sweep(void)
{
    const float N = 32.0f, w = 0.5f;
    CHECK(pelt__clump_sub_shells(0.5f, 0.53f, w, N, 0.0f) == 1); /* no pull */
    unsigned totals[3] = {0, 0, 0}, most = 0;
    const float sweeps[3] = {2.0f, 30.0f, 120.0f}; /* pixels over the whole profile */
    for (int j = 0; j < 3; j++) {
        unsigned prev = PELT__CLUMP_SUB_MAX + 1;
        for (int n = 0; n < 32; n++) {
            float hb = (float)n / N, h = (1.0f + (float)n) / N;
            unsigned k = pelt__clump_sub_shells(hb, h, w, N, sweeps[j]);
            CHECK(k >= 1 && k <= PELT__CLUMP_SUB_MAX);
            if (h <= PELT__CLUMP_BASE) CHECK(k == 1); /* the roots stay spread */
            float px = sweeps[j] * (pelt__clump_tuft_profile(h, w, N) - pelt__clump_tuft_profile(hb, w, N));
            CHECK(px / (float)k <= PELT__CLUMP_SUB_PX * 1.0001f || k == PELT__CLUMP_SUB_MAX);
            if (k > 1) CHECK(px / (float)(k - 1) > PELT__CLUMP_SUB_PX); /* no more than it takes */
            if (hb >= PELT__CLUMP_BASE) {
                CHECK(k <= prev); /* the tuft gathers fastest at its base */
                prev = k;
            }
            totals[j] += k;
            most = k > most ? k : most;
        }
        CHECK(pelt__clump_sub_shells(0.99f, 1.0f, w, N, sweeps[j]) == 1); /* near the tip, one */
    }
    printf("  shells drawn for 32 layers, a tuft's rim swept 2, 30, 120 px: %u, %u, %u (most %u a layer)\n", totals[0],
           totals[1], totals[2], most);
    CHECK(totals[0] == 32);                       /* small on screen: none */
    CHECK(totals[1] > 32 && totals[1] < totals[2]); /* more as the tuft grows on screen */
    CHECK(most == PELT__CLUMP_SUB_MAX);

    /* The k sub shells stand evenly below the layer, the last on it, and
     * over one another cover what the layer covers. */
    for (float k = 1.0f; k <= 6.0f; k += 1.0f) {
        for (float part = 0.0f; part < k; part += 1.0f) {
            float l = pelt__sub_shell_layer(10.0f, part, k, 2.0f);
            CHECK(l > 8.0f && l <= 10.0f);
            CHECK(fabsf(l - (8.0f + 2.0f * (part + 1.0f) / k)) < 1e-5f);
        }
        for (float a = 0.0f; a <= 1.0f; a += 0.125f) {
            float b = pelt__sub_shell_alpha(a, k);
            CHECK(b <= a + 1e-6f);
            CHECK(fabsf(1.0f - powf(1.0f - b, k) - a) < 1e-5f);
        }
    }
}

static void clump_coverage_thins_toward_the_tips(void)
{
    /* Share of a clump's fragments not discarded, per layer: it must fall
     * from nearly 1 at the root as the clump tightens toward its tip. */
    const unsigned W = 64;
    float *m = disc_mask(W, 0.5f, 0.5f, 0.3f, 1.0f);
    float prev = 2.0f, first = 0.0f, last = 0.0f;
    for (int n = 0; n < 16; n++) {
        float h = (1.0f + n) / 16.0f;
        int kept = 0, inside = 0;
        for (unsigned y = 0; y < 200; y++)
            for (unsigned x = 0; x < 200; x++) {
                float p[2] = {(x + 0.5f) / 200.0f, (y + 0.5f) / 200.0f}, q[2];
                const float *t = pelt__clump_texel(m, W, W, p);
                if (t[3] == 0.0f) continue;
                inside++;
                if (pelt__clump_lookup(m, W, W, p, h, 0.5f, 16.0f, 0.8f, q) !=
                    PELT__CLUMP_DISCARD)
                    kept++;
            }
        float share = (float)kept / (float)inside;
        CHECK(share <= prev);
        prev = share;
        if (n == 0) first = share;
        last = share;
    }
    /* Only fragments in rim texels whose centre is inside but which lie
     * outside r are dropped at the root. */
    CHECK(first > 0.95f);
    CHECK(last < 0.5f);
    free(m);
}

/* Tufts lean (docs/wetness.md): the radius's tag moves it by under 2^-15
 * and picks the lean; 256 keys give leans spread over the square, each
 * within amount r; and the lookup inverts the forward map of a leaning
 * tuft: the hair rooted at q, pulled towards c + lean, is seen at p, and
 * p samples q. */
static void clump_lean_tags_the_radius_and_inverts(void)
{
    float sum[2] = {0.0f, 0.0f}, spread[2] = {0.0f, 0.0f};
    for (uint32_t key = 0; key < 256; key++) {
        float r = pelt__clump_tag(0.1f, key);
        CHECK(fabsf(r - 0.1f) < 0.1f / 32768.0f);
        float t[4] = {0.5f, 0.5f, r, 1.0f}, lean[2];
        pelt__clump_lean(t, 0.5f, lean);
        for (int k = 0; k < 2; k++) {
            CHECK(fabsf(lean[k]) <= 0.5f * r * 1.0001f);
            sum[k] += lean[k];
            spread[k] += fabsf(lean[k]);
        }
        float none[2];
        pelt__clump_lean(t, 0.0f, none);
        CHECK(none[0] == 0.0f && none[1] == 0.0f);
    }
    printf("  mean lean (%.4f, %.4f), mean |lean| (%.4f, %.4f) of r 0.1\n", sum[0] / 256, sum[1] / 256,
           spread[0] / 256, spread[1] / 256);
    CHECK(fabsf(sum[0] / 256) < 0.01f && fabsf(sum[1] / 256) < 0.01f);
    CHECK(spread[0] / 256 > 0.015f && spread[1] / 256 > 0.015f);

    const unsigned W = 64;
    float *m = disc_mask(W, 0.5f, 0.5f, 0.3f, 1.0f);
    const float lean[2] = {0.06f, -0.04f};
    int checked = 0;
    for (int n = 4; n < 16; n += 3) {
        float h = (1.0f + n) / 16.0f, s = 0.8f;
        float pull = s * pelt__clump_tuft_profile(h, 0.5f, 16.0f);
        for (int i = 0; i < 50; i++) {
            float root[2] = {0.5f + 0.2f * cosf(0.7f * i) * (i % 7) / 7.0f, 0.5f + 0.2f * sinf(0.7f * i) * (i % 5) / 5.0f};
            float p[2], q[2];
            for (int k = 0; k < 2; k++) p[k] = 0.5f + (root[k] - 0.5f) * (1.0f - pull) + pull * lean[k];
            if (hypotf(p[0] - 0.5f, p[1] - 0.5f) > 0.28f) continue; /* keep p inside the clump */
            CHECK(pelt__clump_lookup_lean(m, W, W, p, h, 0.5f, 16.0f, s, lean, q) == PELT__CLUMP_DISPLACED);
            CHECK_NEAR(q[0], root[0], 1e-5);
            CHECK_NEAR(q[1], root[1], 1e-5);
            checked++;
        }
    }
    CHECK(checked > 100);
    free(m);
}

/* Ringlets (docs/method.md): three levels (full, half, no curl) 20 slices
 * apart; the wetness picks the two around 1 - rho and the weight between. */
static void ringlet_levels_follow_the_wetness(void)
{
    float o[3];
    pelt__ringlet_levels(0.0f, 3.0f, 20.0f, o); /* dry: the full curl */
    CHECK(o[0] == 0.0f && o[1] == 20.0f && o[2] == 0.0f);
    pelt__ringlet_levels(0.25f, 3.0f, 20.0f, o); /* 3/4 of the curl: halfway to half */
    CHECK(o[0] == 0.0f && o[1] == 20.0f);
    CHECK_NEAR(o[2], 0.5, 1e-6);
    pelt__ringlet_levels(0.75f, 3.0f, 20.0f, o); /* 1/4: between half and none */
    CHECK(o[0] == 20.0f && o[1] == 40.0f);
    CHECK_NEAR(o[2], 0.5, 1e-6);
    pelt__ringlet_levels(1.0f, 3.0f, 20.0f, o); /* soaked: no curl */
    CHECK(o[0] == 20.0f && o[1] == 40.0f && o[2] == 1.0f);
    pelt__ringlet_levels(7.0f, 3.0f, 20.0f, o); /* clamped */
    CHECK(o[1] == 40.0f && o[2] == 1.0f);
    pelt__ringlet_levels(0.5f, 1.0f, 20.0f, o); /* one level: no ringlets */
    CHECK(o[0] == 0.0f && o[1] == 0.0f && o[2] == 0.0f);
}

/* A fin shows a tuft's pull by its share along the fin's edge, in fin
 * texture units: along the edge it is |d| / |dir|, across it nothing, and
 * an edge without uv length (a seam) moves nothing. */
static void clump_fin_shift_is_the_pull_along_the_edge(void)
{
    const float dir[2] = {0.006f, 0.008f}; /* |dir| = 0.01 uv per fin unit */
    const float along[2] = {0.03f, 0.04f}, across[2] = {-0.04f, 0.03f}, none[2] = {0.0f, 0.0f};
    CHECK_NEAR(pelt__clump_fin_shift(along, dir), 5.0f, 1e-4f);
    CHECK_NEAR(pelt__clump_fin_shift((const float[2]){-0.03f, -0.04f}, dir), -5.0f, 1e-4f);
    CHECK_NEAR(pelt__clump_fin_shift(across, dir), 0.0f, 1e-5f);
    CHECK_NEAR(pelt__clump_fin_shift(along, none), 0.0f, 0.0f);
}

int main(void)
{
    RUN(clump_profile_is_zero_at_first_layer_and_one_at_tip);
    RUN(clump_profile_is_monotone_in_height);
    RUN(clump_profile_w0_is_rescaled_linear_and_w1_is_log);
    RUN(clump_profile_single_layer_is_one_and_bad_h_is_zero);
    RUN(clump_texel_matches_gl_nearest);
    RUN(clump_dry_texel_keeps_p_undisplaced);
    RUN(clump_displaced_root_is_hand_computed);
    RUN(clump_first_layer_is_not_displaced);
    RUN(clump_pull_is_capped_below_one);
    RUN(clump_texel_of_another_clump_is_discarded);
    RUN(clump_root_in_dry_fur_is_discarded);
    RUN(clump_coverage_thins_toward_the_tips);
    RUN(bundle_density_counts_where_the_read_averages);
    RUN(sub_shells_follow_the_tufts_sweep);
    RUN(ringlet_levels_follow_the_wetness);
    RUN(clump_fin_shift_is_the_pull_along_the_edge);
    RUN(clump_lean_tags_the_radius_and_inverts);
    return check_summary();
}
