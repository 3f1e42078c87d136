/* Level of detail (core/fur/lod.h): the simplified shell geometry, the
 * shell levels of Lengyel et al. 2001 §2.4 and their composites, and the
 * fins a view can show. */
#include "support/check.h"

#include "core/base/vec.h"
#include "core/fur/fins.h"
#include "core/fur/fur_gpu.h"
#include "core/fur/lod.h"
#include "core/fur/vertex_strand.h"
#include "core/wet/clump.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const pelt_allocator heap = {0};

static void lod_levels_shrink_and_their_error_grows(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.35f, 96, 48, &m, NULL) == PELT_OK);
    if (!m) return;
    pelt__lod_chain c;
    CHECK(pelt__lod_chain_build(m, 1, 0, &heap, &c, NULL) == PELT_OK);
    CHECK(c.count >= 3);
    CHECK(c.levels[0].triangle_count == pelt_mesh_get_data(m).triangle_count);
    CHECK(c.levels[0].error == 0.0f);
    /* The torus is closed once its seam is welded, and wound CCW. */
    CHECK(c.closed);
    CHECK(c.winding == 1);
    CHECK_NEAR(c.radius, 1.35, 0.01);
    for (unsigned k = 1; k < c.count; k++) {
        CHECK(c.levels[k].triangle_count * 10 <= c.levels[k - 1].triangle_count * 8);
        CHECK(c.levels[k].error >= c.levels[k - 1].error);
        CHECK(c.levels[k].fin_count < c.levels[k - 1].fin_count);
        /* Same vertices: every index is one of the mesh's. */
        size_t bad = 0;
        for (size_t i = 0; i < 3 * c.levels[k].triangle_count; i++)
            bad += c.levels[k].indices[i] >= pelt_mesh_get_data(m).vertex_count;
        CHECK(bad == 0);
    }
    /* The error grows slower than the triangles shrink at first: level 1
     * strays less than a hundredth of the radius. */
    CHECK(c.levels[1].error < 0.01f * c.radius);
    /* Picking: no pixels per unit, or a huge zoom, is level 0; far away
     * the coarsest level; the bound holds for the level picked. */
    CHECK(pelt__lod_pick(&c, 0.0f, 0.5f, INFINITY) == 0);
    CHECK(pelt__lod_pick(&c, INFINITY, 0.5f, INFINITY) == 0);
    CHECK(pelt__lod_pick(&c, 1e-6f, 0.5f, INFINITY) == c.count - 1);
    unsigned k = pelt__lod_pick(&c, 300.0f, 0.5f, INFINITY);
    CHECK(c.levels[k].error * 300.0f <= 0.5f);
    if (k + 1 < c.count) CHECK(c.levels[k + 1].error * 300.0f > 0.5f);
    /* The mean edge bounds the level too; edges grow level by level. */
    CHECK(c.levels[1].edge > 1.5f * c.levels[0].edge);
    unsigned e = pelt__lod_pick(&c, 1e-6f, 0.5f, 1.2f * c.levels[1].edge * 1e-6f);
    CHECK(e == 1);
    pelt__lod_chain_free(&c, &heap);

    /* Level of detail off: level 0 only. */
    CHECK(pelt__lod_chain_build(m, 1, 1, &heap, &c, NULL) == PELT_OK);
    CHECK(c.count == 1);
    pelt__lod_chain_free(&c, &heap);
    pelt_mesh_destroy(m);
}

/* The fins' level (pelt__lod_pick_fins): as coarse as the error on screen
 * allows while the mean edge stays within the fin texture's slab, never
 * finer than the shells' level. */
static void lod_fins_take_a_coarser_level_within_a_slab(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.35f, 96, 48, &m, NULL) == PELT_OK);
    if (!m) return;
    pelt__lod_chain c;
    CHECK(pelt__lod_chain_build(m, 1, 0, &heap, &c, NULL) == PELT_OK);
    CHECK(c.count >= 4);
    /* Far away every error passes: the slab alone stops the fins. */
    CHECK(pelt__lod_pick_fins(&c, 0, 1e-6f, 0.5f, 1.01f * c.levels[2].edge) == 2);
    CHECK(pelt__lod_pick_fins(&c, 0, 1e-6f, 0.5f, 0.99f * c.levels[1].edge) == 0);
    /* Never finer than the shells, whatever the slab. */
    CHECK(pelt__lod_pick_fins(&c, 3, 1e-6f, 0.5f, 0.5f * c.levels[0].edge) == 3);
    /* Close, the error bounds them as it bounds the shells. */
    CHECK(pelt__lod_pick_fins(&c, 0, 300.0f, 0.5f, INFINITY) == pelt__lod_pick(&c, 300.0f, 0.5f, INFINITY));
    unsigned k = pelt__lod_pick_fins(&c, 0, 300.0f, 0.5f, INFINITY);
    CHECK(c.levels[k].error * 300.0f <= 0.5f);
    /* No measure of the view: the shells' level. */
    CHECK(pelt__lod_pick_fins(&c, 1, 0.0f, 0.5f, INFINITY) == 1);
    CHECK(pelt__lod_pick_fins(&c, 1, INFINITY, 0.5f, INFINITY) == 1);
    pelt__lod_chain_free(&c, &heap);
    pelt_mesh_destroy(m);
}

static void lod_an_open_square_is_not_closed(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_square(2.0f, 16, &m, NULL) == PELT_OK);
    if (!m) return;
    pelt__lod_chain c;
    CHECK(pelt__lod_chain_build(m, 1, 0, &heap, &c, NULL) == PELT_OK);
    CHECK(!c.closed);
    pelt__lod_chain_free(&c, &heap);
    pelt_mesh_destroy(m);
}

static void lod_pixels_per_unit_follow_the_distance(void)
{
    float near_ppu = pelt__lod_pixels_per_unit(2.0f, 600.0f, 1.0f, 5.0f, 1.0f);
    CHECK_NEAR(near_ppu, 2.0 * 300.0 / 4.0, 1e-3);
    CHECK_NEAR(pelt__lod_pixels_per_unit(2.0f, 600.0f, 1.0f, 9.0f, 1.0f), near_ppu / 2.0, 1e-3);
    CHECK(isinf(pelt__lod_pixels_per_unit(2.0f, 600.0f, 1.0f, 0.5f, 1.0f))); /* inside */
}

static void lod_shell_levels_halve_to_one_shell(void)
{
    CHECK(pelt__lod_shell_levels(16) == 5); /* 16 8 4 2 1 */
    CHECK(pelt__lod_shell_count(16, 2) == 4);
    CHECK(pelt__lod_shell_levels(1) == 1);
    CHECK(pelt__lod_shell_levels(10) == 5); /* 10 5 3 2 1 */
    CHECK(pelt__lod_shell_count(10, 2) == 3);
    /* Anchored at the outermost shell: every level reaches h = 1. */
    for (unsigned n = 1; n <= 20; n++)
        for (unsigned k = 0; k < pelt__lod_shell_levels(n); k++) {
            unsigned c = pelt__lod_shell_count(n, k);
            CHECK(pelt__lod_shell_layer(n, k, c - 1) == n - 1);
            CHECK(pelt__lod_shell_layer(n, k, 0) < (1u << k));
        }
    /* The draw's instances are the level's shells, inner first. */
    for (unsigned k = 0; k < pelt__lod_shell_levels(16); k++) {
        float shells[4], next[2], slices[3], alpha;
        unsigned count;
        pelt__lod_shell_uniforms(16, k, 0.0f, 0, shells, next, &count);
        CHECK(count == pelt__lod_shell_count(16, k));
        for (unsigned i = 0; i < count; i++) {
            float layer = pelt__lod_shell_instance(shells, next, 16.0f, (float)i, slices, &alpha);
            CHECK(layer == (float)pelt__lod_shell_layer(16, k, i));
            CHECK(slices[0] == (float)(pelt__lod_shell_base(16, k) + i) && alpha == 1.0f);
        }
    }
    CHECK(pelt__lod_shell_base(16, 0) == 1);
    CHECK(pelt__lod_shell_base(16, 1) == 17);
    CHECK(pelt__lod_shell_base(16, 2) == 25);
    CHECK(pelt__lod_shell_extra_slices(16) == 8 + 4 + 2 + 1);
}

/* The choice: spacing at least shell_pixels; the upper half octave blends
 * towards the next level; the blend is continuous across the boundary. */
/* The fur texture's level: a round footprint reads the level of its size,
 * as a texture read would; a grazing one, 8 texels across the view and 1
 * along it, the level of its long side over 2 (a texture read: 8 texels,
 * level 3, the hairs blurred along the short side too); past 2 to 1 the
 * short side sets the level (max_aniso 2 here; the shells' default is
 * PELT__FUR_TEXTURE_ANISO, lod.texture_aniso). How far it sharpens follows
 * the shells' spacing on screen: fully where they lie within 0.7 px of
 * each other, not at all from 1.4 px apart, where they show as rows. */
static void lod_fur_texture_keeps_the_short_side_sharp(void)
{
    const float tile = 256.0f, texel = 1.0f / tile, k = 2.0f;
    CHECK(PELT__FUR_TEXTURE_ANISO == 4.0f); /* lod.texture_aniso's default */
    const float round_x[2] = {2.0f * texel, 0.0f}, round_y[2] = {0.0f, 2.0f * texel};
    CHECK_NEAR(pelt__lod_fur_texture(round_x, round_y, tile, k), 1.0f, 1e-5);
    const float long_x[2] = {8.0f * texel * 0.6f, 8.0f * texel * 0.8f}, short_y[2] = {-texel * 0.8f, texel * 0.6f};
    CHECK_NEAR(pelt__lod_fur_texture(long_x, short_y, tile, k), 2.0f, 1e-5);
    CHECK_NEAR(pelt__lod_fur_texture(short_y, long_x, tile, k), 2.0f, 1e-5); /* either way */
    CHECK_NEAR(pelt__lod_fur_texture(long_x, short_y, tile, 1.0f), 3.0f, 1e-5); /* a texture read's level */
    const float wide_y[2] = {0.0f, 6.0f * texel};
    CHECK_NEAR(pelt__lod_fur_texture(long_x, wide_y, tile, k), log2f(6.0f), 1e-5); /* 6 > 8 / 2 */
    const float tiny[2] = {0.25f * texel, 0.0f}, none[2] = {0.0f, 0.0f};
    CHECK_NEAR(pelt__lod_fur_texture(tiny, tiny, tile, k), -2.0f, 1e-5); /* magnified */
    CHECK(isfinite(pelt__lod_fur_texture(none, none, tile, k)));
    /* The shells read half a level finer where the footprint is round (the
     * nearest mip level, rounded down, not up), less as it grows longer,
     * and as it was from twice as long as wide: there the read is already
     * finer than the pixel across it, and sharper its rows would crawl. */
    CHECK(PELT__FUR_TEXTURE_SHARPEN > 0.0f && PELT__FUR_TEXTURE_SHARPEN < 1.0f);
    CHECK_NEAR(pelt__lod_shell_fur_texture(round_x, round_y, tile, k), 0.5f, 1e-5);
    CHECK_NEAR(pelt__lod_shell_fur_texture(round_x, round_y, tile, 1.0f), 0.5f, 1e-5); /* either max_aniso */
    CHECK_NEAR(pelt__lod_shell_fur_texture(long_x, short_y, tile, k), 2.0f, 1e-5);
    CHECK_NEAR(pelt__lod_shell_fur_texture(long_x, wide_y, tile, k), log2f(6.0f) - 0.5f * (2.0f - 8.0f / 6.0f), 1e-5);
    float was = -1.0f; /* the level never falls as the footprint widens */
    for (int i = 1; i <= 16; i++) {
        const float w[2] = {0.0f, 0.5f * (float)i * texel};
        float lod = pelt__lod_shell_fur_texture(long_x, w, tile, k);
        CHECK(lod >= was - 1e-6f && lod <= pelt__lod_fur_texture(long_x, w, tile, k) + 1e-6f);
        was = lod;
    }

    const float most = PELT__FUR_TEXTURE_ANISO;
    CHECK(pelt__lod_fur_texture_aniso(0.6f, 0.0f, most) == most);       /* edge-on, 0.6 px apart */
    CHECK(pelt__lod_fur_texture_aniso(1.4f, 0.0f, most) == 1.0f);       /* 1.4 px apart: rows */
    CHECK_NEAR(pelt__lod_fur_texture_aniso(1.05f, 0.0f, most), 1.0f + 0.5f * (most - 1.0f), 1e-5);
    CHECK(pelt__lod_fur_texture_aniso(3.0f, 0.99f, most) == most);      /* face-on: 0.42 px */
    CHECK(pelt__lod_fur_texture_aniso(0.5f, 0.0f, 1.0f) == 1.0f);       /* 1: the long side's level */
    CHECK(pelt__lod_fur_texture_aniso(0.5f, 0.0f, 16.0f) == 16.0f);
    /* The fins: the long side's texels to a pixel where the short side is a
     * texel or less, a texture read's own level from 2 texels. */
    const float fin_long[2] = {0.0f, 6.0f}, fin_close[2] = {0.5f, 0.0f}, fin_mid[2] = {1.5f, 0.0f},
                fin_far[2] = {3.0f, 0.0f};
    CHECK(pelt__lod_fin_texture_aniso(fin_close, fin_long) == PELT__FIN_TEXTURE_ANISO);
    CHECK(pelt__lod_fin_texture_aniso(fin_long, fin_close) == PELT__FIN_TEXTURE_ANISO); /* either way */
    CHECK_NEAR(pelt__lod_fin_texture_aniso(fin_mid, fin_long), 1.0f + 0.5f * (PELT__FIN_TEXTURE_ANISO - 1.0f), 1e-5);
    CHECK(pelt__lod_fin_texture_aniso(fin_far, fin_long) == 1.0f);
    CHECK_NEAR(pelt__lod_fur_texture(fin_close, fin_long, 1.0f, PELT__FIN_TEXTURE_ANISO), log2f(6.0f / 4.0f), 1e-5);

    float last = most + 1.0f;
    for (int i = 0; i <= 60; i++) {
        float a = pelt__lod_fur_texture_aniso(0.05f * (float)i, 0.0f, most);
        CHECK(a <= last && a >= 1.0f && a <= most);
        last = a;
    }
}

/* Fetches along the footprint (lod.texture_taps): a round footprint and one
 * within max_aniso of round take one fetch at the shells' own level; an
 * 8-to-1 one at max_aniso 2 takes 4, each at the short side's level, so
 * the hairs stay a texel wide across the view; capped at 2 fetches each
 * covers half (level 1); allowed 1 it is the one-fetch read. More fetches
 * never read coarser. */
static void lod_fur_texture_taps_split_a_long_footprint(void)
{
    const float tile = 256.0f, texel = 1.0f / tile, k = 2.0f;
    const float round_x[2] = {2.0f * texel, 0.0f}, round_y[2] = {0.0f, 2.0f * texel};
    const float long_x[2] = {8.0f * texel * 0.6f, 8.0f * texel * 0.8f}, short_y[2] = {-texel * 0.8f, texel * 0.6f};
    const float near_x[2] = {1.9f * texel, 0.0f}, near_y[2] = {0.0f, texel};
    float lod = -99.0f;
    CHECK(pelt__lod_fur_texture_taps(round_x, round_y, tile, k, 4, &lod) == 1);
    CHECK_NEAR(lod, pelt__lod_shell_fur_texture(round_x, round_y, tile, k), 1e-6);
    CHECK(pelt__lod_fur_texture_taps(near_x, near_y, tile, k, 4, &lod) == 1);
    CHECK_NEAR(lod, pelt__lod_shell_fur_texture(near_x, near_y, tile, k), 1e-6);
    CHECK(pelt__lod_fur_texture_taps(long_x, short_y, tile, k, 4, &lod) == 4);
    CHECK_NEAR(lod, 0.0f, 1e-5);
    CHECK(pelt__lod_fur_texture_taps(short_y, long_x, tile, k, 4, &lod) == 4); /* either way */
    CHECK(pelt__lod_fur_texture_taps(long_x, short_y, tile, k, 8, &lod) == 4); /* no more than it needs */
    CHECK(pelt__lod_fur_texture_taps(long_x, short_y, tile, k, 2, &lod) == 2);
    CHECK_NEAR(lod, 1.0f, 1e-5);
    CHECK(pelt__lod_fur_texture_taps(long_x, short_y, tile, k, 1, &lod) == 1);
    CHECK_NEAR(lod, pelt__lod_shell_fur_texture(long_x, short_y, tile, k), 1e-6);
    CHECK(pelt__lod_fur_texture_taps(long_x, short_y, tile, 1.0f, 8, &lod) == 8); /* rows: 1 texel a pixel */
    CHECK_NEAR(lod, 0.0f, 1e-5);
    for (unsigned m = 1; m < 8; m++) {
        float a, b;
        pelt__lod_fur_texture_taps(long_x, short_y, tile, k, m, &a);
        pelt__lod_fur_texture_taps(long_x, short_y, tile, k, m + 1, &b);
        CHECK(b <= a + 1e-6f);
    }
}

/* A hair of radius r texels in the fur texture (the disc's coverage ramps
 * over a texel, as furtex.c splats it), read with linear filtering at m
 * pixels a texel and seen through k shells that show the same cross-section
 * (along the hair): its width on screen, in texels. */
static float hair_width_seen(float r, float m, int k, bool edge)
{
    float texel[32];
    for (int t = 0; t < 32; t++) texel[t] = fminf(fmaxf(r + 0.5f - fabsf((float)t + 0.5f - 16.3f), 0.0f), 1.0f);
    const float dx[2] = {1.0f / (m * 256.0f), 0.0f}, dy[2] = {0.0f, 1.0f / (m * 256.0f)};
    float gain = pelt__lod_fur_edge_gain(dx, dy, 256.0f), sum = 0.0f;
    int pixels = (int)(32.0f * m);
    for (int p = 0; p < pixels; p++) {
        float u = ((float)p + 0.5f) / m - 0.5f, i = floorf(u), f = u - i;
        int i0 = (int)fmaxf(i, 0.0f), i1 = (int)fminf(i + 1.0f, 31.0f);
        float a = texel[i0] * (1.0f - f) + texel[i1] * f;
        float rgba[4] = {0.5f * a, 0.25f * a, 0.75f * a, a};
        if (edge) {
            pelt__lod_fur_edge(rgba, gain);
            if (rgba[3] > 0.0f) CHECK_NEAR(rgba[0] / rgba[3], 0.5f, 1e-5); /* the colour is kept */
        }
        sum += 1.0f - powf(1.0f - rgba[3], (float)k);
    }
    return sum / m;
}

/* Seen close, the edge gain keeps a hair its width: a texel spanning 4
 * pixels spreads the hair's edge over 4, and 8 shells showing the same
 * edge composite it to a hair 40% wider than it is; steepened to a pixel it
 * stays within 10%. Read at a pixel a texel or less, nothing changes. */
static void lod_fur_edge_keeps_a_hair_its_width(void)
{
    const float texel = 1.0f / 256.0f;
    const float close_x[2] = {0.25f * texel, 0.0f}, close_y[2] = {0.0f, 0.25f * texel};
    CHECK_NEAR(pelt__lod_fur_edge_gain(close_x, close_y, 256.0f), 4.0f, 1e-4);
    const float far_y[2] = {0.0f, 2.0f * texel}, none[2] = {0.0f, 0.0f};
    CHECK(pelt__lod_fur_edge_gain(close_x, far_y, 256.0f) == 1.0f); /* the longer side is minified */
    CHECK(pelt__lod_fur_edge_gain(far_y, far_y, 256.0f) == 1.0f);
    CHECK(isfinite(pelt__lod_fur_edge_gain(none, none, 256.0f)));

    for (int i = 0; i <= 20; i++) { /* gain 1: as it was */
        float a = 0.05f * (float)i, rgba[4] = {a, a, a, a};
        pelt__lod_fur_edge(rgba, 1.0f);
        CHECK_NEAR(rgba[3], a, 1e-6);
    }
    float half[4] = {0.1f, 0.2f, 0.3f, 0.5f}, in[4] = {0.3f, 0.3f, 0.3f, 0.6f}, out[4] = {0.4f, 0.4f, 0.4f, 0.4f};
    pelt__lod_fur_edge(half, 4.0f);
    pelt__lod_fur_edge(in, 4.0f);
    pelt__lod_fur_edge(out, 4.0f);
    CHECK_NEAR(half[3], 0.5f, 1e-6); /* the edge stays where it is */
    CHECK_NEAR(in[3], 0.9f, 1e-5);
    CHECK_NEAR(out[3], 0.1f, 1e-5);
    CHECK_NEAR(in[0] / in[3], 0.5f, 1e-5);

    const float r = 1.6f, width = 2.0f * r; /* the default strand radius */
    float plain = hair_width_seen(r, 4.0f, 8, false), sharp = hair_width_seen(r, 4.0f, 8, true);
    printf("  a %.1f-texel hair at 4 px a texel through 8 shells: %.2f texels wide read plain, %.2f steepened\n",
           width, plain, sharp);
    CHECK(plain > 1.3f * width);
    CHECK(fabsf(sharp - width) < 0.1f * width);
    CHECK(fabsf(hair_width_seen(r, 4.0f, 1, true) - width) < 0.05f * width); /* one shell: its width kept */
    CHECK_NEAR(hair_width_seen(r, 1.0f, 8, true), hair_width_seen(r, 1.0f, 8, false), 1e-4); /* a pixel a texel */
}

/* The shells are planes along n: a ray meets a hair in as many of them as
 * its sideways drift against the hair from one plane to the next allows.
 * Shearing hair and ray alike (a combed hair seen by an eye that moves
 * with the comb) changes nothing; upright hair keeps |T.V|; a hair
 * leaning 60 degrees seen 40 degrees off the normal across its lean
 * drifts sideways by sqrt(tan60^2 + tan40^2) = 1.92 a unit of height,
 * where the angle between the two (|T.V| = 0.38) says 2.41. */
static void lod_shell_stack_cos_follows_the_stack(void)
{
    const float n[3] = {0.0f, 0.0f, 1.0f};
    for (int i = 0; i <= 8; i++) {
        float b = 0.15f * (float)i, sheared[2] = {0.2f * (float)i, -0.1f * (float)i};
        float t[3] = {sinf(b), 0.0f, cosf(b)}, v[3] = {0.0f, sinf(0.7f), -cosf(0.7f)};
        /* The same hair and ray, both sheared along the plane. */
        float ts[3] = {t[0] + sheared[0] * t[2], t[1] + sheared[1] * t[2], t[2]};
        float vs[3] = {v[0] + sheared[0] * v[2], v[1] + sheared[1] * v[2], v[2]};
        float tl = sqrtf(ts[0] * ts[0] + ts[1] * ts[1] + ts[2] * ts[2]);
        float vl = sqrtf(vs[0] * vs[0] + vs[1] * vs[1] + vs[2] * vs[2]);
        for (int k = 0; k < 3; k++) ts[k] /= tl, vs[k] /= vl;
        CHECK_NEAR(pelt__lod_shell_stack_cos(ts, vs, n), pelt__lod_shell_stack_cos(t, v, n), 1e-5);
    }
    /* Upright hair: |T.V|. */
    const float up[3] = {0.0f, 0.0f, 1.0f};
    for (int i = 0; i <= 10; i++) {
        float e = 0.15f * (float)i, v[3] = {sinf(e), 0.0f, -cosf(e)};
        CHECK_NEAR(pelt__lod_shell_stack_cos(up, v, n), cosf(e), 1e-6);
    }
    /* A hair leaning 60 degrees along x, the ray 40 degrees off -n along y. */
    const float lean = 1.0471976f, off = 0.6981317f;
    float t[3] = {sinf(lean), 0.0f, cosf(lean)}, v[3] = {0.0f, sinf(off), -cosf(off)};
    float drift = sqrtf(tanf(lean) * tanf(lean) + tanf(off) * tanf(off));
    CHECK_NEAR(pelt__lod_shell_stack_cos(t, v, n), 1.0f / sqrtf(1.0f + drift * drift), 1e-5);
    CHECK(pelt__lod_shell_stack_cos(t, v, n) > fabsf(t[0] * v[0] + t[1] * v[1] + t[2] * v[2]) + 0.05f);
    /* Along the hair: the ray never leaves it; in the plane: at once. */
    float along[3] = {-t[0], -t[1], -t[2]}, flat[3] = {1.0f, 0.0f, 0.0f};
    CHECK_NEAR(pelt__lod_shell_stack_cos(t, along, n), 1.0f, 1e-6);
    CHECK(pelt__lod_shell_stack_cos(flat, v, n) == 0.0f);
}

/* The shells' over-count of a hair seen along its length: a ray that
 * runs along a hair crosses it in k shells, each drawing its share so
 * that together they draw it once. Seen from the side (the ray across the
 * hair) every shell shows another part of the scene: 1. Along the hair,
 * as many as its width spans layer spacings, up to the cap; fewer as the
 * view tilts off the hair, and fewer the more the hair drifts from shell
 * to shell (a curl). */
static void lod_shell_overcount_counts_a_hair_once(void)
{
    float span = pelt__lod_shell_hair_span(0.004f, 0.8f, 0.0f, 32.0f, 0.08f); /* 1.6 spacings at the root */
    CHECK_NEAR(span, 1.6f, 1e-5);
    CHECK_NEAR(pelt__lod_shell_hair_span(0.004f, 0.8f, 1.0f, 32.0f, 0.08f), 0.2f * 1.6f, 1e-5); /* tapered */
    /* The cap: 3 shells up to 32 layers, 3/32 of the fur's height beyond. */
    const float cap = pelt__lod_shell_overcount_cap(32.0f);
    CHECK(cap == PELT__SHELL_OVERCOUNT_MAX && pelt__lod_shell_overcount_cap(16.0f) == PELT__SHELL_OVERCOUNT_MAX);
    CHECK_NEAR(pelt__lod_shell_overcount_cap(128.0f), 4.0f * PELT__SHELL_OVERCOUNT_MAX, 1e-5);
    /* Along a hair at 128 layers its width spans 4x the shells: 4x the count. */
    CHECK_NEAR(pelt__lod_shell_overcount(4.0f * span, 1.0f, 0.0f, 1.0f, pelt__lod_shell_overcount_cap(128.0f)),
               4.0f * pelt__lod_shell_overcount(span, 1.0f, 0.0f, 1.0f, cap), 1e-5);
    CHECK(pelt__lod_shell_overcount(span, 0.0f, 0.0f, 1.0f, cap) == 1.0f);  /* side-on */
    CHECK_NEAR(pelt__lod_shell_overcount(span, 1.0f, 0.0f, 1.0f, cap), cap, 1e-6); /* along it: capped */
    float prev = cap + 1.0f;
    for (int i = 0; i <= 10; i++) { /* tilting off the hair: fewer */
        float k = pelt__lod_shell_overcount(4.0f, cosf(0.15f * (float)i), 0.0f, 1.0f, cap);
        CHECK(k <= prev && k >= 1.0f && k <= cap);
        prev = k;
    }
    CHECK(pelt__lod_shell_overcount(4.0f, cosf(1.2f), 0.0f, 1.0f, cap) < cap); /* between the bounds */
    CHECK(pelt__lod_shell_overcount(4.0f, cosf(1.2f), 0.0f, 1.0f, cap) > 1.0f);
    /* A curl carries the hair off the ray: many small curls leave one shell. */
    float drift = pelt__lod_shell_hair_drift(0.0f, 0.0f, 0.5f, 0.15f, 0.5f, 6.2831853f * 4.0f);
    CHECK(pelt__lod_shell_overcount(span, 1.0f, drift, 1.0f, cap) == 1.0f);
    CHECK(pelt__lod_shell_hair_drift(0.0f, 30.0f, 0.5f, 0.1f, 0.0f, 0.0f) == 0.0f); /* straight hair */
    CHECK(pelt__lod_shell_hair_drift(0.01f, 30.0f, 0.8f, 0.1f, 0.0f, 0.0f) >
          pelt__lod_shell_hair_drift(0.01f, 30.0f, 0.2f, 0.1f, 0.0f, 0.0f)); /* the helix widens */
    /* The k shells' shares composite to the hair's coverage. */
    for (int i = 0; i <= 10; i++) {
        float a = 0.1f * (float)i, k = 2.5f, share = pelt__lod_shell_overcount_alpha(a, k);
        CHECK_NEAR(1.0f - powf(1.0f - share, k), a, 1e-5);
        CHECK(share <= a + 1e-6f);
    }
    CHECK_NEAR(pelt__lod_shell_overcount_alpha(0.6f, 1.0f), 0.6f, 1e-6);
}

/* Seen edge-on, a shell may stand for more than one crossing of a hair
 * (lod.edge_depth): the least count is 1/depth where N.V is 0, rises
 * smoothly and reaches 1 at PELT__SHELL_EDGE_REACH, the same either side;
 * at depth 1 it is exactly 1 everywhere (the default draws as before). A
 * hair seen side-on then counts 1/depth: its share of coverage is the
 * coverage of depth crossings. */
static void lod_shell_edge_least_thickens_the_edge_on_shells(void)
{
    CHECK(PELT__SHELL_EDGE_REACH > 0.0f && PELT__SHELL_EDGE_REACH < 1.0f);
    for (int i = 0; i <= 20; i++) CHECK(pelt__lod_shell_edge_least(-1.0f + 0.1f * (float)i, 1.0f) == 1.0f);
    CHECK_NEAR(pelt__lod_shell_edge_least(0.0f, 16.0f), 1.0f / 16.0f, 1e-6);
    CHECK(pelt__lod_shell_edge_least(PELT__SHELL_EDGE_REACH, 16.0f) == 1.0f);
    CHECK(pelt__lod_shell_edge_least(0.95f, 16.0f) == 1.0f);
    CHECK_NEAR(pelt__lod_shell_edge_least(-0.3f, 16.0f), pelt__lod_shell_edge_least(0.3f, 16.0f), 1e-7);
    float prev = 0.0f;
    for (int i = 0; i <= 14; i++) {
        float least = pelt__lod_shell_edge_least(0.05f * (float)i, 16.0f);
        CHECK(least >= prev && least >= 1.0f / 16.0f && least <= 1.0f);
        prev = least;
    }
    const float cap = pelt__lod_shell_overcount_cap(32.0f);
    CHECK_NEAR(pelt__lod_shell_overcount(1.6f, 0.0f, 0.0f, 1.0f / 16.0f, cap), 1.0f / 16.0f, 1e-6); /* side-on */
    CHECK(pelt__lod_shell_overcount(1.6f, 0.0f, 0.0f, 1.0f, cap) == 1.0f); /* least 1: as it was */
    CHECK_NEAR(pelt__lod_shell_overcount(1.6f, 1.0f, 0.0f, 0.25f, cap), cap, 1e-6); /* along it: as before */
    /* The fragment's share, exponent 1/k (pelt__lod_coverage_share): a
     * count of 1/16 composites 16 crossings of a hair of coverage 0.1. */
    const float a = 0.1f, k = pelt__lod_shell_overcount(1.6f, 0.0f, 0.0f, 1.0f / 16.0f, cap);
    CHECK_NEAR(pelt__lod_coverage_share(pelt__lod_coverage_log(a), 1.0f / k), 1.0f - powf(1.0f - a, 16.0f), 1e-4);
    CHECK(pelt__lod_coverage_share(pelt__lod_coverage_log(a), 1.0f / k) > 0.8f);
}

/* A shell fragment's coverage composed in one power: the log of the
 * complement times the three exponents gives what the tuft's squeeze, the
 * overcount's share and the sub shells' share give one after the other
 * (in double precision; the three in float lose up to 5e-4 where the
 * coverage nears 1, the one power less), and each alone what its own
 * function gives. */
static void lod_coverage_powers_compose(void)
{
    double worst_once = 0.0, worst_chained = 0.0;
    for (int i = 0; i <= 20; i++)
        for (int j = 0; j <= 8; j++) {
            float a = 0.05f * (float)i; /* 0 .. 1, both ends included */
            float squeeze = 0.1f + 0.1125f * (float)j, k = 1.0f + 0.25f * (float)j, sub = 1.0f + (float)(j % 3);
            double exact = 1.0 - pow(1.0 - (double)a, 1.0 / ((double)squeeze * (double)k * (double)sub));
            float chained = pelt__sub_shell_alpha(pelt__lod_shell_overcount_alpha(pelt__clump_coverage(a, squeeze), k), sub);
            float once = pelt__lod_coverage_share(pelt__lod_coverage_log(a), 1.0f / squeeze / k / sub);
            worst_once = fmax(worst_once, fabs(exact - (double)once));
            worst_chained = fmax(worst_chained, fabs(exact - (double)chained));
            CHECK_NEAR(pelt__lod_coverage_share(pelt__lod_coverage_log(a), 1.0f / k), pelt__lod_shell_overcount_alpha(a, k),
                       2e-6);
            CHECK_NEAR(pelt__lod_coverage_share(pelt__lod_coverage_log(a), 1.0f / squeeze), pelt__clump_coverage(a, squeeze),
                       2e-6);
        }
    printf("  worst |one power - exact| = %.3g, |three - exact| = %.3g\n", worst_once, worst_chained);
    CHECK(worst_once < 1e-5);
    CHECK(worst_once <= worst_chained);
    /* The ends: no hair stays none, an opaque hair opaque. */
    CHECK(pelt__lod_coverage_share(pelt__lod_coverage_log(0.0f), 0.3f) == 0.0f);
    CHECK(pelt__lod_coverage_share(pelt__lod_coverage_log(1.0f), 0.3f) == 1.0f);
    /* The shells' cut (coverage below 0.05) read on the log. */
    CHECK_NEAR(PELT__COVERAGE_CLEAR_LOG, log2(0.95), 1e-7);
    CHECK(pelt__lod_coverage_log(0.049f) > PELT__COVERAGE_CLEAR_LOG && pelt__lod_coverage_log(0.051f) < PELT__COVERAGE_CLEAR_LOG);
}

/* A leaning hair's sideways move per layer: none standing up, tan of its
 * lean, whatever the lengths of t and n, bounded lying flat; and what it
 * is for: face-on, the budget that fades half the shells of upright hair
 * keeps those of hair combed 60 degrees. */
static void lod_lean_drift_is_the_tangent_of_the_lean(void)
{
    const float n[3] = {0.0f, 0.0f, 1.0f}, n2[3] = {0.0f, 0.0f, 3.0f};
    const float up[3] = {0.0f, 0.0f, 0.5f}, down[3] = {0.0f, 0.0f, -2.0f};
    CHECK(pelt__lod_shell_lean_drift(up, n) == 0.0f);
    CHECK(pelt__lod_shell_lean_drift(down, n) == 0.0f);
    for (int deg = 5; deg <= 85; deg += 10) {
        float a = (float)deg * 3.14159265f / 180.0f;
        float t[3] = {2.0f * sinf(a) * 0.6f, 2.0f * sinf(a) * 0.8f, 2.0f * cosf(a)};
        CHECK_NEAR(pelt__lod_shell_lean_drift(t, n), tanf(a), 1e-4 * (1.0 + tanf(a)));
        CHECK_NEAR(pelt__lod_shell_lean_drift(t, n2), tanf(a), 1e-4 * (1.0 + tanf(a)));
    }
    const float flat[3] = {1.0f, 0.0f, 0.0f}, zero[3] = {0.0f, 0.0f, 0.0f};
    CHECK_NEAR(pelt__lod_shell_lean_drift(flat, n), 1.0f / PELT__SHELL_LEAN_MIN_COS, 1e-3);
    CHECK(pelt__lod_shell_lean_drift(zero, n) == 0.0f);
    const float combed[3] = {sinf(1.0471976f), 0.0f, cosf(1.0471976f)};
    float lean = pelt__lod_shell_lean_drift(combed, n);
    CHECK(pelt__lod_view_blend(0.6f, 0.95f, 0.5f, 0.0f) == 1.0f); /* upright: every other shell */
    CHECK(pelt__lod_view_blend(0.6f, 0.95f, 0.5f, lean) == 0.0f); /* combed: every shell */
}

/* The view's budget: edge-on every shell, face-on half of them; the
 * weight grows as the fur turns towards the eye. An even shell's texel at
 * weight 1 is the texel composited over itself (what it stands for). */
static void lod_view_blend_follows_the_view(void)
{
    CHECK(pelt__lod_view_blend(0.6f, 0.0f, 0.5f, 0.0f) == 0.0f);   /* edge-on, 0.6 px > 0.5 */
    CHECK(pelt__lod_view_blend(0.6f, 0.95f, 0.5f, 0.0f) == 1.0f);  /* face-on: 0.19 px */
    CHECK(pelt__lod_view_blend(0.6f, 1.0f, 0.5f, 0.0f) == 1.0f);   /* straight on: no spacing at all */
    CHECK(pelt__lod_view_blend(0.6f, -0.95f, 0.5f, 0.0f) == 1.0f); /* from behind, the same */
    float last = 0.0f;
    for (int k = 0; k <= 100; k++) {
        float w = pelt__lod_view_blend(0.6f, k / 100.0f, 0.5f, 0.0f);
        CHECK(w >= last - 1e-6f && w >= 0.0f && w <= 1.0f);
        last = w;
    }
    /* A curled hair moving sideways from shell to shell keeps them face-on:
     * 0.6 px apart side-on drifting 1.5 spacings a layer is 0.9 px. */
    CHECK(pelt__lod_view_blend(0.6f, 1.0f, 0.5f, 1.5f) == 0.0f);
    CHECK(pelt__lod_view_blend(0.6f, 0.95f, 0.5f, 0.3f) > 0.0f); /* a slight drift: some */
    CHECK(pelt__lod_view_blend(0.6f, 0.95f, 0.5f, 0.3f) < 1.0f);
    /* Exactly between: spacing 0.6 sin = 0.5 / sqrt(2) gives a weight of one half. */
    float s = 0.5f / sqrtf(2.0f) / 0.6f;
    CHECK_NEAR(pelt__lod_view_blend(0.6f, sqrtf(1.0f - s * s), 0.5f, 0.0f), 0.5f, 1e-4);
    float t[4] = {0.2f, 0.1f, 0.05f, 0.4f};
    pelt__lod_view_texel(1.0f, t); /* 0.4 over 0.4: 0.4 + 0.4 * 0.6 */
    CHECK_NEAR(t[3], 0.64f, 1e-6);
    CHECK_NEAR(t[0], 0.2f * 1.6f, 1e-6);
    float u[4] = {0.2f, 0.1f, 0.05f, 0.4f};
    pelt__lod_view_texel(0.0f, u);
    CHECK(u[3] == 0.4f && u[0] == 0.2f);
}

static void lod_shell_choice_blends_without_a_jump(void)
{
    unsigned level;
    float blend;
    pelt__lod_shell_choice(16, 64.0f, 1.0f, &level, &blend);
    CHECK(level == 0 && blend == 0.0f);
    pelt__lod_shell_choice(16, 16.0f, 1.0f, &level, &blend);
    CHECK(level == 0 && blend == 0.0f);
    pelt__lod_shell_choice(16, 8.0f, 1.0f, &level, &blend); /* spacing 0.5 px: 8 shells */
    CHECK(level == 1 && blend == 0.0f);
    pelt__lod_shell_choice(16, 0.01f, 1.0f, &level, &blend);
    CHECK(level == 4 && blend == 0.0f);
    pelt__lod_shell_choice(16, NAN, 1.0f, &level, &blend);
    CHECK(level == 0 && blend == 0.0f);
    /* Shells drawn, counting a blending-out shell by its opacity, fall
     * smoothly as the fur shrinks. */
    double previous = 16.0;
    for (float px = 16.0f; px > 0.5f; px *= 0.98f) {
        pelt__lod_shell_choice(16, px, 1.0f, &level, &blend);
        double shells = pelt__lod_shell_count(16, level) -
                        blend * (pelt__lod_shell_count(16, level) - pelt__lod_shell_count(16, level + 1));
        CHECK(shells <= previous + 1e-6);
        CHECK(previous - shells < 0.5);
        previous = shells;
    }
}

/* The coarser shell is the pair composited with "over", premultiplied. */
static void lod_shell_composite_is_over(void)
{
    enum { SIZE = 2, N = 4 };
    uint8_t volume[(N + 1) * SIZE * SIZE * 4];
    for (size_t i = 0; i < sizeof volume; i++) volume[i] = (uint8_t)((i * 37u) % 200u);
    for (size_t s = 0; s <= N; s++) /* premultiplied: colour <= alpha */
        for (size_t t = 0; t < SIZE * SIZE; t++) {
            uint8_t *p = volume + (s * SIZE * SIZE + t) * 4;
            p[3] = (uint8_t)(100 + 30 * s);
            for (int c = 0; c < 3; c++) p[c] = (uint8_t)(p[c] % (p[3] + 1));
        }
    uint8_t extra[(2 + 1) * SIZE * SIZE * 4];
    CHECK(pelt__lod_shell_extra_slices(N) == 3);
    pelt__lod_shell_composite(volume, SIZE, N, extra);
    /* Level 1, inner shell (layer 1): slice 2 over slice 1. */
    for (int c = 0; c < 4; c++) {
        double outer = volume[(2 * SIZE * SIZE) * 4 + c], inner = volume[(1 * SIZE * SIZE) * 4 + c];
        double a = volume[(2 * SIZE * SIZE) * 4 + 3] / 255.0;
        CHECK_NEAR(extra[c], outer + (1.0 - a) * inner, 1.0);
    }
    /* Level 2's one shell covers at least what any of its shells covers. */
    uint8_t top = extra[(2 * SIZE * SIZE) * 4 + 3];
    for (unsigned s = 1; s <= N; s++) CHECK(top >= volume[(s * SIZE * SIZE) * 4 + 3]);
}

/* One frame of fins (core/fur/fin_frame.c): exactly the fins whose fade
 * (pelt__fin_fade) reaches 0.05, with that fade; each vertex's strand
 * starts at the vertex, rises along its normal at rest and is as long as
 * the fur; ends index the level's fin vertices. */
/* Fins closer than their slab fade by the ratio; wider spacing keeps the
 * texture's own opacity; degenerate input draws nothing odd. */
static void lod_fins_closer_than_their_slab_fade(void)
{
    CHECK(pelt__fin_spacing_opacity(0.5f, 0.25f) == 1.0f);
    CHECK(pelt__fin_spacing_opacity(0.25f, 0.25f) == 1.0f);
    CHECK(fabsf(pelt__fin_spacing_opacity(0.1f, 0.25f) - 0.4f) < 1e-6f);
    CHECK(pelt__fin_spacing_opacity(0.0f, 0.25f) == 0.0f);
    CHECK(pelt__fin_spacing_opacity(0.1f, 0.0f) == 1.0f);
    float last = 0.0f;
    for (int k = 0; k <= 40; k++) {
        float o = pelt__fin_spacing_opacity(0.01f * (float)k, 0.25f);
        CHECK(o >= last && o <= 1.0f);
        last = o;
    }
}

/* The outline's hairs of a frame's fins (pelt__outline_hairs): a fin
 * that faces the eye's ray (its fade 0) carries none; the others as many
 * as their edge in tiles times the hairs a tile holds, rounded up, at
 * most PELT__OUTLINE_HAIRS_MAX; each names its fin's two vertices, its
 * number and the fin's fade; the table's room is kept. The fade is the
 * eye's ray's, not the view direction's. */
static void lod_outline_hairs_follow_the_fins_near_the_outline(void)
{
    enum { STRIDE = 8 };
    /* Vertices on the x axis (0, 0.05, 2.05), normals +y (a fin facing
     * the eye on +z: its fade 1), and the first two again with normals +z
     * (a fin seen edge-on: fade 0). */
    const float xs[5] = {0.0f, 0.05f, 2.05f, 0.0f, 0.05f};
    float v[5 * STRIDE] = {0};
    for (int i = 0; i < 5; i++) {
        v[i * STRIDE] = xs[i];
        v[i * STRIDE + (i < 3 ? 5 : 6)] = 1.0f;
        v[i * STRIDE + 7] = 1.0f; /* groomed density: every hair */
    }
    const uint32_t ends[3][2] = {{3, 4}, {0, 1}, {1, 2}};
    uint32_t fins[12] = {0};
    for (int i = 0; i < 3; i++) fins[4 * i] = ends[i][0], fins[4 * i + 1] = ends[i][1];
    /* 2 tiles a unit, 48 hairs a tile: the short fin 0.1 tile, 4.8 -> 5. */
    pelt__outline_frame f = {v, STRIDE, 4, {0.025f, 0.0f, 100.0f}, 2.0f, 0.01f, 48.0f, PELT__OUTLINE_LEAST_FADE};
    uint32_t out[4 * 64];
    size_t n = pelt__outline_hairs(fins, 3, &f, out, 64);
    CHECK(n == 5 + PELT__OUTLINE_HAIRS_MAX);
    for (size_t h = 0; h < n && h < 64; h++) {
        bool first = h < 5;
        CHECK(out[4 * h] == (first ? 0u : 1u) && out[4 * h + 1] == (first ? 1u : 2u));
        CHECK(out[4 * h + 2] == (uint32_t)(first ? h : h - 5));
        float fade;
        memcpy(&fade, &out[4 * h + 3], sizeof fade);
        CHECK(fade > 0.99f && fade <= 1.0f);
    }
    CHECK(pelt__outline_hairs(fins, 3, &f, out, 7) == 7);
    /* Seen from the side (the eye on +y), the first fin faces the ray. */
    f.eye[1] = 100.0f, f.eye[2] = 0.0f;
    CHECK(pelt__outline_hairs(fins, 3, &f, out, 64) == 5);
    f.hairs = 0.0f;
    CHECK(pelt__outline_hairs(fins, 3, &f, out, 64) == 0);
    /* Closer than the slab, a fin fades by the ratio (0.1 of 0.2 tiles). */
    pelt_vec3 a = v3(0, 0, 0), b = v3(0.05f, 0, 0), n_up = v3(0, 1, 0);
    CHECK(fabsf(pelt__outline_fade(a, b, n_up, n_up, v3(0.025f, 0, 100), 2.0f, 0.2f) - 0.5f) < 1e-3f);
}

/* A fin fainter than 1 shows only the hairs whose threshold lies below its
 * fade (pelt__outline_alpha): the list leaves the others out, so the
 * vertex stage does no work for them, and the picture is the same. A fin
 * at fade 0.75 (its normal's cosine to the eye's ray 0.875): of its 32
 * hairs, the listed ones are exactly those with alpha above 0. */
static void lod_outline_hairs_leave_out_those_the_fade_hides(void)
{
    enum { STRIDE = 8 };
    const float c = 0.875f, s = 0.48412292f;
    float v[2 * STRIDE] = {0};
    v[STRIDE] = 2.05f;
    for (int i = 0; i < 2; i++) v[i * STRIDE + 5] = c, v[i * STRIDE + 6] = s, v[i * STRIDE + 7] = 1.0f;
    const uint32_t fins[4] = {0, 1, 0, 0};
    pelt__outline_frame f = {v, STRIDE, 4, {1.025f, 0.0f, 100.0f}, 2.0f, 0.01f, 48.0f, PELT__OUTLINE_LEAST_FADE};
    uint32_t out[4 * 64];
    size_t n = pelt__outline_hairs(fins, 1, &f, out, 64);
    float fade = pelt__outline_fade(v3(0, 0, 0), v3(2.05f, 0, 0), v3(0, c, s), v3(0, c, s), v3(1.025f, 0, 100), 2.0f,
                                    0.01f);
    CHECK(fabsf(fade - 0.75f) < 1e-3f);
    size_t shown = 0, listed_shown = 0;
    for (uint32_t k = 0; k < PELT__OUTLINE_HAIRS_MAX; k++) {
        float show = pelt__outline_random(pelt__outline_seed(0, 1, k), 3u);
        bool visible = pelt__outline_alpha((float)k, (float)PELT__OUTLINE_HAIRS_MAX, fade, show) > 0.0f;
        bool listed = false;
        for (size_t h = 0; h < n && h < 64; h++) listed = listed || out[4 * h + 2] == k;
        shown += visible;
        listed_shown += visible && listed;
        CHECK(listed == visible);
    }
    printf("  a fin at fade %.3f: %zu of its %d hairs listed, %zu show\n", fade, n, PELT__OUTLINE_HAIRS_MAX, shown);
    CHECK(n == shown && listed_shown == shown);
    CHECK(n < PELT__OUTLINE_HAIRS_MAX && n > PELT__OUTLINE_HAIRS_MAX / 2);
    /* Grooming thinned to 0.4 at a: the hairs whose draw 5 is above it go too. */
    v[7] = 0.4f;
    size_t thinned = pelt__outline_hairs(fins, 1, &f, out, 64), kept = 0;
    for (uint32_t k = 0; k < PELT__OUTLINE_HAIRS_MAX; k++) {
        uint32_t seed = pelt__outline_seed(0, 1, k);
        kept += fade > pelt__outline_random(seed, 3u) && !(pelt__outline_random(seed, 5u) > 0.4f);
    }
    printf("  groomed to 0.4: %zu listed, %zu kept\n", thinned, kept);
    CHECK(thinned == kept && thinned < n);
}

/* Where the view is known, a fin whose hair is out of the outline's reach
 * on screen (pelt__outline_share 0: at most PELT__OUTLINE_LOW_PX, at least
 * PELT__OUTLINE_NONE_PX) lists no hair: the vertex stage would give every
 * one of them alpha 0. Identity matrices on a 100 px viewport: a hair of
 * height y is 50 y px long; a model scaling by 2 doubles it. */
static void lod_outline_hairs_leave_out_fins_out_of_reach(void)
{
    enum { STRIDE = 16, TOP = 8 };
    float v[2 * STRIDE] = {0};
    v[STRIDE] = 0.5f;
    for (int i = 0; i < 2; i++) v[i * STRIDE + 5] = v[i * STRIDE + 7] = 1.0f; /* normals +y: the fin faces +z */
    const uint32_t fins[4] = {0, 1, 0, 0};
    static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    static const float twice[16] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1};
    pelt__outline_frame f = {v,   STRIDE,   4,           {0.25f, 0.0f, 100.0f}, 2.0f, 0.01f, 48.0f,
                             PELT__OUTLINE_LEAST_FADE, identity, identity, {100.0f, 100.0f}, TOP};
    uint32_t out[4 * 64];
    const float heights[5] = {0.05f, 0.079f, 0.2f, 0.64f, 0.66f}; /* 2.5, 3.95, 10, 32, 33 px */
    const bool listed[5] = {false, false, true, true, false};
    for (int i = 0; i < 5; i++) {
        v[TOP + 1] = v[STRIDE + TOP + 1] = heights[i];
        v[TOP] = 0.0f, v[STRIDE + TOP] = 0.5f;
        CHECK_NEAR(pelt__outline_hair_px(&f, v, v + STRIDE), 50.0f * heights[i], 1e-3);
        size_t n = pelt__outline_hairs(fins, 1, &f, out, 64);
        printf("  hair %.2f px on screen: %zu hairs listed\n", 50.0f * heights[i], n);
        CHECK(listed[i] ? n > 0 : n == 0);
    }
    f.model = twice; /* 2.5 px -> 5 px: within reach */
    v[TOP + 1] = v[STRIDE + TOP + 1] = 0.05f;
    CHECK(pelt__outline_hairs(fins, 1, &f, out, 64) > 0);
    f.view_proj = NULL; /* the view not known: every fin near the outline */
    v[TOP + 1] = v[STRIDE + TOP + 1] = 0.66f;
    CHECK(pelt__outline_hairs(fins, 1, &f, out, 64) > 0);
}

/* The rows of a fin frame: as few as follow the strands within row_error.
 * Straight strands at rest need one; a curled strand (bowed by about its
 * curl radius) needs more the smaller the error, never more than asked. */
static unsigned fin_rows_for(pelt_fur *fur, float row_error)
{
    pelt__fur_snapshot fs;
    pelt__fur_gpu_snapshot(fur, &fs);
    const pelt__lod_level *l = &fs.lod->levels[0];
    uint32_t *fins = malloc(l->fin_count * 4 * sizeof *fins);
    float *verts = malloc(l->fin_vertex_count * 4 * PELT__FIN_VERTEX_TEXELS * sizeof *verts);
    pelt__fin_frame_desc fd = {0, 3, row_error, {0.0f, 0.0f, -1.0f}, false};
    unsigned rows = 0;
    size_t dry = 0;
    if (fins && verts && pelt__fur_gpu_fin_frame(fur, &fd, fins, verts, &rows, &dry) == 0) rows = 0;
    free(fins);
    free(verts);
    return rows;
}

static void lod_fin_rows_follow_the_strands_bow(void)
{
    pelt_mesh *m = NULL;
    pelt_fur *straight = NULL, *curly = NULL;
    CHECK(pelt_mesh_sphere(1.0f, 16, 8, &m, NULL) == PELT_OK);
    if (!m) return;
    CHECK(pelt_fur_create(m, &(pelt_fur_desc){.look.texture_size = 16, .length = 0.1f}, &straight, NULL) == PELT_OK);
    CHECK(pelt_fur_create(m,
                          &(pelt_fur_desc){.look.texture_size = 16, .length = 0.1f, .look.curl_frequency = 6.2831853f,
                                           .look.curl_radius = 0.02f, .look.curl_phase = PELT_CURL_COHERENT},
                          &curly, NULL) == PELT_OK);
    if (straight && curly) {
        unsigned s_fine = fin_rows_for(straight, 1e-5f), s_coarse = fin_rows_for(straight, 1.0f);
        unsigned c_fine = fin_rows_for(curly, 1e-4f), c_mid = fin_rows_for(curly, 0.006f);
        unsigned c_coarse = fin_rows_for(curly, 1.0f), c_every = fin_rows_for(curly, 0.0f);
        printf("  rows: straight %u, %u; curled %u, %u, %u (error 0: %u)\n", s_fine, s_coarse, c_fine, c_mid,
               c_coarse, c_every);
        CHECK(s_fine == 1 && s_coarse == 1);
        CHECK(c_fine == 3 && c_coarse == 1 && c_every == 3);
        CHECK(c_mid >= c_coarse && c_mid <= c_fine);
    }
    pelt_fur_destroy(straight);
    pelt_fur_destroy(curly);
    pelt_mesh_destroy(m);
}

/* A unit sphere (32 x 16) with fur 0.1 long on a 16-texel texture; false,
 * with nothing left over, when either could not be made. */
static bool sphere_with_fur(pelt_mesh **m, pelt_fur **fur)
{
    CHECK(pelt_mesh_sphere(1.0f, 32, 16, m, NULL) == PELT_OK);
    CHECK(*m && pelt_fur_create(*m, &(pelt_fur_desc){.look.texture_size = 16, .length = 0.1f}, fur, NULL) == PELT_OK);
    if (*fur) return true;
    pelt_mesh_destroy(*m);
    return false;
}

static void lod_a_fin_frame_holds_the_fins_the_view_shows(void)
{
    pelt_mesh *m = NULL;
    pelt_fur *fur = NULL;
    if (!sphere_with_fur(&m, &fur)) return;
    pelt__fur_snapshot fs;
    pelt__fur_gpu_snapshot(fur, &fs);
    const pelt__lod_chain *c = fs.lod;
    const pelt__lod_level *l = &c->levels[0];
    uint32_t *fins = malloc(l->fin_count * 4 * sizeof *fins);
    float *verts = malloc(l->fin_vertex_count * 4 * PELT__FIN_VERTEX_TEXELS * sizeof *verts);
    const pelt_mesh_data d = pelt_mesh_get_data(m);
    pelt_vec3 view = v3_norm_or(v3(0.3f, -0.4f, -1.0f), v3(0, 0, -1));
    pelt__fin_frame_desc fd = {0, 3, 0.0f, {view.x, view.y, view.z}, false};
    unsigned rows = 0;
    size_t dry = 0, kept = fins && verts ? pelt__fur_gpu_fin_frame(fur, &fd, fins, verts, &rows, &dry) : 0;
    CHECK(kept == 0 || rows == 3); /* row_error 0: every row */
    CHECK(dry == kept);            /* no vertex_wet: every fin counts as dry */
    const pelt_fur_desc fdesc = pelt_fur_get_desc(fur);
    const float slab = fdesc.fins.density / (float)fdesc.look.texture_size;
    size_t shown = 0, bad_fade = 0, bad_end = 0;
    for (size_t i = 0, k = 0; i < l->fin_count; i++) {
        pelt_vec3 n = pelt__fin_normal(v3_load(d.positions + 3 * l->fins[i].a), v3_load(d.positions + 3 * l->fins[i].b),
                                       v3_load(d.normals + 3 * l->fins[i].a), v3_load(d.normals + 3 * l->fins[i].b));
        float edge = v3_len(v3_sub(v3_load(d.positions + 3 * l->fins[i].b), v3_load(d.positions + 3 * l->fins[i].a)));
        float fade = pelt__fin_fade(n, view);
        if (fade < PELT__FIN_CUT) continue; /* the view's fade alone decides */
        fade *= pelt__fin_spacing_opacity(edge * fdesc.look.tiling, slab);
        shown++;
        if (k < kept) {
            float got;
            memcpy(&got, &fins[4 * k + 3], sizeof got);
            bad_fade += fabsf(got - fade) > 1e-6f;
            bad_end += l->fin_vertices[fins[4 * k]] != l->fins[i].a || l->fin_vertices[fins[4 * k + 1]] != l->fins[i].b;
            k++;
        }
    }
    printf("  %zu of %zu fins shown\n", kept, l->fin_count);
    CHECK(kept == shown && kept > 0 && kept < l->fin_count);
    CHECK(bad_fade == 0 && bad_end == 0);
    size_t bad_root = 0, bad_tip = 0;
    for (size_t v = 0; v < l->fin_vertex_count && kept; v++) {
        const float *t = verts + v * 4 * PELT__FIN_VERTEX_TEXELS;
        pelt_vec3 p = v3_load(d.positions + 3 * l->fin_vertices[v]), n = v3_load(d.normals + 3 * l->fin_vertices[v]);
        bad_root += v3_len(v3_sub(v3_load(t), p)) > 1e-6f;
        /* At rest, no curl, no comb: the tip (h = 1, row 3) is p + L n. */
        bad_tip += v3_len(v3_sub(v3_load(t + 8 * 3), v3_mad(p, n, 0.1f))) > 1e-5f;
    }
    CHECK(bad_root == 0 && bad_tip == 0);

    /* Close up, with the shells in 2 sub shells a layer, the same fins at
     * half their opacity (the cut is the view's fade's alone). */
    uint32_t *half = malloc(l->fin_count * 4 * sizeof *half);
    if (half && kept) {
        pelt__fin_frame_desc hd = fd;
        hd.opacity = 0.5f;
        size_t hdry = 0, hkept = pelt__fur_gpu_fin_frame(fur, &hd, half, verts, &rows, &hdry);
        size_t bad_half = 0;
        for (size_t k = 0; k < hkept && hkept == kept; k++) {
            float a, b;
            memcpy(&a, &fins[4 * k + 3], sizeof a);
            memcpy(&b, &half[4 * k + 3], sizeof b);
            bad_half += fabsf(b - 0.5f * a) > 1e-6f || half[4 * k] != fins[4 * k] || half[4 * k + 1] != fins[4 * k + 1];
        }
        CHECK(hkept == kept && bad_half == 0);
    }
    free(half);

    /* Wet fins drawn apart: with the vertices of one side marked wet, the
     * same fins come out, those with both ends dry first, each part in
     * the order above. */
    uint8_t *vertex_wet = calloc(d.vertex_count, 1);
    uint32_t *split = malloc(l->fin_count * 4 * sizeof *split);
    if (vertex_wet && split && kept) {
        for (size_t v = 0; v < d.vertex_count; v++) vertex_wet[v] = d.positions[3 * v] > 0.3f;
        fd.vertex_wet = vertex_wet;
        size_t split_dry = 0, split_kept = pelt__fur_gpu_fin_frame(fur, &fd, split, verts, &rows, &split_dry);
        CHECK(split_kept == kept && split_dry > 0 && split_dry < kept);
        size_t at_dry = 0, at_wet = split_dry, misplaced = 0;
        for (size_t k = 0; k < kept; k++) {
            bool wet = vertex_wet[l->fin_vertices[fins[4 * k]]] || vertex_wet[l->fin_vertices[fins[4 * k + 1]]];
            size_t *at = wet ? &at_wet : &at_dry;
            misplaced += memcmp(split + 4 * *at, fins + 4 * k, 4 * sizeof *fins) != 0;
            (*at)++;
        }
        printf("  %zu of them dry, then %zu wet\n", split_dry, kept - split_dry);
        CHECK(misplaced == 0 && at_dry == split_dry && at_wet == kept);
    }
    free(vertex_wet), free(split);
    free(fins), free(verts);
    pelt_fur_destroy(fur);
    pelt_mesh_destroy(m);
}

/* Close up, a layer in sub shells (lod.sub_shells): none while the
 * shells stand within PELT__SUB_SHELL_PIXELS of each other, then as many
 * as bring them within it, at most the cap; 1 with the cap at 1 or a
 * spacing that is no number. Each sub shell's spacing stays within the
 * bound wherever the cap allows, and the count never falls as the
 * spacing grows. */
static void lod_sub_shells_close_the_rows(void)
{
    CHECK(pelt__lod_sub_shells(0.0f, 4) == 1);
    CHECK(pelt__lod_sub_shells(PELT__SUB_SHELL_PIXELS, 4) == 1);
    CHECK(pelt__lod_sub_shells(1.5f * PELT__SUB_SHELL_PIXELS, 4) == 2);
    CHECK(pelt__lod_sub_shells(2.5f * PELT__SUB_SHELL_PIXELS, 4) == 3);
    CHECK(pelt__lod_sub_shells(100.0f, 4) == 4);
    CHECK(pelt__lod_sub_shells(100.0f, 8) == 8);
    CHECK(pelt__lod_sub_shells(100.0f, 1) == 1);
    CHECK(pelt__lod_sub_shells(NAN, 4) == 1);
    CHECK(pelt__lod_sub_shells(INFINITY, 4) == 4);
    unsigned was = 1;
    for (int i = 0; i <= 200; i++) {
        float side = 0.05f * (float)i;
        unsigned k = pelt__lod_sub_shells(side, 8);
        CHECK(k >= was && k >= 1 && k <= 8);
        if (k < 8) CHECK(side / (float)k <= PELT__SUB_SHELL_PIXELS * (1.0f + 1e-5f));
        if (k > 1) CHECK(side / (float)(k - 1) > PELT__SUB_SHELL_PIXELS - 1e-5f); /* no more than it takes */
        was = k;
    }

    /* Per vertex: every sub shell where the layers stand 1.4 px apart or
     * more on screen, none from 0.35 of that down, smooth between; face-on
     * the spacing is foreshortened, a curl's drift counts whole. */
    const float px = PELT__SUB_SHELL_PIXELS;
    CHECK(pelt__lod_sub_shell_need(2.0f * px, 0.0f, 0.0f) == 1.0f); /* edge-on, twice apart */
    CHECK(pelt__lod_sub_shell_need(px, 0.0f, 0.0f) == 1.0f);
    CHECK(pelt__lod_sub_shell_need(0.35f * px, 0.0f, 0.0f) == 0.0f);
    CHECK(pelt__lod_sub_shell_need(0.3f * px, 0.0f, 0.0f) == 0.0f);
    CHECK_NEAR(pelt__lod_sub_shell_need(0.675f * px, 0.0f, 0.0f), 0.5f, 1e-5f);
    CHECK(pelt__lod_sub_shell_need(2.0f * px, 1.0f, 0.0f) == 0.0f);   /* face-on */
    CHECK(pelt__lod_sub_shell_need(2.0f * px, 1.0f, 0.5f) == 1.0f);   /* face-on, a curl drifting half a spacing */
    CHECK(pelt__lod_sub_shell_need(NAN, 0.0f, 0.0f) == 0.0f);
    float last = 0.0f;
    for (int i = 0; i <= 100; i++) { /* from face-on to edge-on: never fewer */
        float need = pelt__lod_sub_shell_need(2.0f * px, 1.0f - 0.01f * (float)i, 0.0f);
        CHECK(need >= last - 1e-6f);
        last = need;
    }
    /* The exponents of a layer's k sub shells add up to 1 at any need:
     * together they cover what the layer did. */
    for (int k = 1; k <= 6; k++)
        for (int j = 0; j <= 10; j++) {
            float need = 0.1f * (float)j, sum = 0.0f;
            for (int part = 0; part < k; part++) {
                float e = pelt__lod_sub_shell_exponent((float)part, (float)k, need);
                CHECK(e >= 0.0f && e <= 1.0f);
                sum += e;
            }
            CHECK_NEAR(sum, 1.0f, 1e-5f);
        }
    CHECK(pelt__lod_sub_shell_exponent(0.0f, 3.0f, 0.0f) == 0.0f); /* not needed: clipped */
    CHECK(pelt__lod_sub_shell_exponent(2.0f, 3.0f, 0.0f) == 1.0f); /* the layer's own takes it all */
    CHECK_NEAR(pelt__lod_sub_shell_exponent(1.0f, 3.0f, 1.0f), 1.0f / 3.0f, 1e-6f);
}

/* The angle between the level's normal interpolated where each left-out
 * vertex lies (its nearest point on the level, found by brute force) and
 * the vertex's own; `fitted`: the level's fitted normals. Returns the
 * mean, the 90th percentile in *p90. */
static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static float level_normal_error(const pelt_mesh *mesh, const pelt__lod_level *l, bool fitted, float *p90)
{
    const pelt_mesh_data m = pelt_mesh_get_data(mesh);
    const float *tan = pelt_mesh_tangents(mesh);
    bool *kept = calloc(m.vertex_count, sizeof *kept);
    float *errors = calloc(m.vertex_count, sizeof *errors);
    size_t count = 0;
    for (size_t i = 0; i < 3 * l->triangle_count; i++) kept[l->indices[i]] = true;
    for (size_t i = 0; i < m.vertex_count; i++) {
        if (kept[i]) continue;
        pelt_vec3 p = v3_load(m.positions + 3 * i), n = v3_load(m.normals + 3 * i);
        float best = INFINITY, at[3] = {0};
        size_t tri = 0;
        for (size_t t = 0; t < l->triangle_count; t++) {
            const uint32_t *v = l->indices + 3 * t;
            float side = 0.0f;
            for (int k = 0; k < 3; k++) side += v3_dot(v3_load(m.normals + 3 * (size_t)v[k]), n);
            if (side <= 0.0f) continue;
            /* The plane's nearest point, its barycentrics clamped: close
             * enough on a smooth surface to pick the triangle. */
            pelt_vec3 a = v3_load(m.positions + 3 * (size_t)v[0]);
            pelt_vec3 e0 = v3_sub(v3_load(m.positions + 3 * (size_t)v[1]), a);
            pelt_vec3 e1 = v3_sub(v3_load(m.positions + 3 * (size_t)v[2]), a), d = v3_sub(p, a);
            float d00 = v3_dot(e0, e0), d01 = v3_dot(e0, e1), d11 = v3_dot(e1, e1);
            float d20 = v3_dot(d, e0), d21 = v3_dot(d, e1), den = d00 * d11 - d01 * d01;
            float wv = clampf((d11 * d20 - d01 * d21) / den, 0.0f, 1.0f);
            float ww = clampf((d00 * d21 - d01 * d20) / den, 0.0f, 1.0f - wv);
            pelt_vec3 q = v3_sub(v3_mad(v3_mad(a, e0, wv), e1, ww), p);
            if (v3_dot(q, q) < best) {
                best = v3_dot(q, q), tri = t;
                at[0] = 1.0f - wv - ww, at[1] = wv, at[2] = ww;
            }
        }
        if (best == INFINITY) continue;
        pelt_vec3 sum = v3(0.0f, 0.0f, 0.0f);
        for (int k = 0; k < 3; k++) {
            size_t j = l->indices[3 * tri + (size_t)k];
            float nj[3];
            memcpy(nj, m.normals + 3 * j, sizeof nj);
            if (fitted) {
                const float *t = tan + 4 * j;
                pelt_vec3 u = v3_norm_or(v3_load(t), v3(1.0f, 0.0f, 0.0f));
                pelt_vec3 v = v3_scale(v3_cross(v3_load(m.normals + 3 * j), u), t[3]);
                float uf[3], vf[3];
                v3_store(uf, u);
                v3_store(vf, v);
                pelt__lod_fit_normal(m.normals + 3 * j, uf, vf, l->fit_normals + 3 * j, nj);
            }
            sum = v3_mad(sum, v3_load(nj), at[k]);
        }
        errors[count++] = acosf(fminf(1.0f, v3_dot(sum, n) / v3_len(sum)));
    }
    float mean = 0.0f;
    for (size_t i = 0; i < count; i++) mean += errors[i];
    qsort(errors, count, sizeof *errors, cmp_float);
    *p90 = count ? errors[(size_t)(0.9 * (double)count)] : 0.0f;
    free(errors);
    free(kept);
    return count ? mean / (float)count : 0.0f;
}

/* A coarse level's triangles interpolate its kept vertices' normals over
 * the ones it left out, so a hair there turns away from the full mesh's;
 * the fitted normals turn it back (docs/lod.md). A bumpy sphere: its
 * bumps are what a coarse level leaves out. */
static void lod_fitted_normals_follow_the_full_mesh(void)
{
    pelt_mesh *sphere = NULL, *m = NULL;
    CHECK(pelt_mesh_sphere(1.0f, 96, 48, &sphere, NULL) == PELT_OK);
    if (!sphere) return;
    pelt_mesh_data d = pelt_mesh_get_data(sphere);
    float *pos = malloc(3 * d.vertex_count * sizeof *pos);
    for (size_t i = 0; i < d.vertex_count; i++) {
        const float *p = d.positions + 3 * i;
        float r = 1.0f + 0.03f * sinf(9.0f * atan2f(p[2], p[0])) * sinf(11.0f * acosf(fmaxf(-1.0f, fminf(1.0f, p[1]))));
        for (int k = 0; k < 3; k++) pos[3 * i + (size_t)k] = p[k] * r;
    }
    d.positions = pos;
    d.normals = NULL; /* worked out from the bumps */
    CHECK(pelt_mesh_create(&d, &m, NULL) == PELT_OK);
    pelt_mesh_destroy(sphere);
    free(pos);
    if (!m) return;
    pelt__lod_chain c;
    CHECK(pelt__lod_chain_build(m, 1, 0, &heap, &c, NULL) == PELT_OK);
    CHECK(c.count >= 3);
    CHECK(c.levels[0].fit_normals == NULL);
    for (unsigned k = 1; k < c.count; k++) CHECK((c.levels[k].fit_normals != NULL) == (k <= PELT__LOD_FIT_LEVELS));
    for (unsigned k = 1; k <= 2 && k < c.count; k++) {
        float p90_plain, p90_fit;
        float plain = level_normal_error(m, &c.levels[k], false, &p90_plain);
        float fit = level_normal_error(m, &c.levels[k], true, &p90_fit);
        /* Measured: level 1 0.146 -> 0.088 rad mean, 0.263 -> 0.150 at the
         * 90th percentile; level 2 0.184 -> 0.122, 0.322 -> 0.240. */
        CHECK(plain > 0.0f);
        CHECK(fit < 0.85f * plain);
        CHECK(p90_fit < 0.85f * p90_plain);
        printf("level %u: mean %.4f -> %.4f rad, p90 %.4f -> %.4f\n", k, plain, fit, p90_plain, p90_fit);
    }
    pelt__lod_chain_free(&c, &heap);
    pelt_mesh_destroy(m);
    /* A coarse sphere's last levels are a few long triangles: every vertex
     * gets a finite difference of two unit vectors, the left-out ones 0. */
    CHECK(pelt_mesh_sphere(1.0f, 48, 24, &m, NULL) == PELT_OK);
    if (!m) return;
    CHECK(pelt__lod_chain_build(m, 1, 0, &heap, &c, NULL) == PELT_OK);
    size_t bad = 0, turned = 0;
    for (unsigned k = 1; k < c.count; k++) {
        const float *fit = c.levels[k].fit_normals;
        for (size_t i = 0; fit && i < 3 * pelt_mesh_get_data(m).vertex_count; i += 3) {
            float len2 = fit[i] * fit[i] + fit[i + 1] * fit[i + 1] + fit[i + 2] * fit[i + 2];
            bad += !(len2 <= 4.0f);
            turned += len2 > 1e-8f;
        }
    }
    CHECK(bad == 0);
    CHECK(turned > 0);
    pelt__lod_chain_free(&c, &heap);
    pelt_mesh_destroy(m);
    /* A triangle a million cells long beside small ones: the grid widens
     * its cells rather than fill a million cells (this returns at once). */
    CHECK(pelt_mesh_square(1.0f, 32, &m, NULL) == PELT_OK);
    if (!m) return;
    pelt_mesh_data sq = pelt_mesh_get_data(m);
    size_t nv = sq.vertex_count, nt = sq.triangle_count;
    float *p = malloc((nv + 3) * 3 * sizeof *p), *nrm = malloc((nv + 3) * 3 * sizeof *nrm);
    uint32_t *idx = malloc((nt + 1) * 3 * sizeof *idx);
    memcpy(p, sq.positions, nv * 3 * sizeof *p);
    memcpy(nrm, sq.normals, nv * 3 * sizeof *nrm);
    memcpy(idx, sq.indices, nt * 3 * sizeof *idx);
    const float far[9] = {-1e4f, 0.0f, -1e4f, 1e4f, 0.0f, -1e4f, 0.0f, 1e-3f, 1e4f};
    memcpy(p + 3 * nv, far, sizeof far);
    for (size_t k = 0; k < 3; k++) {
        memcpy(nrm + 3 * (nv + k), sq.normals, 3 * sizeof *nrm);
        idx[3 * nt + k] = (uint32_t)(nv + k);
    }
    pelt_mesh_data big = {.positions = p, .normals = nrm, .vertex_count = nv + 3, .indices = idx,
                          .triangle_count = nt + 1};
    float *tan = calloc((nv + 3) * 4, sizeof *tan), *out = malloc((nv + 3) * 3 * sizeof *out);
    for (size_t i = 0; i < nv + 3; i++) tan[4 * i] = tan[4 * i + 3] = 1.0f;
    CHECK(pelt__lod_fit_normals(&big, tan, idx, nt + 1, 0.01f, &heap, out, NULL) == PELT_OK);
    size_t finite = 0;
    for (size_t i = 0; i < 3 * (nv + 3); i++) finite += isfinite(out[i]);
    CHECK(finite == 3 * (nv + 3));
    free(p), free(nrm), free(idx), free(tan), free(out);
    pelt_mesh_destroy(m);
}

/* A hair seen from the side between two shells: the gap lies in the
 * shell's plane where the eye sees the hair's point one shell lower, none
 * face-on, and the second read is weighed only near edge-on. */
static void lod_shell_gap_reaches_the_next_shell(void)
{
    const float n[3] = {0.0f, 0.0f, 1.0f}, u[3] = {1.0f, 0.0f, 0.0f}, v[3] = {0.0f, 1.0f, 0.0f};
    const float up[3] = {0.0f, 0.0f, 1.0f}, down[3] = {0.0f, 0.0f, -1.0f};
    float g[3];
    pelt__lod_shell_gap(n, up, down, u, v, 0.01f, 4.0f, -1.0f, g);
    CHECK_NEAR(g[0], 0.0, 1e-6);
    CHECK_NEAR(g[1], 0.0, 1e-6);
    CHECK_NEAR(g[2], 0.0, 1e-6);
    /* From 12 degrees above the plane, a leaning hair: near edge-on, but
     * not at the outline (|V.n| 0.2), where the read weighs most. */
    pelt_vec3 V = v3_norm_or(v3(0.3f, 0.95f, -0.21f), v3(0, 1, 0)), t = v3_norm_or(v3(0.2f, -0.1f, 1.0f), v3(0, 0, 1));
    float Vf[3], tf[3], step = 0.01f, per = 4.0f;
    v3_store(Vf, V), v3_store(tf, t);
    pelt__lod_shell_gap(n, tf, Vf, u, v, step, per, -1.0f, g);
    CHECK(g[2] > 0.75f && g[2] <= 1.0f);
    /* d = the gap in world units; d + t step runs along V. */
    pelt_vec3 d = v3(g[0] / per, g[1] / per, 0.0f);
    pelt_vec3 ray = v3_mad(d, t, step);
    CHECK(v3_len(v3_cross(ray, V)) < 1e-5f * v3_len(ray));
    CHECK(v3_len(d) > 3.0f * step); /* about cot 12 degrees spacings */
    /* At the outline itself (|V.n| 0.05) the tangent plane no longer
     * holds: no read. */
    float Vo[3];
    v3_store(Vo, v3_norm_or(v3(0.3f, 0.95f, -0.05f), v3(0, 1, 0)));
    float go[3];
    pelt__lod_shell_gap(n, tf, Vo, u, v, step, per, -1.0f, go);
    CHECK_NEAR(go[2], 0.0, 1e-6);
    /* Halfway to face-on, partly; beyond it, none. */
    V = v3_norm_or(v3(0.0f, 0.96f, -0.25f), v3(0, 1, 0));
    v3_store(Vf, V);
    pelt__lod_shell_gap(n, tf, Vf, u, v, step, per, -1.0f, g);
    CHECK(g[2] > 0.0f && g[2] < 1.0f);
    V = v3_norm_or(v3(0.0f, 0.9f, -0.44f), v3(0, 1, 0));
    v3_store(Vf, V);
    pelt__lod_shell_gap(n, tf, Vf, u, v, step, per, -1.0f, g);
    CHECK_NEAR(g[2], 0.0, 1e-6);
    /* Edge-on, but the shells stand within a quarter pixel on screen: their
     * sections overlap there, no second read; from 0.6 px, all of it. */
    V = v3_norm_or(v3(0.3f, 0.95f, -0.21f), v3(0, 1, 0));
    v3_store(Vf, V);
    float ungated[3];
    pelt__lod_shell_gap(n, tf, Vf, u, v, step, per, -1.0f, ungated);
    pelt__lod_shell_gap(n, tf, Vf, u, v, step, per, 0.2f, g);
    CHECK_NEAR(g[2], 0.0, 1e-6);
    pelt__lod_shell_gap(n, tf, Vf, u, v, step, per, 0.4f, g);
    CHECK(g[2] > 0.0f && g[2] < ungated[2]);
    pelt__lod_shell_gap(n, tf, Vf, u, v, step, per, 0.7f, g);
    CHECK_NEAR(g[2], ungated[2], 1e-6);
}

/* The view split (pelt__fur_gpu_view_split): its face-on triangles are a
 * part of the level's, the rest side-on, and no vertex of a face-on one
 * gives the read across the gap any weight at any height of its hair, as
 * the vertex stage works it out (V at the shell's vertex, a coarse level's
 * fitted normal, the model's placement, and in half the views the shells'
 * spacing on screen, about the gate's). */
static void lod_view_split_keeps_the_gap_read_where_it_is_weighed(void)
{
    pelt_mesh *m = NULL;
    pelt_fur *fur = NULL;
    if (!sphere_with_fur(&m, &fur)) return;
    const pelt_mesh_data d = pelt_mesh_get_data(m);
    const float *tangents = pelt_mesh_tangents(m);
    pelt__fur_snapshot fs;
    pelt__fur_gpu_snapshot(fur, &fs);
    uint8_t *side_of = malloc(d.vertex_count);
    uint32_t *tris = malloc(d.triangle_count * 3 * sizeof *tris);
    size_t *uses = calloc(d.vertex_count, sizeof *uses);
    const float eyes[4][3] = {{0.0f, 0.5f, 4.0f}, {2.0f, -1.0f, 1.5f}, {0.0f, 0.0f, 1.6f}, {-3.0f, 2.0f, -6.0f}};
    /* Twice the size, turned a quarter about y and moved. */
    const float turned[16] = {0, 0, -2, 0, 0, 2, 0, 0, 2, 0, 0, 0, 0.5f, -0.25f, 0.1f, 1};
    const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    size_t faces = 0, sides = 0, wrong = 0, lost = 0;
    for (unsigned level = 0; level < 2 && level < fs.lod->count && side_of && tris && uses; level++)
        for (int k = 0; k < 16; k++) {
            const float *model = k % 8 < 4 ? identity : turned;
            float scale = k % 8 < 4 ? 1.0f : 2.0f;
            pelt_vec3 eye = v3_load(eyes[k % 4]), fwd = v3_norm_or(v3_scale(eye, -1.0f), v3(0, 0, -1));
            pelt__view_split_desc vd = {level, false, {0}, scale, {eye.x, eye.y, eye.z}, PELT__VIEW_SPLIT_MARGIN,
                                        /* shells 0.26 px apart at the eye's distance */
                                        k < 8 ? 0.0f : 0.26f * v3_len(eye),
                                        {fwd.x, fwd.y, fwd.z, -v3_dot(fwd, eye)}};
            memcpy(vd.model, model, sizeof vd.model);
            const pelt__lod_level *l = &fs.lod->levels[level];
            size_t total = 0, face = pelt__fur_gpu_view_split(fur, &vd, side_of, tris, &total);
            CHECK(total == l->triangle_count && face <= total);
            faces += face, sides += total - face;
            /* The same triangles: every vertex used as often. */
            memset(uses, 0, d.vertex_count * sizeof *uses);
            for (size_t t = 0; t < 3 * total; t++) uses[l->indices[t]]++, uses[tris[t]]--;
            for (size_t i = 0; i < d.vertex_count; i++) lost += uses[i] != 0;
            for (size_t t = 0; t < 3 * face; t++) {
                uint32_t i = tris[t];
                fin_strand st = pelt__fur_vertex_strand(fur, &d, tangents, false, 0.0f, 1.0f, i);
                /* The shells' spacing on screen at the root, as shell_vs.glsl. */
                pelt_vec3 root = pelt__mat4_apply(model, st.p, 1.0f);
                float clip_w = fmaxf(v3_dot(fwd, root) + vd.w_row[3], 1e-6f);
                float groom = st.L / pelt_fur_get_desc(fur).length; /* the groom's length multiple */
                float spacing_px = vd.shell_spacing > 0.0f ? vd.shell_spacing * groom / clip_w : -1.0f;
                if (level > 0 && l->fit_normals) {
                    float n[3], u[3], v[3], fit[3];
                    v3_store(n, st.n), v3_store(u, st.u), v3_store(v, st.v);
                    pelt__lod_fit_normal(n, u, v, l->fit_normals + 3 * i, fit);
                    pelt_vec3 fitted = v3(fit[0], fit[1], fit[2]);
                    st.tip = v3_mad(st.tip, v3_sub(fitted, st.n), st.L);
                    st.n = fitted;
                }
                for (int h = 0; h <= 4; h++) {
                    pelt_vec3 p = v3_add(st.p, pelt__fur_vertex_strand_offset(&st, 0.25f * (float)h));
                    pelt_vec3 w = pelt__mat4_apply(model, p, 1.0f);
                    pelt_vec3 n = v3_norm_or(pelt__mat4_apply(model, st.n, 0.0f), v3(0, 1, 0));
                    float nf[3], Vf[3], g[3];
                    v3_store(nf, n);
                    v3_store(Vf, v3_norm_or(v3_sub(w, v3_load(vd.eye)), v3(0, 0, -1)));
                    const float u[3] = {1, 0, 0}, v[3] = {0, 1, 0};
                    pelt__lod_shell_gap(nf, nf, Vf, u, v, 0.01f, 1.0f, spacing_px, g);
                    wrong += g[2] > 0.0f;
                }
            }
        }
    printf("  %zu face-on and %zu side-on triangles over 32 views; %zu face-on vertex heights weigh the read\n",
           faces, sides, wrong);
    CHECK(lost == 0);
    CHECK(wrong == 0);
    CHECK(faces > 0 && sides > 0);
    free(side_of);
    free(tris);
    free(uses);
    pelt_fur_destroy(fur);
    pelt_mesh_destroy(m);
}

int main(void)
{
    RUN(lod_levels_shrink_and_their_error_grows);
    RUN(lod_fins_take_a_coarser_level_within_a_slab);
    RUN(lod_an_open_square_is_not_closed);
    RUN(lod_pixels_per_unit_follow_the_distance);
    RUN(lod_shell_levels_halve_to_one_shell);
    RUN(lod_shell_choice_blends_without_a_jump);
    RUN(lod_view_blend_follows_the_view);
    RUN(lod_lean_drift_is_the_tangent_of_the_lean);
    RUN(lod_shell_composite_is_over);
    RUN(lod_fins_closer_than_their_slab_fade);
    RUN(lod_a_fin_frame_holds_the_fins_the_view_shows);
    RUN(lod_fin_rows_follow_the_strands_bow);
    RUN(lod_outline_hairs_follow_the_fins_near_the_outline);
    RUN(lod_outline_hairs_leave_out_those_the_fade_hides);
    RUN(lod_outline_hairs_leave_out_fins_out_of_reach);
    RUN(lod_fur_texture_keeps_the_short_side_sharp);
    RUN(lod_fur_texture_taps_split_a_long_footprint);
    RUN(lod_fur_edge_keeps_a_hair_its_width);
    RUN(lod_shell_overcount_counts_a_hair_once);
    RUN(lod_shell_stack_cos_follows_the_stack);
    RUN(lod_shell_edge_least_thickens_the_edge_on_shells);
    RUN(lod_coverage_powers_compose);
    RUN(lod_sub_shells_close_the_rows);
    RUN(lod_fitted_normals_follow_the_full_mesh);
    RUN(lod_shell_gap_reaches_the_next_shell);
    RUN(lod_view_split_keeps_the_gap_read_where_it_is_weighed);
    return check_summary();
}
