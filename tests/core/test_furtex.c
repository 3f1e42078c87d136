/* Fur texture synthesis (Lengyel et al. 2001 §2.2). */
#include "support/check.h"

#include "core/fur/furtex.h"

#include <stdlib.h>
#include <string.h>

static uint8_t *make(const pelt__furtex_desc *d)
{
    uint8_t *v = malloc(pelt__furtex_bytes(d));
    if (v) pelt__furtex_generate(d, v);
    return v;
}

static const pelt__furtex_desc base = {128, 16, 7, 3000.0f, 1.6f, 0.8f};

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

static void furtex_rejects_sizes_that_overflow(void)
{
    pelt__furtex_desc huge = base;
    huge.size = 100000;
    CHECK(pelt__furtex_bytes(&huge) == 0);
    huge.size = 0;
    CHECK(pelt__furtex_bytes(&huge) == 0);
}

int main(void)
{
    RUN(furtex_innermost_slice_is_opaque_skin);
    RUN(furtex_is_deterministic_per_seed);
    RUN(furtex_tiles_without_a_seam);
    RUN(furtex_coverage_falls_towards_the_tips);
    RUN(furtex_density_thickness_and_taper_do_what_they_say);
    RUN(furtex_rejects_sizes_that_overflow);
    return check_summary();
}
