/* The one welder (core/base/weld.h): what counts as the same point, the
 * canonical index, dense ids and the ascending chains. */
#include "support/check.h"

#include "core/base/weld.h"
#include "core/base/rng.h"
#include "pelt/mesh.h"

#include <stdlib.h>
#include <string.h>

/* Brute force: the smallest index whose key equals i's, component by
 * component as floats. */
static uint32_t brute_canon(const float *p, const float *n, size_t i)
{
    for (size_t j = 0; j < i; j++) {
        bool same = true;
        for (int k = 0; k < 3; k++) same = same && p[3 * j + k] == p[3 * i + k];
        for (int k = 0; n && k < 3; k++) same = same && n[3 * j + k] == n[3 * i + k];
        if (same) return (uint32_t)j;
    }
    return (uint32_t)i;
}

static void weld_canon_is_smallest_index_at_the_same_position(void)
{
    /* 0, 2 and 5 at one point, 1 and 4 at another, 3 alone. */
    const float p[] = {1, 2, 3, 4, 5, 6, 1, 2, 3, 7, 8, 9, 4, 5, 6, 1, 2, 3};
    uint32_t canon[6];
    CHECK(pelt__weld(p, NULL, 6, canon));
    const uint32_t expect[] = {0, 1, 0, 3, 1, 0};
    CHECK(memcmp(canon, expect, sizeof expect) == 0);
}

static void weld_treats_minus_zero_as_zero_and_nan_as_alone(void)
{
    const float nan = NAN;
    const float p[] = {0.0f, 1, 0, -0.0f, 1, -0.0f, nan, 0, 0, nan, 0, 0, 1e-30f, 1, 0};
    uint32_t canon[5];
    CHECK(pelt__weld(p, NULL, 5, canon));
    CHECK(canon[1] == 0); /* -0 is +0 */
    CHECK(canon[2] == 2); /* a NaN equals nothing, itself included */
    CHECK(canon[3] == 3);
    CHECK(canon[4] == 4); /* no tolerance: 1e-30 is not 0 */
}

static void weld_with_normals_splits_a_crease(void)
{
    /* One point with two normals (a hard edge), twice each. */
    const float p[] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    const float n[] = {0, 1, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0};
    uint32_t canon[4];
    CHECK(pelt__weld(p, n, 4, canon));
    const uint32_t expect[] = {0, 1, 0, 1};
    CHECK(memcmp(canon, expect, sizeof expect) == 0);
    CHECK(pelt__weld(p, NULL, 4, canon));
    for (int i = 0; i < 4; i++) CHECK(canon[i] == 0);
}

static void weld_ids_are_dense_in_order_of_first_vertex(void)
{
    const uint32_t canon[] = {0, 1, 0, 3, 1, 0, 6};
    uint32_t ids[7];
    CHECK(pelt__weld_ids(canon, 7, ids) == 4);
    const uint32_t expect[] = {0, 1, 0, 2, 1, 0, 3};
    CHECK(memcmp(ids, expect, sizeof expect) == 0);
    uint32_t in_place[7];
    memcpy(in_place, canon, sizeof canon);
    CHECK(pelt__weld_ids(in_place, 7, in_place) == 4);
    CHECK(memcmp(in_place, expect, sizeof expect) == 0);
}

static void weld_chain_walks_each_group_in_ascending_order(void)
{
    const uint32_t canon[] = {0, 1, 0, 3, 1, 0, 6};
    uint32_t next[7];
    pelt__weld_chain(canon, 7, next);
    const uint32_t N = PELT__WELD_NONE;
    const uint32_t expect[] = {2, 4, 5, N, N, N, N};
    CHECK(memcmp(next, expect, sizeof expect) == 0);
}

/* Random points from a small lattice (many repeats, some -0), with and
 * without normals: the hash welder agrees with the brute-force definition,
 * and every chain visits exactly its group, ascending. */
static void weld_matches_brute_force_on_random_repeats(void)
{
    enum { N = 3000 };
    float *p = malloc(N * 3 * sizeof *p), *n = malloc(N * 3 * sizeof *n);
    uint32_t *canon = malloc(N * sizeof *canon), *next = malloc(N * sizeof *next);
    pelt__rng r = pelt__rng_seed(5, 17);
    for (size_t i = 0; i < 3 * N; i++) {
        float v = (float)(pelt__rng_next(&r) % 5) - 2.0f;
        p[i] = v == 0.0f && pelt__rng_next(&r) % 2 ? -0.0f : v;
        n[i] = (float)(pelt__rng_next(&r) % 2);
    }
    for (int with_normals = 0; with_normals < 2; with_normals++) {
        const float *nn = with_normals ? n : NULL;
        CHECK(pelt__weld(p, nn, N, canon));
        size_t bad = 0;
        for (size_t i = 0; i < N; i++) bad += canon[i] != brute_canon(p, nn, i);
        CHECK(bad == 0);
        pelt__weld_chain(canon, N, next);
        size_t visited = 0, disorder = 0;
        for (size_t c = 0; c < N; c++) {
            if (canon[c] != c) continue;
            uint32_t prev = 0;
            for (uint32_t v = (uint32_t)c; v != PELT__WELD_NONE; v = next[v]) {
                visited++;
                disorder += canon[v] != c || (v != c && v <= prev);
                prev = v;
            }
        }
        CHECK(visited == N);
        CHECK(disorder == 0);
    }
    free(p), free(n), free(canon), free(next);
}

/* The shipped path: the torus's seam copies (u = 0 and u = 1 columns) weld to
 * the first column, so the mesh gives them one normal and tangent. */
static void weld_finds_the_torus_seam(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 30, 20, &m, NULL) == PELT_OK);
    if (!m) return;
    pelt_mesh_data d = pelt_mesh_get_data(m);
    uint32_t *canon = malloc(d.vertex_count * sizeof *canon);
    uint32_t *ids = malloc(d.vertex_count * sizeof *ids);
    CHECK(pelt__weld(d.positions, NULL, d.vertex_count, canon));
    size_t groups = pelt__weld_ids(canon, d.vertex_count, ids);
    /* (30 + 1) x (20 + 1) grid vertices, the last row and column repeat the first. */
    CHECK(d.vertex_count == 31 * 21);
    CHECK(groups == 30 * 20);
    size_t bad = 0;
    for (size_t i = 0; i < d.vertex_count; i++)
        if (canon[i] != i) {
            bad += memcmp(d.positions + 3 * i, d.positions + 3 * canon[i], 12) != 0;
            bad += memcmp(d.normals + 3 * i, d.normals + 3 * canon[i], 12) != 0;
            bad += memcmp(pelt_mesh_tangents(m) + 4 * i, pelt_mesh_tangents(m) + 4 * canon[i], 16) != 0;
        }
    CHECK(bad == 0);
    free(canon), free(ids);
    pelt_mesh_destroy(m);
}

int main(void)
{
    RUN(weld_canon_is_smallest_index_at_the_same_position);
    RUN(weld_treats_minus_zero_as_zero_and_nan_as_alone);
    RUN(weld_with_normals_splits_a_crease);
    RUN(weld_ids_are_dense_in_order_of_first_vertex);
    RUN(weld_chain_walks_each_group_in_ascending_order);
    RUN(weld_matches_brute_force_on_random_repeats);
    RUN(weld_finds_the_torus_seam);
    return check_summary();
}
