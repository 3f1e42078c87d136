/* Natural wet clumps (core/wet/clump_cells.c, docs/wetness.md): cells fixed
 * on the surface cut wet areas into clumps of wet.clump_size, through the
 * fur's droplet calls, what the renderer uploads. */
#include "support/check.h"

#include "pelt/wetness.h"
#include "core/fur/fur_gpu.h"
#include "core/wet/clump.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int cmp_centre(const void *a, const void *b)
{
    const float *p = a, *q = b;
    if (p[0] != q[0]) return p[0] < q[0] ? -1 : 1;
    return (p[1] > q[1]) - (p[1] < q[1]);
}

/* Two clump centres are the same clump within this (uv): each texel works
 * its clump's centre out through its own triangle, so they agree to
 * rounding. */
#define SAME_CENTRE 1e-4f

/* Distinct clump centres among the wet texels of the fur's mask: the
 * clumps Alg. 2 draws. */
static size_t distinct_clumps(const pelt_fur *fur)
{
    pelt__fur_snapshot fs;
    pelt__fur_gpu_snapshot(fur, &fs);
    unsigned w = fs.mask_width, h = fs.mask_height;
    const float *m = fs.mask;
    float *c = malloc((size_t)w * h * 2 * sizeof *c);
    size_t n = 0;
    for (size_t i = 0; c && i < (size_t)w * h; i++)
        if (m[4 * i + 3] > 0.0f) {
            c[2 * n] = roundf(m[4 * i] / SAME_CENTRE) * SAME_CENTRE;
            c[2 * n + 1] = roundf(m[4 * i + 1] / SAME_CENTRE) * SAME_CENTRE;
            n++;
        }
    if (!c) return 0;
    qsort(c, n, 2 * sizeof *c, cmp_centre);
    size_t distinct = 0;
    for (size_t i = 0; i < n; i++)
        distinct += i == 0 || c[2 * i] != c[2 * i - 2] || c[2 * i + 1] != c[2 * i - 1];
    free(c);
    return distinct;
}

/* Fur with natural clumps of clump_size; 0: one clump per droplet. */
static pelt_fur *wet_fur(const pelt_mesh *m, float clump_size)
{
    pelt_fur_desc d = {.layers = 4, .look.texture_size = 64, .wet.clump_size = clump_size,
                       .wet.clumps = clump_size > 0.0f ? PELT_CLUMPS_NATURAL : PELT_CLUMPS_DROPLET};
    pelt_fur *fur = NULL;
    pelt_error err = {0};
    if (pelt_fur_create(m, &d, &fur, &err) != PELT_OK) fprintf(stderr, "  %s\n", err.message);
    return fur;
}

/* A fully wet 2 x 2 square: one droplet over all of it. Silva's Alg. 1
 * (clump_size 0) makes it one clump; with a clump size the square holds
 * about area / clump_size^2 of them, four times as many at half the size;
 * five droplets apart make five clumps without a clump size. */
static void clump_count_grows_with_area_over_clump_size_squared(void)
{
    pelt_mesh *sq = NULL;
    CHECK(pelt_mesh_square(2.0f, 16, &sq, NULL) == PELT_OK);
    if (!sq) return;
    const pelt_droplet all = {{0.5f, 0.5f}, 0.75f, 1.0f};
    const float sizes[] = {0.0f, 0.4f, 0.2f, 0.1f};
    size_t counts[4];
    for (int k = 0; k < 4; k++) {
        pelt_fur *fur = wet_fur(sq, sizes[k]);
        CHECK(fur != NULL);
        if (!fur) return;
        CHECK(pelt_fur_add_droplet(fur, &all, NULL) == PELT_OK);
        counts[k] = distinct_clumps(fur);
        double expected = sizes[k] > 0.0f ? 4.0 / ((double)sizes[k] * sizes[k]) : 1.0;
        printf("  clump size %.2f: %zu clumps on the wet square (area / size^2 = %.0f)\n",
               (double)sizes[k], counts[k], expected);
        CHECK(counts[k] >= 0.85 * expected && counts[k] <= 1.15 * expected);
        pelt_fur_destroy(fur);
    }
    CHECK(counts[0] == 1);
    CHECK(counts[2] > 3 * counts[1] && counts[3] > 3 * counts[2]);

    pelt_fur *fur = wet_fur(sq, 0.0f);
    for (int i = 0; fur && i < 5; i++) {
        pelt_droplet d = {{0.1f + 0.2f * (float)i, 0.5f}, 0.05f, 1.0f};
        pelt_fur_add_droplet(fur, &d, NULL);
    }
    size_t five = fur ? distinct_clumps(fur) : 0;
    printf("  clump size 0: five droplets apart, %zu clumps\n", five);
    CHECK(five == 5);
    pelt_fur_destroy(fur);
    pelt_mesh_destroy(sq);
}

static double coefficient_of_variation(const double *x, size_t n)
{
    double mean = 0.0, var = 0.0;
    for (size_t i = 0; i < n; i++) mean += x[i];
    mean /= (double)n;
    for (size_t i = 0; i < n; i++) var += (x[i] - mean) * (x[i] - mean);
    return sqrt(var / (double)n) / mean;
}

/* Natural clumps by default, and not a lattice (docs/wetness.md, Natural
 * clumps): on a soaked square the tufts' sizes (their wet texels) vary
 * with a coefficient of variation of at least 0.3, and the distances from
 * each tuft's centre to its nearest neighbour vary by at least 0.15 of
 * their mean (0 on a lattice, about 0.5 for independent random points). */
static void tufts_vary_in_size_and_are_not_a_lattice(void)
{
    pelt_mesh *sq = NULL;
    CHECK(pelt_mesh_square(2.0f, 16, &sq, NULL) == PELT_OK);
    if (!sq) return;
    pelt_fur_desc d = {.layers = 4, .look.texture_size = 64, .wet.clump_size = 0.12f};
    pelt_fur *fur = NULL;
    CHECK(pelt_fur_create(sq, &d, &fur, NULL) == PELT_OK);
    if (!fur) return;
    const pelt_droplet all = {{0.5f, 0.5f}, 0.75f, 1.0f};
    CHECK(pelt_fur_add_droplet(fur, &all, NULL) == PELT_OK);
    pelt__fur_snapshot fs;
    pelt__fur_gpu_snapshot(fur, &fs);
    size_t texels = (size_t)fs.mask_width * fs.mask_height, n = 0;
    float *c = malloc(texels * 2 * sizeof *c);
    double *size = calloc(texels, sizeof *size), *nearest = calloc(texels, sizeof *nearest);
    float *centre = malloc(texels * 2 * sizeof *centre);
    if (!c || !size || !nearest || !centre) goto out;
    for (size_t i = 0; i < texels; i++)
        if (fs.mask[4 * i + 3] > 0.0f) {
            c[2 * n] = roundf(fs.mask[4 * i] / SAME_CENTRE) * SAME_CENTRE;
            c[2 * n + 1] = roundf(fs.mask[4 * i + 1] / SAME_CENTRE) * SAME_CENTRE;
            n++;
        }
    qsort(c, n, 2 * sizeof *c, cmp_centre);
    size_t clumps = 0;
    for (size_t i = 0; i < n; i++) {
        if (i == 0 || c[2 * i] != c[2 * i - 2] || c[2 * i + 1] != c[2 * i - 1]) {
            centre[2 * clumps] = c[2 * i], centre[2 * clumps + 1] = c[2 * i + 1];
            clumps++;
        }
        size[clumps - 1] += 1.0;
    }
    /* Tufts whose cell the square's edge cuts are smaller for that: only
     * those whose centre lies 1.5 sizes from every edge count. */
    size_t inner = 0;
    const float margin = 1.5f * 0.12f / 2.0f;
    for (size_t k = 0; k < clumps; k++) {
        float x = centre[2 * k], y = centre[2 * k + 1];
        if (x < margin || y < margin || x > 1.0f - margin || y > 1.0f - margin) continue;
        double best = INFINITY;
        for (size_t j = 0; j < clumps; j++)
            if (j != k) best = fmin(best, hypot(centre[2 * j] - x, centre[2 * j + 1] - y));
        size[inner] = size[k];
        nearest[inner] = best;
        inner++;
    }
    double cv_size = coefficient_of_variation(size, inner), cv_nearest = coefficient_of_variation(nearest, inner);
    printf("  %zu tufts (%zu inside): size cv %.2f, nearest-neighbour distance cv %.2f\n", clumps, inner, cv_size,
           cv_nearest);
    CHECK(inner > 100);
    CHECK(cv_size >= 0.3);
    CHECK(cv_nearest >= 0.15);
out:
    free(c);
    free(size);
    free(nearest);
    free(centre);
    pelt_fur_destroy(fur);
    pelt_mesh_destroy(sq);
}

/* Alg. 2 keeps every fragment of its own clump (|p - c| <= r) and the
 * clumps are whole: after many overlapping droplets, rain-like, of both
 * signs, on a torus whose uvs wrap (a seam in u and v), each wet texel lies
 * within its clump's radius and all wet texels of a clump agree on it in
 * 3D: a cell that crosses the seam renders as one clump on both sides. */
static void overlapping_droplets_keep_whole_clumps_across_the_seam(void)
{
    pelt_mesh *torus = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 78, 60, &torus, NULL) == PELT_OK);
    if (!torus) return;
    pelt_fur *fur = wet_fur(torus, 0.12f);
    CHECK(fur != NULL);
    if (!fur) return;
    pelt_rain r = {0.0f, 0.03f, 0.08f, 0.5f, 1.0f, 3};
    pelt_fur_add_random_droplets(fur, &r, 400);
    pelt_rain dryer = {0.0f, 0.02f, 0.04f, -1.0f, -1.0f, 4};
    pelt_fur_add_random_droplets(fur, &dryer, 40);
    /* Droplets on the seam itself. */
    for (int i = 0; i < 8; i++) {
        pelt_droplet d = {{0.0f, 0.125f * (float)i}, 0.06f, 1.0f};
        pelt_fur_add_droplet(fur, &d, NULL);
    }
    pelt__fur_snapshot fs;
    pelt__fur_gpu_snapshot(fur, &fs);
    unsigned w = fs.mask_width, h = fs.mask_height;
    const float *m = fs.mask;
    size_t wet = 0, outside = 0, seam = 0;
    float worst = 0.0f;
    for (unsigned y = 0; y < h; y++)
        for (unsigned x = 0; x < w; x++) {
            const float *t = m + 4 * ((size_t)y * w + x);
            if (!(t[3] > 0.0f)) continue;
            wet++;
            float pu = ((float)x + 0.5f) / (float)w, pv = ((float)y + 0.5f) / (float)h;
            float d = hypotf(pu - t[0], pv - t[1]);
            if (d > t[2]) outside++;
            worst = fmaxf(worst, d / t[2]);
            /* The centre beyond the mask's edge: the clump's middle lies
             * across the seam, in this side's coordinates. */
            if (t[0] < 0.0f || t[0] > 1.0f || t[1] < 0.0f || t[1] > 1.0f) seam++;
        }
    printf("  %zu wet texels in %zu clumps, %zu with their clump's centre across the seam; "
           "%zu outside their clump's radius (largest distance %.2f of the radius)\n",
           wet, distinct_clumps(fur), seam, outside, (double)worst);
    CHECK(wet > 1000);
    CHECK(outside == 0);
    CHECK(seam > 0);
    pelt_fur_destroy(fur);
    pelt_mesh_destroy(torus);
}

/* Clump seeds are fixed on the surface: a droplet that overlaps an earlier
 * one leaves the clumps it does not reach as they were, and texels wet by
 * both stay in the clump they were in with the same neighbours. */
static void a_second_droplet_keeps_the_first_ones_clumps(void)
{
    pelt_mesh *sq = NULL;
    CHECK(pelt_mesh_square(2.0f, 16, &sq, NULL) == PELT_OK);
    pelt_fur *fur = sq ? wet_fur(sq, 0.2f) : NULL;
    CHECK(fur != NULL);
    if (!fur) return;
    pelt_droplet a = {{0.35f, 0.5f}, 0.25f, 1.0f}, b = {{0.65f, 0.5f}, 0.25f, 1.0f};
    pelt_fur_add_droplet(fur, &a, NULL);
    pelt__fur_snapshot fs;
    pelt__fur_gpu_snapshot(fur, &fs);
    unsigned w = fs.mask_width, h = fs.mask_height;
    const float *m = fs.mask;
    size_t n = (size_t)w * h;
    float *before = malloc(n * 4 * sizeof *before);
    CHECK(before != NULL);
    if (!before) return;
    memcpy(before, m, n * 4 * sizeof *before);
    pelt_fur_add_droplet(fur, &b, NULL);
    /* Pairs of neighbouring texels wet before: in one clump before iff in
     * one clump after. Texels far from b (u < 0.3) keep their clump. */
    size_t pairs = 0, split = 0, far = 0, moved = 0;
    for (unsigned y = 0; y < h; y++)
        for (unsigned x = 0; x + 1 < w; x++) {
            size_t i = (size_t)y * w + x, j = i + 1;
            if (!(before[4 * i + 3] > 0.0f) || !(before[4 * j + 3] > 0.0f)) continue;
            bool same_before = hypotf(before[4 * i] - before[4 * j], before[4 * i + 1] - before[4 * j + 1]) < SAME_CENTRE;
            bool same_after = hypotf(m[4 * i] - m[4 * j], m[4 * i + 1] - m[4 * j + 1]) < SAME_CENTRE;
            pairs++;
            split += same_before != same_after;
            if ((x + 0.5f) / (float)w < 0.3f) {
                far++;
                moved += memcmp(before + 4 * i, m + 4 * i, 4 * sizeof *m) != 0;
            }
        }
    printf("  %zu neighbouring wet pairs: %zu changed clump company; %zu of %zu far texels changed\n",
           pairs, split, moved, far);
    CHECK(pairs > 100 && split == 0);
    CHECK(far > 50 && moved == 0);
    free(before);
    pelt_fur_destroy(fur);
    pelt_mesh_destroy(sq);
}

int main(void)
{
    RUN(clump_count_grows_with_area_over_clump_size_squared);
    RUN(tufts_vary_in_size_and_are_not_a_lattice);
    RUN(overlapping_droplets_keep_whole_clumps_across_the_seam);
    RUN(a_second_droplet_keeps_the_first_ones_clumps);
    return check_summary();
}
