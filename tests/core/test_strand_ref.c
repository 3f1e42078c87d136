/* The strand reference's hairs (core/fur/strand_ref.c): enough pieces
 * along a hair that its curls stay round and a wet hair follows its
 * tuft. */
#include "support/check.h"

#include "core/base/vec.h"
#include "core/fur/strand_ref.h"
#include "pelt/wetness.h"

#include <math.h>
#include <stdlib.h>

static pelt_fur *curly_square(const pelt_mesh *m, const char *preset)
{
    pelt_fur_desc d = {0};
    d.length = 0.3f;
    d.look.density = 200.0f;
    pelt_error err;
    if (preset && pelt_fur_desc_curl_preset(&d, m, preset, &err) != PELT_OK) {
        fprintf(stderr, "  preset: %s\n", err.message);
        return NULL;
    }
    pelt_fur *fur = NULL;
    if (pelt_fur_create(m, &d, &fur, &err) != PELT_OK) {
        fprintf(stderr, "  fur: %s\n", err.message);
        return NULL;
    }
    return fur;
}

/* Straight fur (curly_square's) on a unit square of 4 x 4 cells: the fur,
 * with the mesh in *m, or NULL with nothing left to free. */
static pelt_fur *straight_square(pelt_mesh **m)
{
    *m = NULL;
    CHECK(pelt_mesh_square(1.0f, 4, m, NULL) == PELT_OK);
    if (!*m) return NULL;
    pelt_fur *fur = curly_square(*m, NULL);
    CHECK(fur != NULL);
    if (!fur) {
        pelt_mesh_destroy(*m);
        *m = NULL;
    }
    return fur;
}

/* The hairs' polylines with `segments` pieces (PELT__STRAND_TEXELS each). */
static float *build_hairs(const pelt_fur *fur, unsigned segments, size_t *hairs)
{
    size_t tile_count = pelt__strand_ref_tile(fur, NULL, 0);
    pelt__furtex_strand *tile = malloc((tile_count ? tile_count : 1) * sizeof *tile);
    pelt__strand_ref_tile(fur, tile, tile_count);
    size_t cap = pelt__strand_ref_count(fur, tile, tile_count);
    float *out = malloc((cap ? cap : 1) * 4 * (size_t)PELT__STRAND_TEXELS(segments) * sizeof(float));
    *hairs = pelt__strand_ref_build(fur, tile, tile_count, segments, out, cap);
    free(tile);
    return out;
}

/* Mean length of the hairs' polylines, built with `segments` pieces. */
static double mean_hair_length(const pelt_fur *fur, unsigned segments, size_t *hairs)
{
    size_t n = 0;
    float *out = build_hairs(fur, segments, &n);
    size_t stride = 4 * (size_t)PELT__STRAND_TEXELS(segments);
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) {
        const float *h = out + i * stride;
        for (unsigned k = 0; k < segments; k++) {
            const float *a = h + 8 * k, *b = h + 8 * (k + 1);
            sum += sqrt((double)(b[0] - a[0]) * (b[0] - a[0]) + (double)(b[1] - a[1]) * (b[1] - a[1]) +
                        (double)(b[2] - a[2]) * (b[2] - a[2]));
        }
    }
    free(out);
    *hairs = n;
    return n ? sum / (double)n : 0.0;
}

/* A polyline through points of a curl is shorter than the curl: with too
 * few pieces, chords cut across the turns and the hair is drawn as a
 * zigzag. The pieces pelt__strand_ref_segments picks must keep the length
 * within 3% of the finest the reference can draw. */
static void curly_hairs_get_enough_pieces_to_stay_round(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_square(1.0f, 4, &m, NULL) == PELT_OK);
    if (!m) return;
    const char *presets[] = {"few-large-curls", "many-small-curls"};
    for (int i = 0; i < 2; i++) {
        pelt_fur *fur = curly_square(m, presets[i]);
        CHECK(fur != NULL);
        if (!fur) continue;
        unsigned s = pelt__strand_ref_segments(fur);
        size_t n0 = 0, n1 = 0, n2 = 0;
        double coarse = mean_hair_length(fur, PELT__STRAND_SEGMENTS_MIN, &n0);
        double picked = mean_hair_length(fur, s, &n1);
        double finest = mean_hair_length(fur, PELT__STRAND_SEGMENTS_MAX, &n2);
        fprintf(stderr, "  %s: %u pieces, %zu hairs, mean length %.4f (8 pieces %.4f, %d pieces %.4f)\n",
                presets[i], s, n1, picked, coarse, PELT__STRAND_SEGMENTS_MAX, finest);
        CHECK(n1 > 100 && n0 == n1 && n2 == n1);
        CHECK(s > PELT__STRAND_SEGMENTS_MIN);
        CHECK(picked >= 0.97 * finest);
        /* The test can fail: 8 pieces, as the reference once drew every
         * hair, lose more than the bound on the small curls. */
        if (i == 1) CHECK(coarse < 0.97 * finest);
        pelt_fur_destroy(fur);
    }
    /* Straight fur keeps the minimum: its hairs are smooth curves anyway. */
    pelt_fur *straight = curly_square(m, NULL);
    CHECK(straight && pelt__strand_ref_segments(straight) == PELT__STRAND_SEGMENTS_MIN);
    pelt_fur_destroy(straight);
    pelt_mesh_destroy(m);
}

/* How far a hair drawn with `segments` pieces turns from the same hair
 * drawn with the most pieces: the angle between the coarser piece's
 * direction and the finer polyline's at the same height, in degrees, mean
 * over the wet hairs' points (their light follows that direction). */
static double wet_hair_turn(const pelt_fur *fur, unsigned segments, size_t *wet_hairs)
{
    const unsigned fine = PELT__STRAND_SEGMENTS_MAX;
    size_t n = 0, n_fine = 0;
    float *coarse = build_hairs(fur, segments, &n);
    float *finest = build_hairs(fur, fine, &n_fine);
    const size_t sc = 4 * (size_t)PELT__STRAND_TEXELS(segments), sf = 4 * (size_t)PELT__STRAND_TEXELS(fine);
    double sum = 0.0;
    size_t count = 0, wet = 0;
    for (size_t i = 0; i < n && n == n_fine; i++) {
        const float *c = coarse + i * sc, *f = finest + i * sf;
        if (!(f[8 * (fine + 1) + 4] > 0.0f)) continue; /* dry root */
        wet++;
        for (unsigned k = 0; k < fine; k++) {
            unsigned j = k * segments / fine;
            pelt_vec3 piece = v3_norm_or(v3(c[8 * (j + 1)] - c[8 * j], c[8 * (j + 1) + 1] - c[8 * j + 1],
                                            c[8 * (j + 1) + 2] - c[8 * j + 2]), v3(0.0f, 0.0f, 1.0f));
            pelt_vec3 along = v3_norm_or(v3(f[8 * (k + 1)] - f[8 * k], f[8 * (k + 1) + 1] - f[8 * k + 1],
                                            f[8 * (k + 1) + 2] - f[8 * k + 2]), v3(0.0f, 0.0f, 1.0f));
            float cosine = v3_dot(piece, along);
            sum += acos(cosine < 1.0f ? (cosine > -1.0f ? cosine : -1.0f) : 1.0f) * 57.29578;
            count++;
        }
    }
    free(coarse);
    free(finest);
    *wet_hairs = wet;
    return count ? sum / (double)count : 180.0;
}

/* A tuft gathers its hairs within a few layers above its base: drawn
 * with 8 even pieces, one chord cuts across that bend and the hair's
 * light, which follows its tangent, with it. Where the fur is wet, the
 * pieces picked keep the hairs' direction within 1 degree of the finest
 * the reference draws, on average (the picture of the wet close-up then
 * within 1/255 of the finest's, docs/reference.md). */
static void wet_hairs_follow_their_tuft(void)
{
    pelt_mesh *m = NULL;
    pelt_fur *fur = straight_square(&m);
    if (!fur) return;
    const pelt_droplet drop = {{0.5f, 0.5f}, 0.2f, 1.0f};
    pelt_error err;
    CHECK(pelt_fur_add_droplet(fur, &drop, &err) == PELT_OK);
    unsigned s = pelt__strand_ref_segments(fur);
    size_t wet = 0, wet8 = 0;
    double picked = wet_hair_turn(fur, s, &wet);
    double coarse = wet_hair_turn(fur, PELT__STRAND_SEGMENTS_MIN, &wet8);
    fprintf(stderr, "  %u pieces: %zu wet hairs turn from the finest by %.2f degrees (8 pieces %.2f)\n", s, wet,
            picked, coarse);
    CHECK(wet > 100 && wet8 == wet);
    CHECK(s == PELT__STRAND_SEGMENTS_WET);
    CHECK(picked < 1.0);
    /* The test can fail: 8 pieces, as the reference drew wet hairs, stray
     * further. */
    CHECK(coarse > 1.0);
    pelt_fur_destroy(fur);
    pelt_mesh_destroy(m);
}

/* Straight fur on the unit square with `lie` degrees of wet lie (wet.lie),
 * soaked by one droplet in the middle; NULL with nothing left to free. */
static pelt_fur *soaked_square(const pelt_mesh *m, float lie)
{
    pelt_fur_desc d = {0};
    d.length = 0.3f;
    d.look.density = 200.0f;
    d.wet.lie = lie;
    pelt_fur *fur = NULL;
    pelt_error err;
    if (pelt_fur_create(m, &d, &fur, &err) != PELT_OK) return NULL;
    const pelt_droplet drop = {{0.5f, 0.5f}, 0.2f, 1.0f};
    if (pelt_fur_add_droplet(fur, &drop, &err) != PELT_OK) {
        pelt_fur_destroy(fur);
        return NULL;
    }
    return fur;
}

/* How far hair b's tip stands from hair a's (polylines of `seg` pieces). */
static pelt_vec3 tip_shift(const float *ha, const float *hb, unsigned seg)
{
    return v3_sub(v3_load(hb + 8 * seg), v3_load(ha + 8 * seg));
}

/* Wet fur lies along its grain (docs/wetness.md, Wet fur lies down): with
 * wet.lie 40, the reference's soaked hairs reach further along one
 * direction, the comb's, than with none, every one the same way, and the
 * dry hairs stay where they were. */
static void wet_hairs_lie_along_the_comb(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_square(1.0f, 16, &m, NULL) == PELT_OK);
    if (!m) return;
    pelt_fur *upright = soaked_square(m, 0.0f), *lying = soaked_square(m, 40.0f);
    CHECK(upright && lying);
    if (upright && lying) {
        unsigned seg = pelt__strand_ref_segments(upright);
        CHECK(seg == pelt__strand_ref_segments(lying));
        size_t n = 0, n_lie = 0;
        float *a = build_hairs(upright, seg, &n), *b = build_hairs(lying, seg, &n_lie);
        CHECK(n == n_lie && n > 100);
        const size_t stride = 4 * (size_t)PELT__STRAND_TEXELS(seg);
        pelt_vec3 mean = v3(0, 0, 0), centre = v3(0, 0, 0);
        double dry_moved = 0.0;
        size_t wet = 0, dry = 0;
        for (size_t i = 0; i < n && n == n_lie; i++)
            centre = v3_add(centre, v3_scale(v3_load(a + i * stride), 1.0f / (float)n));
        for (size_t i = 0; i < n && n == n_lie; i++) {
            const float *ha = a + i * stride, *hb = b + i * stride;
            pelt_vec3 shift = tip_shift(ha, hb, seg);
            if (ha[8 * (seg + 1) + 4] > 0.0f) {
                mean = v3_add(mean, shift);
                wet++;
            } else if (v3_len(v3_sub(v3_load(ha), centre)) > 0.3f) {
                /* Dry and two cells clear of the droplet's 0.2: no wet vertex
                 * of the 16 x 16 cells shears it. */
                dry_moved = fmax(dry_moved, (double)v3_len(shift));
                dry++;
            }
        }
        mean = v3_scale(mean, wet ? 1.0f / (float)wet : 0.0f);
        double agree = 0.0;
        for (size_t i = 0; i < n && n == n_lie; i++) {
            const float *ha = a + i * stride, *hb = b + i * stride;
            if (!(ha[8 * (seg + 1) + 4] > 0.0f)) continue;
            pelt_vec3 shift = tip_shift(ha, hb, seg);
            agree += v3_dot(v3_norm_or(shift, v3(0, 0, 0)), v3_norm_or(mean, v3(0, 0, 0)));
        }
        agree = wet ? agree / (double)wet : 0.0;
        fprintf(stderr, "  %zu wet hairs' tips move %.3f (fur 0.3) one way (mean cosine %.3f); %zu dry hairs %.2g\n",
                wet, (double)v3_len(mean), agree, dry, dry_moved);
        CHECK(wet > 100 && dry > 100);
        CHECK(v3_len(mean) > 0.1f); /* a third of the fur's length or more */
        CHECK(agree > 0.9);
        CHECK(dry_moved < 1e-5);
        free(a);
        free(b);
    }
    if (upright) pelt_fur_destroy(upright);
    if (lying) pelt_fur_destroy(lying);
    pelt_mesh_destroy(m);
}

/* The shells light a hair at its layer's height in the fur, h of the full
 * length (Silva Eq. 6's gamma darkens the lower part of the fur), and a
 * short hair's tip lies in a low layer. So each hair carries its length
 * of the full height, and a point's height in the fur is its fraction
 * along the hair times that: on straight fur standing upright, the tip's
 * height over the skin is that length times the fur's within 1%. The
 * hairs' lengths vary (0.6 to 1), so a reference that lit the tip of
 * every hair as the top of the fur fails. */
static void hairs_carry_their_height_in_the_fur(void)
{
    pelt_mesh *m = NULL;
    pelt_fur *fur = straight_square(&m);
    if (!fur) return;
    const unsigned segments = PELT__STRAND_SEGMENTS_MIN;
    size_t n = 0;
    float *out = build_hairs(fur, segments, &n);
    const size_t stride = 4 * (size_t)PELT__STRAND_TEXELS(segments);
    double worst = 0.0, shortest = 1.0, longest = 0.0;
    for (size_t i = 0; i < n; i++) {
        const float *h = out + i * stride;
        const float *tip = h + 8 * segments, *e = h + 8 * (segments + 1);
        pelt_vec3 rise = v3(tip[0] - h[0], tip[1] - h[1], tip[2] - h[2]);
        double height = v3_dot(rise, v3(e[0], e[1], e[2])) / 0.3; /* curly_square's length */
        double length = e[5];
        CHECK(tip[7] == 1.0f); /* the tip is the end of the hair */
        worst = fmax(worst, fabs(height - tip[7] * length));
        shortest = fmin(shortest, length);
        longest = fmax(longest, length);
    }
    fprintf(stderr, "  %zu hairs, lengths %.3f..%.3f of the fur's; worst |tip height - length| %.2g\n", n,
            shortest, longest, worst);
    CHECK(n > 100);
    CHECK(shortest < 0.7 && longest > 0.9);
    CHECK(worst < 0.01);
    free(out);
    pelt_fur_destroy(fur);
    pelt_mesh_destroy(m);
}

int main(void)
{
    RUN(curly_hairs_get_enough_pieces_to_stay_round);
    RUN(wet_hairs_follow_their_tuft);
    RUN(wet_hairs_lie_along_the_comb);
    RUN(hairs_carry_their_height_in_the_fur);
    return check_summary();
}
