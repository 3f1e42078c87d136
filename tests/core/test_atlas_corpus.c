/* Atlas over every triangle mesh of Debian's libcgal-demo data archive that
 * loads: no flipped triangle, no texel claimed by two triangles at the mask
 * resolution, area-stretch statistics printed. Failures name the mesh. */
#define _POSIX_C_SOURCE 200809L /* opendir, stat */
#include "pelt/atlas.h"

#include "support/check.h"
#include "support/corpus.h"
#include "core/mesh/mesh_internal.h"

#include <stdlib.h>
#include <string.h>

#define CORPUS_DIR PELT_TEST_OUT "/atlas_corpus"
/* Keeps the run under a minute under ASan (the largest corpus mesh has
 * 88,928 triangles): bigger meshes would be listed as
 * skipped (the 365k-triangle timing is measured separately, in Release). */
#define MAX_TRIANGLES 100000

static void cgal_meshes_atlas_has_no_flip_and_no_overlap(void)
{
    char *names[1024];
    long listed = corpus_list(CORPUS_DIR, names, 1024);
    CHECK(listed >= 0);
    if (listed < 0) return;
    size_t count = (size_t)listed;
    size_t built = 0, skipped = 0, failed = 0;
    double worst = 0;
    printf("  %-30s %8s %7s %7s %6s %6s %6s %7s\n", "mesh", "tris", "patches", "mask", "min", "mean",
           "max", "seconds");
    for (size_t i = 0; i < count; i++) {
        char path[2048];
        snprintf(path, sizeof path, "%s/data/meshes/%s", CORPUS_DIR, names[i]);
        pelt_mesh *m = NULL;
        if (pelt_mesh_load(path, &m, NULL) != PELT_OK) { /* not a triangle mesh pelt loads */
            free(names[i]);
            continue;
        }
        if (m->triangle_count > MAX_TRIANGLES) {
            printf("  %-30s %8zu skipped (over %d triangles)\n", names[i], m->triangle_count, MAX_TRIANGLES);
            skipped++;
        } else {
            pelt_atlas_desc d = {.mode = PELT_ATLAS_PATCHES};
            pelt_atlas *a = NULL;
            pelt_error e = {0};
            pelt_status st = pelt_atlas_create(m, &d, &a, &e);
            if (st != PELT_OK) {
                fprintf(stderr, "  %s: atlas failed: %s\n", names[i], e.message);
                CHECK(st == PELT_OK);
                failed++;
            } else {
                const pelt_atlas_stats *s = pelt_atlas_get_stats(a);
                pelt_atlas_check c = {0};
                CHECK(pelt_atlas_check_uvs(pelt_atlas_mesh(a), s->mask_size, &c, NULL) == PELT_OK);
                printf("  %-30s %8zu %7zu %7u %6.3f %6.3f %6.2f %7.2f\n", names[i], m->triangle_count,
                       s->patch_count, s->mask_size, (double)s->stretch_min, (double)s->stretch_mean,
                       (double)s->stretch_max, s->build_seconds);
                /* Zero uv area (a sliver below float precision of the atlas)
                 * claims no texel and is not flipped: reported, not failed. */
                if (c.degenerate)
                    printf("  %s: %zu triangles of zero atlas area\n", names[i], c.degenerate);
                if (c.flipped || c.overlap_texels || c.outside) {
                    fprintf(stderr, "  %s: %zu flipped, %zu texels claimed twice, %zu outside, %zu degenerate\n",
                            names[i], c.flipped, c.overlap_texels, c.outside, c.degenerate);
                    failed++;
                }
                CHECK(c.flipped == 0);
                CHECK(c.overlap_texels == 0);
                CHECK(c.outside == 0);
                if (s->stretch_max > worst) worst = s->stretch_max;
                built++;
            }
            pelt_atlas_destroy(a);
        }
        pelt_mesh_destroy(m);
        free(names[i]);
    }
    printf("  %zu atlases built, %zu failed, %zu skipped as too big; worst max area stretch %.2f\n",
           built, failed, skipped, worst);
    CHECK(built > 0);
}

int main(void)
{
    if (!corpus_available()) {
        return check_skip("libcgal-demo is not installed (" CGAL_ARCHIVE " is missing)");
    }
    RUN(cgal_meshes_atlas_has_no_flip_and_no_overlap);
    return check_summary();
}
