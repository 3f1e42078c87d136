/* Ray casts through the BVH agree with testing every triangle. */
#include "support/check.h"
#include "core/mesh/mesh_internal.h"
#include "core/mesh/raycast.h"

#include <stdlib.h>
#include <time.h>

static double now_s(void)
{
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static uint64_t lcg(uint64_t *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return *s >> 33;
}

/* Uniform in [-1, 1]. */
static float sym(uint64_t *s) { return (float)lcg(s) / 2147483648.0f * 2.0f - 1.0f; }

/* Random rays from a box of side 2*spread around the origin toward random
 * points near the mesh, plus some in fully random directions. */
static void random_ray(uint64_t *s, float spread, float aim, float o[3], float d[3])
{
    for (int a = 0; a < 3; a++) o[a] = spread * sym(s);
    bool aimed = lcg(s) % 4 != 0;
    for (int a = 0; a < 3; a++) d[a] = aimed ? aim * sym(s) - o[a] : sym(s);
}

/* Compares BVH and brute force over `rays` random rays; returns how many
 * rays hit. */
static int compare_rays(const pelt_mesh *mesh, const pelt__bvh *bvh, int rays, uint64_t seed,
                        float spread, float aim)
{
    int hits = 0, same_tri = 0;
    for (int i = 0; i < rays; i++) {
        float o[3], d[3];
        random_ray(&seed, spread, aim, o, d);
        pelt__hit a = {0}, b = {0};
        bool ha = pelt__bvh_raycast(bvh, o, d, INFINITY, &a);
        bool hb = pelt__raycast_brute(mesh, o, d, INFINITY, &b);
        CHECK(ha == hb);
        if (!ha || !hb) continue;
        hits++;
        /* Same arithmetic per triangle: the closest t matches exactly; the
         * triangle may differ only when the ray crosses a shared edge. */
        CHECK(a.t == b.t);
        if (a.triangle == b.triangle) same_tri++;
        CHECK_NEAR(a.bary[0] + a.bary[1] + a.bary[2], 1.0, 1e-5);
        /* The hit point reconstructed from barycentrics lies on the ray. */
        const uint32_t *ix = mesh->indices + a.triangle * 3;
        for (int k = 0; k < 3; k++) {
            float p = 0.0f;
            for (int v = 0; v < 3; v++) p += a.bary[v] * mesh->positions[(size_t)ix[v] * 3 + k];
            CHECK_NEAR(p, o[k] + a.t * d[k], 1e-3);
        }
    }
    CHECK(same_tri >= hits - hits / 200);
    return hits;
}

static void raycast_matches_brute_force_on_sphere(void)
{
    pelt_mesh *mesh = NULL;
    CHECK(pelt_mesh_sphere(1.0f, 48, 24, &mesh, NULL) == PELT_OK);
    if (!mesh) return;
    pelt__bvh *bvh = NULL;
    CHECK(pelt__bvh_build(mesh, NULL, &bvh, NULL) == PELT_OK);
    /* Origins both inside and outside the sphere. */
    int hits = compare_rays(mesh, bvh, 3000, 42, 3.0f, 1.2f);
    CHECK(hits > 1000);
    pelt__bvh_destroy(bvh);
    pelt_mesh_destroy(mesh);
}

static void raycast_matches_brute_force_on_torus(void)
{
    pelt_mesh *mesh = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.35f, 60, 30, &mesh, NULL) == PELT_OK);
    if (!mesh) return;
    pelt__bvh *bvh = NULL;
    CHECK(pelt__bvh_build(mesh, NULL, &bvh, NULL) == PELT_OK);
    int hits = compare_rays(mesh, bvh, 3000, 7, 2.5f, 1.4f);
    CHECK(hits > 1000);
    pelt__bvh_destroy(bvh);
    pelt_mesh_destroy(mesh);
}

static void raycast_respects_t_max_and_rejects_bad_rays(void)
{
    pelt_mesh *mesh = NULL;
    CHECK(pelt_mesh_sphere(1.0f, 32, 16, &mesh, NULL) == PELT_OK);
    if (!mesh) return;
    pelt__bvh *bvh = NULL;
    CHECK(pelt__bvh_build(mesh, NULL, &bvh, NULL) == PELT_OK);
    float o[3] = {0.0f, 0.05f, 5.0f}, d[3] = {0.0f, 0.0f, -1.0f};
    pelt__hit h;
    /* The polygonal sphere's surface is within (0.98, 1] of the centre. */
    CHECK(pelt__bvh_raycast(bvh, o, d, INFINITY, &h));
    CHECK(h.t > 4.0f && h.t < 4.03f);
    CHECK(!pelt__bvh_raycast(bvh, o, d, 3.9f, &h));
    float away[3] = {0.0f, 0.0f, 1.0f};
    CHECK(!pelt__bvh_raycast(bvh, o, away, INFINITY, &h));
    float zero[3] = {0.0f, 0.0f, 0.0f}, bad[3] = {NAN, 0.0f, 0.0f};
    CHECK(!pelt__bvh_raycast(bvh, o, zero, INFINITY, &h));
    CHECK(!pelt__bvh_raycast(bvh, bad, d, INFINITY, &h));
    CHECK(!pelt__bvh_raycast(bvh, o, d, NAN, &h));
    /* Axis-parallel rays from inside hit the far wall at about 1. */
    float c[3] = {0.0f, 0.0f, 0.0f}, x[3] = {1.0f, 0.0f, 0.0f};
    CHECK(pelt__bvh_raycast(bvh, c, x, INFINITY, &h));
    CHECK(h.t > 0.98f && h.t <= 1.0001f);
    pelt__bvh_destroy(bvh);
    pelt_mesh_destroy(mesh);
}

static void raycast_large_mesh_agrees_and_reports_time(void)
{
    /* 428 slices x 428 stacks: about 365k triangles, like the Lion. */
    pelt_mesh *mesh = NULL;
    CHECK(pelt_mesh_sphere(1.0f, 428, 428, &mesh, NULL) == PELT_OK);
    if (!mesh) return;
    pelt__bvh *bvh = NULL;
    double t0 = now_s();
    CHECK(pelt__bvh_build(mesh, NULL, &bvh, NULL) == PELT_OK);
    double t1 = now_s();
    if (!bvh) {
        pelt_mesh_destroy(mesh);
        return;
    }
    uint64_t s = 2024;
    const int rays = 20000;
    int hits = 0;
    double t2 = now_s();
    for (int i = 0; i < rays; i++) {
        float o[3], d[3];
        random_ray(&s, 3.0f, 1.2f, o, d);
        pelt__hit h;
        hits += pelt__bvh_raycast(bvh, o, d, INFINITY, &h);
    }
    double t3 = now_s();
    size_t nodes;
    unsigned depth;
    pelt__bvh_stats(bvh, &nodes, &depth);
    printf("info: %zu triangles: BVH build %.1f ms (%zu nodes, depth %u), "
           "%.2f us per ray (%d of %d hit)\n",
           mesh->triangle_count, (t1 - t0) * 1e3, nodes, depth,
           (t3 - t2) * 1e6 / rays, hits, rays);
    CHECK(compare_rays(mesh, bvh, 30, 5, 3.0f, 1.2f) > 5);
    pelt__bvh_destroy(bvh);
    pelt_mesh_destroy(mesh);
}

int main(void)
{
    RUN(raycast_matches_brute_force_on_sphere);
    RUN(raycast_matches_brute_force_on_torus);
    RUN(raycast_respects_t_max_and_rejects_bad_rays);
    RUN(raycast_large_mesh_agrees_and_reports_time);
    return check_summary();
}
