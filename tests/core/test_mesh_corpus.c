/* Loads every mesh of Debian's libcgal-demo data archive (real OFF, PLY
 * and STL files: elephant, bunny, lion...). A file may be refused, but only
 * with a clean PELT_ERR_FORMAT whose message names it; OFF files with
 * triangle-only faces must keep every face (kept + dropped = declared). */
#define _POSIX_C_SOURCE 200809L /* popen-free: opendir, stat */
#include "support/check.h"
#include "support/corpus.h"

#include "core/mesh/mesh_internal.h"

#include <stdlib.h>
#include <string.h>

#define CORPUS_DIR PELT_TEST_OUT "/cgal_corpus"

/* Faces of an OFF file whose faces are all triangles, or -1 when it has
 * polygons (assimp's ear clipping may drop slivers of those) or cannot be
 * read this simply. Read with fscanf, independent of the loader under test. */
static long long off_declared_triangles(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    char word[64];
    long long nv, nf, ne, total = 0;
    int ok = fscanf(f, "%63s", word) == 1 && strcmp(word, "OFF") == 0 &&
             fscanf(f, "%lld %lld %lld", &nv, &nf, &ne) == 3;
    for (long long v = 0; ok && v < nv; v++) {
        double x, y, z;
        ok = fscanf(f, "%lf %lf %lf", &x, &y, &z) == 3;
        int c;
        while (ok && (c = fgetc(f)) != '\n' && c != EOF) {} /* extra per-vertex values */
    }
    for (long long t = 0; ok && t < nf; t++) {
        long long n;
        ok = fscanf(f, "%lld", &n) == 1 && n == 3;
        total++;
        int c;
        while (ok && (c = fgetc(f)) != '\n' && c != EOF) {}
    }
    fclose(f);
    return ok ? total : -1;
}

static void cgal_meshes_load_or_fail_cleanly(void)
{
    char *names[1024];
    long listed = corpus_list(CORPUS_DIR, names, 1024);
    CHECK(listed >= 0);
    if (listed < 0) return;
    size_t count = (size_t)listed;
    size_t loaded = 0, refused = 0, compared = 0;
    for (size_t i = 0; i < count; i++) {
        char path[2048];
        snprintf(path, sizeof path, "%s/data/meshes/%s", CORPUS_DIR, names[i]);
        pelt_mesh *m = NULL;
        pelt_error e = {0};
        pelt_status st = pelt_mesh_load(path, &m, &e);
        if (st == PELT_OK) {
            pelt_mesh_stats s = pelt_mesh_get_stats(m);
            printf("  %-36s %8zu triangles %6zu dropped\n", names[i], s.triangle_count,
                   s.dropped_degenerate);
            long long want = corpus_has_suffix(names[i], ".off") ? off_declared_triangles(path) : -1;
            if (want >= 0) {
                compared++;
                if ((long long)(s.triangle_count + s.dropped_degenerate) != want) {
                    fprintf(stderr, "  %s: %zu kept + %zu dropped, the file declares %lld\n", names[i],
                            s.triangle_count, s.dropped_degenerate, want);
                    CHECK((long long)(s.triangle_count + s.dropped_degenerate) == want);
                }
            }
            loaded++;
        } else {
            printf("  %-36s refused: %s\n", names[i], e.message);
            int clean = st == PELT_ERR_FORMAT && strstr(e.message, names[i]) != NULL;
            if (!clean) fprintf(stderr, "  %s: status %d is not a clean format error\n", names[i], st);
            CHECK(clean);
            CHECK(m == NULL);
            refused++;
        }
        pelt_mesh_destroy(m);
        free(names[i]);
    }
    printf("  %zu meshes: %zu loaded (%zu checked against their OFF face count), %zu refused\n",
           count, loaded, compared, refused);
    CHECK(count > 0);
    CHECK(loaded > refused); /* the archive is real meshes: most must load */
}

int main(void)
{
    if (!corpus_available()) {
        return check_skip("libcgal-demo is not installed (" CGAL_ARCHIVE " is missing)");
    }
    RUN(cgal_meshes_load_or_fail_cleanly);
    return check_summary();
}
