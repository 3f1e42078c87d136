/* Fur texture synthesis (Lengyel et al. 2001 §2.2). */
#include "support/check.h"

#include "core/fur/fur_gpu.h"
#include "core/fur/furtex.h"
#include "core/fur/fur_shape.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

static uint8_t *make(const pelt__furtex_desc *d)
{
    uint8_t *v = malloc(pelt__furtex_bytes(d));
    if (v) pelt__furtex_generate(d, v);
    return v;
}

static const pelt__furtex_desc base = {128, 16, 7, 750.0f, 1.6f, 0.8f};

/* Mean alpha of slice s (0..1). */
static double coverage(const uint8_t *v, const pelt__furtex_desc *d, unsigned s)
{
    size_t n = (size_t)d->size * d->size;
    const uint8_t *p = v + (size_t)s * n * 4;
    double sum = 0;
    for (size_t i = 0; i < n; i++) sum += p[4 * i + 3];
    return sum / (255.0 * (double)n);
}

static void furtex_innermost_slice_is_opaque_skin(void)
{
    uint8_t *v = make(&base);
    CHECK(v != NULL);
    if (v) CHECK_NEAR(coverage(v, &base, 0), 1.0, 0.0);
    free(v);
}

static void furtex_is_deterministic_per_seed(void)
{
    pelt__furtex_desc other = base;
    other.seed = 8;
    uint8_t *a = make(&base), *b = make(&base), *c = make(&other);
    CHECK(a && b && c);
    if (a && b && c) {
        size_t n = pelt__furtex_bytes(&base);
        CHECK(memcmp(a, b, n) == 0);
        CHECK(memcmp(a, c, n) != 0);
    }
    free(a), free(b), free(c);
}

/* Tileable: the alpha changes across the wrap seam (last column to the
 * first, last row to the first) as much as between interior neighbours,
 * no more. */
static void furtex_tiles_without_a_seam(void)
{
    uint8_t *v = make(&base);
    CHECK(v != NULL);
    if (!v) return;
    unsigned s = base.size;
    const uint8_t *p = v + (size_t)4 * s * s * 4; /* slice 4 */
    double seam_x = 0, inner_x = 0, seam_y = 0, inner_y = 0;
    for (unsigned y = 0; y < s; y++) {
        seam_x += abs(p[4 * (y * s + s - 1) + 3] - p[4 * (y * s + 0) + 3]);
        inner_x += abs(p[4 * (y * s + s / 2 - 1) + 3] - p[4 * (y * s + s / 2) + 3]);
    }
    for (unsigned x = 0; x < s; x++) {
        seam_y += abs(p[4 * ((s - 1) * s + x) + 3] - p[4 * x + 3]);
        inner_y += abs(p[4 * ((s / 2 - 1) * s + x) + 3] - p[4 * (s / 2 * s + x) + 3]);
    }
    printf("  alpha change across the seam %.0f / %.0f, inside %.0f / %.0f\n", seam_x, seam_y,
           inner_x, inner_y);
    CHECK(seam_x < 1.5 * inner_x + 1);
    CHECK(seam_y < 1.5 * inner_y + 1);
    free(v);
}

/* Strands end at random heights and taper: fewer and thinner towards the
 * outermost shell. */
static void furtex_coverage_falls_towards_the_tips(void)
{
    uint8_t *v = make(&base);
    CHECK(v != NULL);
    if (!v) return;
    double low = coverage(v, &base, 1), mid = coverage(v, &base, 9), top = coverage(v, &base, 16);
    printf("  coverage: shell 0 %.3f, shell 8 %.3f, shell 15 %.3f\n", low, mid, top);
    CHECK(low > mid && mid > top);
    CHECK(top > 0.0);
    free(v);
}

static void furtex_density_thickness_and_taper_do_what_they_say(void)
{
    pelt__furtex_desc dense = base, thick = base, blunt = base;
    dense.density *= 2.0f;
    thick.strand_radius *= 2.0f;
    blunt.taper = 0.0f;
    uint8_t *b = make(&base), *d = make(&dense), *t = make(&thick), *u = make(&blunt);
    CHECK(b && d && t && u);
    if (b && d && t && u) {
        double cb = coverage(b, &base, 4), cd = coverage(d, &dense, 4), ct = coverage(t, &thick, 4);
        double tip_b = coverage(b, &base, 12), tip_u = coverage(u, &blunt, 12);
        printf("  shell 3: base %.3f, 2x density %.3f, 2x radius %.3f; shell 11: base %.3f, "
               "no taper %.3f\n", cb, cd, ct, tip_b, tip_u);
        CHECK(cd > cb * 1.3);
        CHECK(ct > cb * 1.3);
        CHECK(tip_u > tip_b * 1.3);
    }
    free(b), free(d), free(t), free(u);
}

/* The texture's size resolves the hairs, it does not make others: the same
 * density (strands per tile) with the radius scaled as the texels shrink
 * draws the same strands (made per 256 texels, a twice as large texture
 * held four times the hairs). A texel's soft edge widens every hair by
 * part of a texel, so the coarser texture covers more; the coverage
 * converges as the size doubles (by less than 60% of the step before). */
static void furtex_size_resolves_the_same_hairs(void)
{
    pelt__furtex_desc d[3] = {base, base, base};
    uint8_t *v[3];
    for (int k = 0; k < 3; k++) {
        d[k].size = base.size << k;
        d[k].strand_radius = base.strand_radius * (float)(1 << k);
        v[k] = make(&d[k]);
        CHECK(v[k] != NULL);
        CHECK(pelt__furtex_strands(&d[k], NULL, 0) == pelt__furtex_strands(&base, NULL, 0));
    }
    if (v[0] && v[1] && v[2]) {
        for (unsigned s = 2; s <= 14; s += 4) {
            double c[3];
            for (int k = 0; k < 3; k++) c[k] = coverage(v[k], &d[k], s);
            printf("  slice %u: coverage %.3f, %.3f, %.3f at %u, %u, %u texels\n", s, c[0], c[1], c[2], d[0].size,
                   d[1].size, d[2].size);
            /* The edge's excess about halves with the texel. */
            CHECK(c[0] > c[1] && c[1] > c[2]);
            CHECK(c[1] - c[2] < 0.6 * (c[0] - c[1]));
        }
    }
    for (int k = 0; k < 3; k++) free(v[k]);
}

static void furtex_rejects_sizes_that_overflow(void)
{
    pelt__furtex_desc huge = base;
    huge.size = 100000;
    CHECK(pelt__furtex_bytes(&huge) == 0);
    huge.size = 0;
    CHECK(pelt__furtex_bytes(&huge) == 0);
}

/* Where strand st's footprint lies in slice `slice` (1..N): the centroid
 * of the texels within 6 texels of `near` whose id is the strand's,
 * weighted by coverage, unwrapped around `near`. False when none is found. */
static bool footprint(const uint8_t *v, const pelt__furtex_desc *d, unsigned slice,
                      const pelt__furtex_strand *st, const float near[2], float out[2])
{
    int s = (int)d->size;
    const uint8_t *p = v + (size_t)slice * (size_t)s * (size_t)s * 4;
    double sx = 0.0, sy = 0.0, sw = 0.0;
    int cx = (int)floorf(near[0]), cy = (int)floorf(near[1]);
    for (int y = cy - 6; y <= cy + 6; y++)
        for (int x = cx - 6; x <= cx + 6; x++) {
            const uint8_t *t = p + 4 * ((size_t)(((y % s) + s) % s) * (size_t)s + (size_t)(((x % s) + s) % s));
            if (t[3] < 40) continue;
            float id = (float)t[2] / (float)t[3];
            if (fabsf(id - st->id) > 2.5f / 255.0f) continue;
            sx += t[3] * (x + 0.5), sy += t[3] * (y + 0.5), sw += t[3];
        }
    if (sw <= 0.0) return false;
    out[0] = (float)(sx / sw), out[1] = (float)(sy / sw);
    return true;
}

/* Lengyel §2.2, curly hair: in a sparse texture each strand's footprint
 * follows pelt__furtex_strand_center from slice to slice, circling its
 * axis with the curl radius; straight strands only drift with their lean;
 * and neighbouring strands are out of step (their curl offsets point
 * every way at one height). */
static void furtex_curly_strands_circle_out_of_step(void)
{
    pelt__furtex_desc curly = {128, 16, 3, 40.0f, 1.0f, 0.0f, 5.0f, 1.0f, false};
    pelt__furtex_desc straight = curly;
    straight.curl_radius = 0.0f;
    uint8_t *vc = make(&curly), *vs = make(&straight);
    pelt__furtex_strand st[64];
    size_t n = pelt__furtex_strands(&curly, st, 64);
    CHECK(vc && vs && n > 20 && n <= 64);
    if (!vc || !vs || n > 64) {
        free(vc), free(vs);
        return;
    }
    double worst = 0.0, sweep_curly = 0.0, sweep_straight = 0.0, cx = 0.0, cy = 0.0;
    size_t followed = 0, offsets = 0;
    for (size_t i = 0; i < n; i++) {
        float lo_c[2] = {0, 0}, lo_s[2] = {0, 0};
        double span_c = 0.0, span_s = 0.0;
        bool first = true;
        for (unsigned slice = 2; slice <= 16; slice += 2) {
            float z = ((float)slice - 0.5f) / 16.0f;
            if (z > st[i].length - 0.05f) break;
            float want[2], flat[2], got_c[2], got_s[2];
            pelt__furtex_strand_center(&curly, &st[i], z, want);
            pelt__furtex_strand_center(&straight, &st[i], z, flat);
            if (!footprint(vc, &curly, slice, &st[i], want, got_c) ||
                !footprint(vs, &straight, slice, &st[i], flat, got_s))
                continue; /* hidden by a neighbour here */
            worst = fmax(worst, hypot(got_c[0] - want[0], got_c[1] - want[1]));
            if (first) memcpy(lo_c, got_c, sizeof lo_c), memcpy(lo_s, got_s, sizeof lo_s), first = false;
            span_c = fmax(span_c, hypot(got_c[0] - lo_c[0], got_c[1] - lo_c[1]));
            span_s = fmax(span_s, hypot(got_s[0] - lo_s[0], got_s[1] - lo_s[1]));
            followed++;
            if (slice == 8) { /* the curl's direction at one height */
                double ox = got_c[0] - got_s[0], oy = got_c[1] - got_s[1], l = hypot(ox, oy);
                if (l > 0.0) cx += ox / l, cy += oy / l, offsets++;
            }
        }
        sweep_curly = fmax(sweep_curly, span_c);
        sweep_straight = fmax(sweep_straight, span_s);
    }
    double resultant = offsets ? hypot(cx, cy) / (double)offsets : 1.0;
    printf("  %zu strands, %zu footprints followed: worst distance from the curve %.2f texels; "
           "widest sweep across the slices %.1f texels curly, %.1f straight; mean direction of "
           "the curl offsets at one height %.2f (1 = all in step)\n",
           n, followed, worst, sweep_curly, sweep_straight, resultant);
    CHECK(followed > 4 * n);
    CHECK(worst < 1.0);
    CHECK(sweep_curly > 1.6 * 5.0);     /* nearly the circle's diameter */
    CHECK(sweep_straight < 0.5 * 5.0);  /* the lean alone */
    CHECK(offsets > n / 2 && resultant < 0.4);
    free(vc), free(vs);
}

/* A wave moves strands along u only; the curl changes nothing else: the
 * skin and a straight texture's strands stay as they were. */
static void furtex_wave_moves_strands_along_u_only(void)
{
    pelt__furtex_desc wavy = {128, 16, 3, 40.0f, 1.0f, 0.0f, 5.0f, 1.0f, true};
    pelt__furtex_strand st[64];
    size_t n = pelt__furtex_strands(&wavy, st, 64);
    CHECK(n > 0 && n <= 64);
    double dv = 0.0, du = 0.0;
    for (size_t i = 0; i < n && i < 64; i++)
        for (int k = 0; k <= 10; k++) {
            float z = (float)k / 10.0f, a[2];
            pelt__furtex_strand_center(&wavy, &st[i], z, a);
            du = fmax(du, fabs(a[0] - (st[i].x + st[i].lean_x * z)));
            dv = fmax(dv, fabs(a[1] - (st[i].y + st[i].lean_y * z)));
        }
    CHECK_NEAR(du, 5.0, 0.05);
    CHECK(dv == 0.0);
    uint8_t *a = make(&wavy), *b = make(&base);
    pelt__furtex_desc base_curled = base;
    base_curled.curl_radius = 3.0f;
    uint8_t *c = make(&base_curled);
    CHECK(a && b && c);
    if (b && c) {
        size_t skin = (size_t)base.size * base.size * 4;
        CHECK(memcmp(b, c, skin) == 0);                              /* the same skin */
        CHECK(memcmp(b + skin, c + skin, pelt__furtex_bytes(&base) - skin) != 0); /* other hair */
    }
    free(a), free(b), free(c);
}

/* Vector correlation of the curl offsets of each strand and its nearest
 * neighbour (toroidal distance), over the heights of `heights`:
 * sum a.b / sqrt(sum |a|^2 sum |b|^2). 1 when every pair moves alike. */
static double neighbour_correlation(const pelt__furtex_strand *st, size_t n, float size,
                                    const float (*offset)[4][2])
{
    double ab = 0.0, aa = 0.0, bb = 0.0;
    for (size_t i = 0; i < n; i++) {
        size_t best = i;
        float best_d = INFINITY;
        for (size_t j = 0; j < n; j++) {
            if (j == i) continue;
            float dx = fabsf(st[i].x - st[j].x), dy = fabsf(st[i].y - st[j].y);
            dx = fminf(dx, size - dx), dy = fminf(dy, size - dy);
            if (dx * dx + dy * dy < best_d) best_d = dx * dx + dy * dy, best = j;
        }
        for (int k = 0; k < 4; k++) {
            const float *a = offset[i][k], *b = offset[best][k];
            ab += a[0] * b[0] + a[1] * b[1];
            aa += a[0] * a[0] + a[1] * a[1];
            bb += b[0] * b[0] + b[1] * b[1];
        }
    }
    return aa > 0.0 && bb > 0.0 ? ab / sqrt(aa * bb) : 0.0;
}

/* Ringlets (beyond Silva Eq. 4, docs/method.md): each strand's curl offset
 * phi(h) at h = 0.25 .. 1, with K_alpha 12 texels and two turns. As
 * printed, Eq. 4 moves the shells at a vertex, so every strand near it
 * takes the same offset: neighbours correlate fully. With the strands'
 * own phases the correlation of neighbours falls below 0.2; and a sparse
 * texture drawn with ringlets holds each strand where its offset says. */
static void ringlets_turn_neighbouring_strands_out_of_step(void)
{
    enum { MAX = 4000 };
    const float K = 12.0f, omega = 12.566371f;
    pelt__furtex_desc d = {256, 16, 5, 3000.0f, 1.6f, 0.8f, 0.0f, 2.0f, false, K, omega};
    pelt__furtex_desc flat = d;
    flat.ringlet_radius = 0.0f;
    static pelt__furtex_strand st[MAX];
    static float coherent[MAX][4][2], ringlet[MAX][4][2];
    size_t n = pelt__furtex_strands(&d, st, MAX);
    CHECK(n > 1000 && n <= MAX);
    if (n > MAX) return;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 4; k++) {
            float h = 0.25f * (float)(k + 1), a[2], b[2];
            /* Eq. 4 as printed: the vertex's phi, the texture's axes as u, v. */
            pelt_vec3 phi = pelt__fur_curl(v3(1, 0, 0), v3(0, 1, 0), omega, K, 0.0f, h);
            coherent[i][k][0] = phi.x, coherent[i][k][1] = phi.y;
            pelt__furtex_strand_center(&d, &st[i], h, a);
            pelt__furtex_strand_center(&flat, &st[i], h, b);
            ringlet[i][k][0] = a[0] - b[0], ringlet[i][k][1] = a[1] - b[1];
        }
    double c_coherent = neighbour_correlation(st, n, 256.0f, (const float (*)[4][2])coherent);
    double c_ringlet = neighbour_correlation(st, n, 256.0f, (const float (*)[4][2])ringlet);
    printf("  %zu strands: correlation of neighbours' curl offsets %.3f coherent (Eq. 4 as printed), "
           "%.3f ringlets\n", n, c_coherent, c_ringlet);
    CHECK(c_coherent > 0.999);
    CHECK(fabs(c_ringlet) < 0.2);

    /* What the texture draws: a sparse one with ringlets, footprints on
     * their curves, and those of neighbouring strands apart. */
    pelt__furtex_desc sparse = {128, 16, 3, 40.0f, 1.0f, 0.0f, 0.0f, 2.0f, false, 6.0f, omega};
    uint8_t *v = make(&sparse);
    pelt__furtex_strand sp[64];
    size_t m = pelt__furtex_strands(&sparse, sp, 64);
    CHECK(v && m > 20 && m <= 64);
    double worst = 0.0;
    size_t followed = 0;
    for (size_t i = 0; v && i < m && i < 64; i++)
        for (unsigned slice = 4; slice <= 16; slice += 4) {
            float z = ((float)slice - 0.5f) / 16.0f, want[2], got[2];
            if (z > sp[i].length - 0.05f) break;
            pelt__furtex_strand_center(&sparse, &sp[i], z, want);
            if (!footprint(v, &sparse, slice, &sp[i], want, got)) continue;
            worst = fmax(worst, hypot(got[0] - want[0], got[1] - want[1]));
            followed++;
        }
    printf("  sparse texture: %zu footprints within %.2f texels of their ringlet\n", followed, worst);
    CHECK(followed > 2 * m);
    CHECK(worst < 1.0);
    free(v);
}

/* The correlation of the curl offsets (h = 1/4 .. 1) of the strand pairs
 * whose roots lie lo to hi texels apart (toroidal), as
 * neighbour_correlation takes it. */
static double band_correlation(const pelt__furtex_desc *d, const pelt__furtex_strand *st, size_t n, float lo,
                               float hi)
{
    pelt__furtex_desc flat = *d;
    flat.ringlet_radius = 0.0f;
    double ab = 0.0, aa = 0.0, bb = 0.0;
    float size = (float)d->size;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++) {
            float dx = fabsf(st[i].x - st[j].x), dy = fabsf(st[i].y - st[j].y);
            dx = fminf(dx, size - dx), dy = fminf(dy, size - dy);
            float r = sqrtf(dx * dx + dy * dy);
            if (r < lo || r >= hi) continue;
            for (int k = 1; k <= 4; k++) {
                float h = 0.25f * (float)k, a[2], a0[2], b[2], b0[2];
                pelt__furtex_strand_center(d, &st[i], h, a);
                pelt__furtex_strand_center(&flat, &st[i], h, a0);
                pelt__furtex_strand_center(d, &st[j], h, b);
                pelt__furtex_strand_center(&flat, &st[j], h, b0);
                double ax = a[0] - a0[0], ay = a[1] - a0[1], bx = b[0] - b0[0], by = b[1] - b0[1];
                ab += ax * bx + ay * by, aa += ax * ax + ay * ay, bb += bx * bx + by * by;
            }
        }
    return aa > 0.0 && bb > 0.0 ? ab / sqrt(aa * bb) : 0.0;
}

/* Ringlets in locks (docs/method.md): strands a lock's width apart or
 * less curl in step, strands several locks apart do not, and the lock
 * follows the curl's radius, so a few large curls make wide locks and
 * many small ones narrow locks (Silva Fig. 7 c, d tell apart). The ids
 * stay uniform, so grooming's density still thins by id. */
static void ringlets_gather_in_locks(void)
{
    enum { MAX = 2000 };
    const float omega = 12.566371f;
    static pelt__furtex_strand st[MAX];
    /* Large curls: K 12 texels, locks about 24 across; small: K 4, about 8. */
    pelt__furtex_desc large = {256, 16, 5, 2000.0f, 1.6f, 0.8f, 0.0f, 2.0f, false, 12.0f, omega, 24.0f};
    pelt__furtex_desc small = large;
    small.ringlet_radius = 4.0f, small.ringlet_lock = 8.0f;
    pelt__furtex_desc loose = large;
    loose.ringlet_lock = 0.0f;
    size_t n = pelt__furtex_strands(&large, st, MAX);
    CHECK(n == 2000);
    int cells_large = pelt__furtex_lock_cells(&large), cells_small = pelt__furtex_lock_cells(&small);
    printf("  locks a side: %d with K 12 texels, %d with K 4, %d without locks\n", cells_large, cells_small,
           pelt__furtex_lock_cells(&loose));
    CHECK(cells_large == 11 && cells_small == 32 && pelt__furtex_lock_cells(&loose) == 0);
    /* Wet fur's curl levels (smaller radii, the same locks) keep every
     * strand's id, so a hair stays the same hair as the curl comes out. */
    static pelt__furtex_strand half[MAX];
    pelt__furtex_desc half_curl = large, no_curl = large;
    half_curl.ringlet_radius = 6.0f, no_curl.ringlet_radius = 0.0f;
    (void)pelt__furtex_strands(&large, st, MAX);
    bool same_ids = pelt__furtex_strands(&half_curl, half, MAX) == n;
    for (size_t i = 0; i < n && same_ids; i++) same_ids = half[i].id == st[i].id;
    (void)pelt__furtex_strands(&no_curl, half, MAX);
    for (size_t i = 0; i < n && same_ids; i++) same_ids = half[i].id == st[i].id;
    CHECK(same_ids);

    double near_large = band_correlation(&large, st, n, 0.0f, 4.0f);
    double far_large = band_correlation(&large, st, n, 72.0f, 96.0f);
    double mid_large = band_correlation(&large, st, n, 8.0f, 12.0f);
    size_t ns = pelt__furtex_strands(&small, st, MAX);
    CHECK(ns == n);
    double near_small = band_correlation(&small, st, n, 0.0f, 4.0f);
    double mid_small = band_correlation(&small, st, n, 8.0f, 12.0f);
    (void)pelt__furtex_strands(&loose, st, MAX);
    double near_loose = band_correlation(&loose, st, n, 0.0f, 4.0f);
    printf("  curl offsets' correlation: large curls %.3f within 4 texels, %.3f at 8-12, %.3f at 72-96; "
           "small curls %.3f within 4, %.3f at 8-12; without locks %.3f within 4\n",
           near_large, mid_large, far_large, near_small, mid_small, near_loose);
    CHECK(near_large > 0.6);            /* a lock curls in step */
    CHECK(fabs(far_large) < 0.2);       /* locks apart do not */
    CHECK(mid_large > 0.3);             /* a wide lock spans 8-12 texels */
    CHECK(mid_small < 0.5 * mid_large); /* a narrow one does not */
    CHECK(near_small > 0.3);
    CHECK(fabs(near_loose) < 0.2); /* "strands": every strand its own */

    /* Grooming's density keeps the strands whose id is below it: the
     * share it keeps stays the density (within 0.05). */
    (void)pelt__furtex_strands(&large, st, MAX);
    for (int q = 1; q <= 3; q++) {
        float density = 0.25f * (float)q;
        size_t kept = 0;
        for (size_t i = 0; i < n; i++) kept += st[i].id < density;
        printf("  density %.2f keeps %.3f of the strands\n", density, (double)kept / (double)n);
        CHECK(fabs((double)kept / (double)n - density) < 0.05);
    }
}

/* A hair is opaque however it runs. A curled strand sweeps across many
 * texels within one slice's slab, each covered by only a few of the
 * slice's sub-samples: its slices must still hold it as opaque as a
 * straight strand's (giving every hit the same share drew curls a third
 * as opaque, and curly fur read as felt). Measured at each strand's
 * centre half-way up slices of a sparse texture, ringlets of a few large
 * curls (Fig. 7c's shape at the default tiling) and the texture's own
 * curl against straight strands. */
static double centre_alpha(const pelt__furtex_desc *d)
{
    uint8_t *v = make(d);
    pelt__furtex_strand st[64];
    size_t m = pelt__furtex_strands(d, st, 64);
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; v && i < m && i < 64; i++)
        for (unsigned slice = 4; slice <= d->layers / 2; slice += 4) {
            float z = ((float)slice - 0.5f) / (float)d->layers, c[2];
            if (z > st[i].length - 0.05f) break;
            pelt__furtex_strand_center(d, &st[i], z, c);
            int x = ((int)floorf(c[0]) % (int)d->size + (int)d->size) % (int)d->size;
            int y = ((int)floorf(c[1]) % (int)d->size + (int)d->size) % (int)d->size;
            sum += v[(((size_t)slice * d->size + (size_t)y) * d->size + (size_t)x) * 4 + 3] / 255.0;
            n++;
        }
    free(v);
    return n ? sum / (double)n : 0.0;
}

static void furtex_curled_strands_are_as_opaque_as_straight_ones(void)
{
    pelt__furtex_desc straight = {128, 32, 3, 40.0f, 1.6f, 0.0f, 0.0f, 2.0f, false, 0.0f, 0.0f};
    pelt__furtex_desc ringlets = straight, curled = straight;
    ringlets.ringlet_radius = 40.0f, ringlets.ringlet_omega = 12.566371f;
    curled.curl_radius = 6.0f, curled.curl_turns = 3.0f;
    double a_straight = centre_alpha(&straight), a_ringlets = centre_alpha(&ringlets),
           a_curled = centre_alpha(&curled);
    printf("  alpha at a strand's centre: straight %.3f, ringlets %.3f, texture curl %.3f\n", a_straight,
           a_ringlets, a_curled);
    CHECK(a_straight > 0.85);
    CHECK(a_ringlets > 0.9 * a_straight);
    CHECK(a_curled > 0.9 * a_straight);
    CHECK(pelt__furtex_hit_weight(0.0f, 1.6f, 4) == 0.5f); /* straight: four hits of a half */
}

/* The slope the shells light the texture's own curl with (its helix or
 * wave, look.strand_curl) is the derivative of the curl each strand of the
 * texture is drawn along, with the strand's own phase: the centre's
 * offset from its leaning axis, differenced over the height. */
static void strand_curl_slope_is_the_drawn_curl_derivative(void)
{
    double worst = 0.0, largest = 0.0;
    for (int wave = 0; wave < 2; wave++) {
        pelt__furtex_desc d = base;
        d.curl_radius = 5.0f;
        d.curl_turns = 3.0f;
        d.curl_wave = wave != 0;
        pelt__furtex_strand st[40];
        size_t n = pelt__furtex_strands(&d, st, 40);
        CHECK(n >= 40);
        for (size_t i = 0; i < 40; i++)
            for (int k = 1; k < 20; k++) {
                float z = (float)k / 20.0f, dz = 1e-3f, a[2], b[2], slope[2];
                pelt__furtex_strand_center(&d, &st[i], z - dz, a);
                pelt__furtex_strand_center(&d, &st[i], z + dz, b);
                /* less the lean, which the slope leaves to the strand's axis */
                float fd[2] = {(b[0] - a[0]) / (2.0f * dz) - st[i].lean_x, (b[1] - a[1]) / (2.0f * dz) - st[i].lean_y};
                pelt__strand_curl_slope(d.curl_radius, 6.2831853f * d.curl_turns, d.curl_wave, z, st[i].phase, slope);
                worst = fmax(worst, fmax(fabs(fd[0] - slope[0]), fabs(fd[1] - slope[1])));
                largest = fmax(largest, fabs(slope[0]));
            }
    }
    printf("  slopes up to %.1f texels per unit height; worst |finite difference - slope| = %.3g\n", largest, worst);
    CHECK(largest > 50.0);
    CHECK(worst < 0.05 * largest);
}

/* The volume's mip chain: coverage, shade and height are each block's mean
 * (rounded up), the id is the most covering hair's, never a mix. A slice of
 * the real volume, taken down to 8 x 8 texels. */
static void furtex_mip_chain_keeps_a_real_hair_id(void)
{
    uint8_t *v = make(&base);
    CHECK(v != NULL);
    if (!v) return;
    unsigned n = base.size;
    const uint8_t *slice = v + (size_t)4 * n * n * 4; /* layer 3 of 16 */
    /* The ids that occur at the finest level. */
    bool present[256] = {false};
    for (size_t i = 0; i < (size_t)n * n; i++) {
        const uint8_t *t = slice + i * 4;
        if (t[3] >= 128) present[(t[2] * 255 + t[3] / 2) / t[3]] = true;
    }
    uint8_t *a = malloc((size_t)n * n * 2), *b = malloc((size_t)n * n * 2);
    CHECK(a && b);
    const uint8_t *up = slice;
    uint8_t *down = a;
    unsigned mixed_mean = 0, mixed_top = 0, blocks = 0;
    for (unsigned side = n; side > 8; side /= 2) {
        pelt__fur_gpu_mip_down(up, side, side, down);
        unsigned half = side / 2;
        for (unsigned y = 0; y < half; y++) {
            for (unsigned x = 0; x < half; x++) {
                const uint8_t *o = down + ((size_t)y * half + x) * 4;
                unsigned sum[4] = {0, 0, 0, 0}, top = 0;
                for (unsigned k = 0; k < 4; k++) {
                    const uint8_t *t = up + ((size_t)(2 * y + k / 2) * side + 2 * x + k % 2) * 4;
                    for (int c = 0; c < 4; c++) sum[c] += t[c];
                    if (t[3] > up[((size_t)(2 * y + top / 2) * side + 2 * x + top % 2) * 4 + 3]) top = k;
                }
                CHECK(o[3] == (sum[3] + 3) / 4 && o[0] == (sum[0] + 3) / 4 && o[1] == (sum[1] + 3) / 4);
                CHECK(o[2] <= o[3]);
                if (o[3] < 128) continue;
                /* At the first level down, where the id still sits on 8
                   bits, it is one the finest level has; the mean of the
                   block's ids often is not. */
                if (side == n) {
                    blocks++;
                    unsigned id = (o[2] * 255 + o[3] / 2) / o[3];
                    bool near = false;
                    for (int e = -2; e <= 2; e++)
                        if ((int)id + e >= 0 && (int)id + e < 256 && present[id + e]) near = true;
                    mixed_top += !near;
                    unsigned mean = (sum[2] * 255 + sum[3] / 2) / sum[3];
                    bool mean_near = false;
                    const uint8_t *t0 = up + ((size_t)(2 * y + top / 2) * side + 2 * x + top % 2) * 4;
                    unsigned top_id = (t0[2] * 255 + t0[3] / 2) / t0[3];
                    mean_near = mean + 2 >= top_id && mean <= top_id + 2;
                    mixed_mean += !mean_near;
                    CHECK(id + 2 >= top_id && id <= top_id + 2);
                }
            }
        }
        up = down;
        down = down == a ? b : a;
    }
    CHECK(blocks > 100);
    CHECK(mixed_top == 0);
    CHECK(mixed_mean > blocks / 20); /* where hairs meet, a mean is no hair's id */
    free(a);
    free(b);
    free(v);
}

int main(void)
{
    RUN(furtex_innermost_slice_is_opaque_skin);
    RUN(furtex_is_deterministic_per_seed);
    RUN(furtex_tiles_without_a_seam);
    RUN(furtex_coverage_falls_towards_the_tips);
    RUN(furtex_density_thickness_and_taper_do_what_they_say);
    RUN(furtex_size_resolves_the_same_hairs);
    RUN(furtex_rejects_sizes_that_overflow);
    RUN(furtex_curly_strands_circle_out_of_step);
    RUN(ringlets_gather_in_locks);
    RUN(furtex_wave_moves_strands_along_u_only);
    RUN(furtex_mip_chain_keeps_a_real_hair_id);
    RUN(ringlets_turn_neighbouring_strands_out_of_step);
    RUN(furtex_curled_strands_are_as_opaque_as_straight_ones);
    RUN(strand_curl_slope_is_the_drawn_curl_derivative);
    return check_summary();
}
