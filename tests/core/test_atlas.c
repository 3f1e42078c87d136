/* Atlas: direction field, patches, packing, uv validation and the cache. */
#include "pelt/atlas.h"
#include "pelt/params.h"

#include "support/check.h"
#include "core/atlas/atlas_cache.h"
#include "core/atlas/atlas_internal.h"
#include "core/atlas/direction_field.h"
#include "core/base/weld.h"
#include "core/mesh/mesh_internal.h"

#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

static pelt_mesh *torus(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.35f, 48, 24, &m, NULL) == PELT_OK);
    return m;
}

static pelt_mesh *sphere(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_sphere(1.0f, 48, 24, &m, NULL) == PELT_OK);
    return m;
}

static pelt_atlas *patches(const pelt_mesh *m, unsigned mask)
{
    pelt_atlas_desc d = {.mode = PELT_ATLAS_PATCHES, .mask_size = mask, .max_patch_faces = 400};
    pelt_atlas *a = NULL;
    pelt_error err = {0};
    pelt_status st = pelt_atlas_create(m, &d, &a, &err);
    if (st != PELT_OK) fprintf(stderr, "  atlas: %s\n", err.message);
    CHECK(st == PELT_OK);
    return a;
}

/* Every face in exactly one patch, and every patch non-empty. */
static void check_partition(const pelt_atlas *a)
{
    const pelt_atlas_stats *s = pelt_atlas_get_stats(a);
    const uint32_t *tp = pelt_atlas_triangle_patches(a);
    size_t *count = calloc(s->patch_count, sizeof *count);
    for (size_t t = 0; t < s->triangle_count; t++) {
        CHECK(tp[t] < s->patch_count);
        if (tp[t] < s->patch_count) count[tp[t]]++;
    }
    size_t empty = 0;
    for (size_t p = 0; p < s->patch_count; p++) empty += count[p] == 0;
    CHECK(empty == 0);
    free(count);
    /* A split vertex belongs to one patch: no output vertex is shared by
     * triangles of two patches. */
    const pelt_mesh *m = pelt_atlas_mesh(a);
    uint32_t *owner = malloc(m->vertex_count * sizeof *owner);
    for (size_t v = 0; v < m->vertex_count; v++) owner[v] = UINT32_MAX;
    size_t shared = 0;
    for (size_t t = 0; t < m->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t v = m->indices[3 * t + k];
            if (owner[v] != UINT32_MAX && owner[v] != tp[t]) shared++;
            owner[v] = tp[t];
        }
    CHECK(shared == 0);
    free(owner);
}

static void check_clean_uvs(const pelt_atlas *a, unsigned res)
{
    pelt_atlas_check c;
    CHECK(pelt_atlas_check_uvs(pelt_atlas_mesh(a), res, &c, NULL) == PELT_OK);
    CHECK(c.flipped == 0);
    CHECK(c.degenerate == 0);
    CHECK(c.outside == 0);
    CHECK(c.overlap_texels == 0);
    CHECK(c.orientation == 1);
    if (c.overlap_texels || c.flipped)
        fprintf(stderr, "  res %u: %zu flipped, %zu texels twice\n", res, c.flipped, c.overlap_texels);
}

static void atlas_torus_faces_in_one_patch_no_flip_no_overlap(void)
{
    pelt_mesh *m = torus();
    pelt_atlas *a = patches(m, 256);
    if (!a) return;
    const pelt_atlas_stats *s = pelt_atlas_get_stats(a);
    CHECK(s->mode_used == PELT_ATLAS_PATCHES);
    CHECK(s->patch_count > 1);
    CHECK(s->flipped == 0);
    check_partition(a);
    check_clean_uvs(a, 256);
    check_clean_uvs(a, 1024); /* finer sampling finds smaller overlaps */
    pelt_atlas_destroy(a);
    pelt_mesh_destroy(m);
}

static void atlas_sphere_faces_in_one_patch_no_flip_no_overlap(void)
{
    pelt_mesh *m = sphere();
    pelt_atlas *a = patches(m, 256);
    if (!a) return;
    check_partition(a);
    check_clean_uvs(a, 256);
    check_clean_uvs(a, 1024);
    pelt_atlas_destroy(a);
    pelt_mesh_destroy(m);
}

/* Inside a patch the area ratio is within max_stretch (2) of the patch mean;
 * with one density for all patches the global spread stays within 2 * 2. */
static void atlas_sphere_stretch_bounded(void)
{
    pelt_mesh *m = sphere();
    pelt_atlas *a = patches(m, 256);
    if (!a) return;
    const pelt_atlas_stats *s = pelt_atlas_get_stats(a);
    CHECK(s->stretch_max <= 4.0f);
    CHECK(s->stretch_min >= 0.25f);
    CHECK_NEAR(s->stretch_mean, 1.0, 0.25);
    pelt_atlas_destroy(a);
    pelt_mesh_destroy(m);
}

/* A flat square flattens isometrically: every triangle has area ratio 1. */
static void atlas_flat_square_has_no_stretch(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_square(2.0f, 12, &m, NULL) == PELT_OK);
    pelt_atlas_desc d = {.mode = PELT_ATLAS_PATCHES, .max_patch_faces = 100000};
    pelt_atlas *a = NULL;
    CHECK(pelt_atlas_create(m, &d, &a, NULL) == PELT_OK);
    if (a) {
        const pelt_atlas_stats *s = pelt_atlas_get_stats(a);
        CHECK(s->patch_count == 1);
        CHECK_NEAR(s->stretch_min, 1.0, 1e-3);
        CHECK_NEAR(s->stretch_max, 1.0, 1e-3);
        /* fur_uvs in tiles: a side of 2 world units spans 2 * density tiles. */
        const pelt_mesh *o = pelt_atlas_mesh(a);
        double area = 0;
        for (size_t t = 0; t < o->triangle_count; t++) {
            const uint32_t *tri = o->indices + 3 * t;
            const float *u = o->fur_uvs;
            area += 0.5 * ((u[2 * tri[1]] - u[2 * tri[0]]) * (u[2 * tri[2] + 1] - u[2 * tri[0] + 1]) -
                           (u[2 * tri[2]] - u[2 * tri[0]]) * (u[2 * tri[1] + 1] - u[2 * tri[0] + 1]));
        }
        CHECK_NEAR(area, 4.0 * s->texel_density * s->texel_density, 1e-3 * area);
    }
    pelt_atlas_destroy(a);
    pelt_mesh_destroy(m);
}

/* The field, mapped into each triangle's fur uvs, points along +u. */
static void atlas_direction_field_runs_along_u(void)
{
    pelt_mesh *m = torus();
    pelt_atlas_desc d = {.mode = PELT_ATLAS_PATCHES, .direction = {0.3f, -1.0f, 0.2f}, .max_patch_faces = 400};
    pelt_atlas *a = NULL;
    CHECK(pelt_atlas_create(m, &d, &a, NULL) == PELT_OK);
    if (!a) {
        pelt_mesh_destroy(m);
        return;
    }
    const pelt_mesh *o = pelt_atlas_mesh(a);
    const float *dir = pelt_atlas_directions(a), *w = pelt_atlas_direction_weights(a);
    double good = 0, total = 0;
    for (size_t t = 0; t < o->triangle_count; t++) {
        const uint32_t *tri = o->indices + 3 * t;
        float wmin = 1;
        double f[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++) {
            if (w[tri[k]] < wmin) wmin = w[tri[k]];
            for (int c = 0; c < 3; c++) f[c] += dir[3 * tri[k] + c];
        }
        if (wmin < 0.9f) continue;
        double e1[3], e2[3];
        for (int c = 0; c < 3; c++) {
            e1[c] = o->positions[3 * tri[1] + c] - o->positions[3 * tri[0] + c];
            e2[c] = o->positions[3 * tri[2] + c] - o->positions[3 * tri[0] + c];
        }
        double g11 = 0, g12 = 0, g22 = 0, r1 = 0, r2 = 0;
        for (int c = 0; c < 3; c++) {
            g11 += e1[c] * e1[c], g12 += e1[c] * e2[c], g22 += e2[c] * e2[c];
            r1 += f[c] * e1[c], r2 += f[c] * e2[c];
        }
        double det = g11 * g22 - g12 * g12, ca = (r1 * g22 - r2 * g12) / det, cb = (r2 * g11 - r1 * g12) / det;
        const float *u = o->fur_uvs;
        double du = ca * (u[2 * tri[1]] - u[2 * tri[0]]) + cb * (u[2 * tri[2]] - u[2 * tri[0]]);
        double dv = ca * (u[2 * tri[1] + 1] - u[2 * tri[0] + 1]) + cb * (u[2 * tri[2] + 1] - u[2 * tri[0] + 1]);
        double area = sqrt(det);
        total += area;
        if (du > 0 && fabs(dv) < du * 0.5774) good += area; /* within 30 degrees */
    }
    CHECK(total > 0);
    CHECK(good >= 0.9 * total);
    if (total > 0) printf("  %.1f%% of the combed area within 30 degrees of +u\n", 100 * good / total);
    pelt_atlas_destroy(a);
    pelt_mesh_destroy(m);
}

/* >= 2 free texels between the touched texels of any two patches. */
static void atlas_gutter_separates_patches(void)
{
    pelt_mesh *m = torus();
    const unsigned res = 256;
    pelt_atlas *a = patches(m, res);
    if (!a) return;
    const pelt_atlas_stats *s = pelt_atlas_get_stats(a);
    const pelt_mesh *o = pelt_atlas_mesh(a);
    const uint32_t *tp = pelt_atlas_triangle_patches(a);
    long *box = malloc(s->patch_count * 4 * sizeof *box);
    for (size_t p = 0; p < s->patch_count; p++) box[4 * p] = box[4 * p + 1] = 1L << 30, box[4 * p + 2] = box[4 * p + 3] = -(1L << 30);
    for (size_t t = 0; t < o->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            const float *uv = o->uvs + 2 * o->indices[3 * t + k];
            long x = (long)floor(uv[0] * res), y = (long)floor(uv[1] * res);
            long *b = box + 4 * tp[t];
            if (x < b[0]) b[0] = x;
            if (y < b[1]) b[1] = y;
            if (x > b[2]) b[2] = x;
            if (y > b[3]) b[3] = y;
        }
    size_t close = 0, border = 0;
    for (size_t p = 0; p < s->patch_count; p++) {
        const long *b = box + 4 * p;
        border += b[0] < 1 || b[1] < 1 || b[2] > (long)res - 2 || b[3] > (long)res - 2;
        for (size_t q = p + 1; q < s->patch_count; q++) {
            const long *c = box + 4 * q;
            long gx = c[0] > b[2] ? c[0] - b[2] - 1 : b[0] - c[2] - 1;
            long gy = c[1] > b[3] ? c[1] - b[3] - 1 : b[1] - c[3] - 1;
            if (gx < 2 && gy < 2) close++;
        }
    }
    CHECK(close == 0);
    CHECK(border == 0);
    free(box);
    pelt_atlas_destroy(a);
    pelt_mesh_destroy(m);
}

/* Split vertices keep the original position and normal; the welded index
 * of every copy has the same position. */
static void atlas_split_vertices_keep_original_normals(void)
{
    pelt_mesh *m = sphere();
    pelt_atlas *a = patches(m, 256);
    if (!a) return;
    const pelt_mesh *o = pelt_atlas_mesh(a);
    const uint32_t *src = pelt_atlas_source_vertices(a), *weld = pelt_atlas_welded_vertices(a);
    size_t bad = 0;
    CHECK(o->vertex_count > m->vertex_count);
    for (size_t v = 0; v < o->vertex_count; v++) {
        bad += memcmp(o->positions + 3 * v, m->positions + 3 * src[v], 12) != 0;
        bad += memcmp(o->normals + 3 * v, m->normals + 3 * src[v], 12) != 0;
        for (int k = 0; k < 3; k++) /* by value: -0 and +0 are one point */
            bad += m->positions[3 * weld[v] + k] != m->positions[3 * src[v] + k];
        bad += weld[v] > src[v];
    }
    CHECK(bad == 0);
    pelt_atlas_destroy(a);
    pelt_mesh_destroy(m);
}

/* Global field (0,-1,0) on a sphere: tangent at the equator points down
 * with full weight; at the poles it vanishes and the fur stands up. */
static void direction_field_stands_up_at_poles(void)
{
    pelt_mesh *m = sphere();
    uint32_t *canon = malloc(m->vertex_count * sizeof *canon);
    float *dir = malloc(m->vertex_count * 12), *w = malloc(m->vertex_count * 4);
    const float g[3] = {0, -1, 0};
    CHECK(pelt__weld(m->positions, NULL, m->vertex_count, canon));
    CHECK(pelt__direction_field(m->positions, m->normals, m->vertex_count, m->indices, m->triangle_count,
                                canon, g, NULL, 4, dir, w));
    size_t poles = 0, equator = 0;
    for (size_t v = 0; v < m->vertex_count; v++) {
        float y = m->positions[3 * v + 1];
        CHECK_NEAR(dir[3 * v] * dir[3 * v] + dir[3 * v + 1] * dir[3 * v + 1] + dir[3 * v + 2] * dir[3 * v + 2], 1.0, 1e-4);
        if (fabsf(y) > 0.999f) {
            poles++;
            CHECK(w[v] < 0.05f);
        }
        if (fabsf(y) < 0.07f) {
            equator++;
            CHECK(w[v] > 0.9f);
            CHECK(dir[3 * v + 1] < -0.98f);
        }
    }
    CHECK(poles > 0 && equator > 0);
    free(canon), free(dir), free(w);
    pelt_mesh_destroy(m);
}

/* Per-vertex vectors win over the global one; zero length stands up. */
static void direction_field_uses_per_vertex_vectors(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_square(1.0f, 4, &m, NULL) == PELT_OK);
    size_t n = m->vertex_count;
    uint32_t *canon = malloc(n * sizeof *canon);
    float *dir = malloc(n * 12), *w = malloc(n * 4), *pv = calloc(n, 12);
    for (size_t v = 0; v < n; v++) pv[3 * v] = 1.0f, pv[3 * v + 1] = 5.0f; /* normal part dropped */
    const float g[3] = {0, 0, 1};
    CHECK(pelt__weld(m->positions, NULL, n, canon));
    CHECK(pelt__direction_field(m->positions, m->normals, n, m->indices, m->triangle_count, canon, g, pv, 4, dir, w));
    for (size_t v = 0; v < n; v++) {
        CHECK_NEAR(dir[3 * v], 1.0, 1e-5);
        CHECK_NEAR(w[v], 1.0, 1e-5);
    }
    memset(pv, 0, n * 12);
    CHECK(pelt__direction_field(m->positions, m->normals, n, m->indices, m->triangle_count, canon, g, pv, 4, dir, w));
    for (size_t v = 0; v < n; v++) CHECK(w[v] == 0.0f);
    free(canon), free(dir), free(w), free(pv);
    pelt_mesh_destroy(m);
}

static pelt_mesh *hand_mesh(const float *uvs, size_t nv, const uint32_t *idx, size_t nt)
{
    float pos[3 * 16];
    for (size_t v = 0; v < nv; v++) pos[3 * v] = uvs[2 * v], pos[3 * v + 1] = 0, pos[3 * v + 2] = uvs[2 * v + 1] + (float)v * 0.01f;
    pelt_mesh_data d = {.positions = pos, .uvs = uvs, .vertex_count = nv, .indices = idx, .triangle_count = nt};
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_create(&d, &m, NULL) == PELT_OK);
    return m;
}

/* Two triangles splitting [0,1]^2 along the diagonal, which passes exactly
 * through 4 of the 16 texel centres at res 4: all 16 covered once. */
static void check_counts_shared_edge_once(void)
{
    const float uv[] = {0, 0, 1, 0, 1, 1, 0, 1};
    const uint32_t idx[] = {0, 1, 2, 0, 2, 3};
    uint8_t claims[16];
    size_t covered = 0;
    CHECK(pelt__raster_overlaps(uv, idx, 2, 4, claims, &covered) == 0);
    CHECK(covered == 16);
    /* The same square split along the other diagonal. */
    const uint32_t idx2[] = {0, 1, 3, 1, 2, 3};
    CHECK(pelt__raster_overlaps(uv, idx2, 2, 4, claims, &covered) == 0);
    CHECK(covered == 16);
}

static void check_accepts_square_uvs(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_square(1.0f, 8, &m, NULL) == PELT_OK);
    pelt_atlas_check c;
    CHECK(pelt_atlas_check_uvs(m, 256, &c, NULL) == PELT_OK);
    CHECK(c.flipped == 0 && c.overlap_texels == 0 && c.outside == 0 && c.degenerate == 0);
    CHECK(c.covered_texels == 256 * 256);
    pelt_atlas *a = NULL;
    CHECK(pelt_atlas_create(m, NULL, &a, NULL) == PELT_OK); /* auto */
    if (a) {
        CHECK(pelt_atlas_get_stats(a)->mode_used == PELT_ATLAS_MESH_UVS);
        CHECK(pelt_atlas_get_stats(a)->uv_warning[0] == '\0');
    }
    pelt_atlas_destroy(a);
    pelt_mesh_destroy(m);
}

static void check_rejects_overlapping_uvs_with_reason(void)
{
    /* Two triangles with the same uv footprint (a 4-vertex quad folded). */
    const float uv[] = {0.1f, 0.1f, 0.9f, 0.1f, 0.1f, 0.9f, 0.15f, 0.12f, 0.85f, 0.15f, 0.12f, 0.8f};
    const uint32_t idx[] = {0, 1, 2, 3, 4, 5};
    pelt_mesh *m = hand_mesh(uv, 6, idx, 2);
    if (!m) return;
    pelt_atlas_check c;
    CHECK(pelt_atlas_check_uvs(m, 64, &c, NULL) == PELT_OK);
    CHECK(c.flipped == 0);
    CHECK(c.overlap_texels > 0);
    pelt_atlas *a = NULL;
    CHECK(pelt_atlas_create(m, NULL, &a, NULL) == PELT_OK);
    if (a) {
        CHECK(pelt_atlas_get_stats(a)->mode_used == PELT_ATLAS_PATCHES);
        CHECK(strstr(pelt_atlas_get_stats(a)->uv_warning, "claimed by two") != NULL);
    }
    pelt_atlas_destroy(a);
    pelt_mesh_destroy(m);
}

static void check_rejects_flipped_uvs_with_reason(void)
{
    /* Three separate triangles, the last one mirrored. */
    const float uv[] = {0, 0, 0.3f, 0, 0, 0.3f, 0.4f, 0, 0.7f, 0, 0.4f, 0.3f, 0, 0.5f, 0, 0.8f, 0.3f, 0.5f};
    const uint32_t idx[] = {0, 1, 2, 3, 4, 5, 6, 7, 8};
    pelt_mesh *m = hand_mesh(uv, 9, idx, 3);
    if (!m) return;
    pelt_atlas_check c;
    CHECK(pelt_atlas_check_uvs(m, 64, &c, NULL) == PELT_OK);
    CHECK(c.flipped == 1);
    CHECK(c.orientation == 1);
    CHECK(c.overlap_texels == 0);
    pelt_atlas_stats s;
    pelt_mesh *o = NULL;
    pelt_atlas_desc d = {.mode = PELT_ATLAS_MESH_UVS}; /* forced: used, still warned */
    CHECK(pelt_atlas_build(m, &d, &o, &s, NULL) == PELT_OK);
    CHECK(s.mode_used == PELT_ATLAS_MESH_UVS);
    CHECK(strstr(s.uv_warning, "flipped") != NULL);
    pelt_mesh_destroy(o);
    pelt_mesh_destroy(m);
}

static bool same_mesh(const pelt_mesh *a, const pelt_mesh *b)
{
    if (a->vertex_count != b->vertex_count || a->triangle_count != b->triangle_count) return false;
    size_t v = a->vertex_count;
    return !memcmp(a->positions, b->positions, v * 12) && !memcmp(a->normals, b->normals, v * 12) &&
           !memcmp(a->uvs, b->uvs, v * 8) && !memcmp(a->fur_uvs, b->fur_uvs, v * 8) &&
           !memcmp(a->tangents, b->tangents, v * 16) &&
           !memcmp(a->indices, b->indices, a->triangle_count * 12);
}

/* An embedder can make the atlas mesh itself from the arrays: the atlas
 * builds it through pelt_mesh_create, so pelt_mesh_get_data -> create gives
 * the same positions, normals, uvs, fur uvs, comb, tangents and indices, and
 * the comb is the direction field times its weight. Patches on a torus and
 * the mesh's own uvs on a sphere (whose spare pole vertices are dropped). */
static void atlas_mesh_rebuilds_from_its_arrays(void)
{
    for (int c = 0; c < 2; c++) {
        pelt_mesh *m = c == 0 ? torus() : sphere();
        pelt_atlas_desc d = {.mode = c == 0 ? PELT_ATLAS_PATCHES : PELT_ATLAS_MESH_UVS,
                             .max_patch_faces = 400};
        pelt_atlas *a = NULL;
        CHECK(pelt_atlas_create(m, &d, &a, NULL) == PELT_OK);
        if (!a) {
            pelt_mesh_destroy(m);
            continue;
        }
        pelt_mesh_data o = pelt_mesh_get_data(pelt_atlas_mesh(a));
        size_t n = o.vertex_count;
        CHECK(n == pelt_atlas_vertex_count(a));
        CHECK(o.fur_uvs != NULL && o.comb != NULL);
        if (!o.fur_uvs || !o.comb || n != pelt_atlas_vertex_count(a)) {
            pelt_atlas_destroy(a);
            pelt_mesh_destroy(m);
            continue;
        }
        const float *dir = pelt_atlas_directions(a), *w = pelt_atlas_direction_weights(a);
        size_t bad_comb = 0;
        for (size_t v = 0; v < n; v++)
            for (int k = 0; k < 3; k++) bad_comb += o.comb[3 * v + k] != dir[3 * v + k] * w[v];
        CHECK(bad_comb == 0);
        pelt_mesh *r = NULL;
        CHECK(pelt_mesh_create(&o, &r, NULL) == PELT_OK);
        if (r) {
            pelt_mesh_data e = pelt_mesh_get_data(r);
            CHECK(e.vertex_count == n && e.triangle_count == o.triangle_count);
            if (e.vertex_count == n && e.triangle_count == o.triangle_count) {
                CHECK(!memcmp(e.positions, o.positions, n * 12));
                CHECK(!memcmp(e.normals, o.normals, n * 12));
                CHECK(!memcmp(e.uvs, o.uvs, n * 8));
                CHECK(e.fur_uvs && !memcmp(e.fur_uvs, o.fur_uvs, n * 8));
                CHECK(e.comb && !memcmp(e.comb, o.comb, n * 12));
                CHECK(!memcmp(pelt_mesh_tangents(r), pelt_mesh_tangents(pelt_atlas_mesh(a)), n * 16));
                CHECK(!memcmp(e.indices, o.indices, o.triangle_count * 12));
            }
        }
        pelt_mesh_destroy(r);
        pelt_atlas_destroy(a);
        pelt_mesh_destroy(m);
    }
}

/* The last warning a logger saw. */
static char last_warning[512];
static int warnings;

static void keep_warning(pelt_log_level level, const char *message, void *user)
{
    (void)user;
    if (level != PELT_LOG_WARNING) return;
    warnings++;
    snprintf(last_warning, sizeof last_warning, "%s", message);
}

/* Cuts the file at path to half its length. */
static void truncate_half(const char *path)
{
    FILE *f = fopen(path, "rb");
    CHECK(f != NULL);
    if (!f) return;
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    CHECK(truncate(path, size / 2) == 0);
    fclose(f);
}

static void atlas_cache_round_trip_and_rejects_corruption(void)
{
    const char *dir = PELT_TEST_OUT "/atlas_cache";
    pelt_mesh *m = torus();
    pelt_atlas_desc d = {.mode = PELT_ATLAS_PATCHES, .cache_dir = dir, .seed = 7, .max_patch_faces = 400};
    pelt_atlas *a = NULL, *b = NULL, *c = NULL, *e = NULL;
    /* Start clean: remove a file left by an earlier run. */
    char path[4200];
    pelt_atlas_desc keyed = d;
    keyed.max_stretch = 2.0f, keyed.smoothing_iterations = 4;
    CHECK(pelt_atlas_create(m, &d, &a, NULL) == PELT_OK);
    if (!a) return;
    const pelt_atlas_stats *sa = pelt_atlas_get_stats(a);
    pelt__atlas_cache_path(dir, pelt__atlas_key(m, &keyed, sa->mask_size, sa->texel_density), path, sizeof path);
    remove(path);
    pelt_atlas_destroy(a);
    CHECK(pelt_atlas_create(m, &d, &a, NULL) == PELT_OK);
    CHECK(!pelt_atlas_get_stats(a)->from_cache);
    FILE *f = fopen(path, "rb");
    CHECK(f != NULL);
    if (f) fclose(f);
    CHECK(pelt_atlas_create(m, &d, &b, NULL) == PELT_OK);
    CHECK(pelt_atlas_get_stats(b)->from_cache);
    CHECK(same_mesh(pelt_atlas_mesh(a), pelt_atlas_mesh(b)));
    CHECK(!memcmp(pelt_atlas_source_vertices(a), pelt_atlas_source_vertices(b), pelt_atlas_vertex_count(a) * 4));
    CHECK(pelt_atlas_get_stats(a)->patch_count == pelt_atlas_get_stats(b)->patch_count);
    CHECK(pelt_atlas_get_stats(a)->stretch_max == pelt_atlas_get_stats(b)->stretch_max);
    /* Flip one byte in the middle: the checksum rejects it, it is rebuilt. */
    f = fopen(path, "r+b");
    if (f) {
        fseek(f, 0, SEEK_END);
        long size = ftell(f);
        fseek(f, size / 2, SEEK_SET);
        int ch = fgetc(f);
        fseek(f, size / 2, SEEK_SET);
        fputc(ch ^ 0x5a, f);
        fclose(f);
    }
    /* ... with a warning naming the file and the reason. */
    pelt_atlas_desc logged = d;
    logged.hooks.logger.func = keep_warning;
    warnings = 0;
    CHECK(pelt_atlas_create(m, &logged, &c, NULL) == PELT_OK);
    CHECK(!pelt_atlas_get_stats(c)->from_cache);
    CHECK(same_mesh(pelt_atlas_mesh(a), pelt_atlas_mesh(c)));
    CHECK(warnings == 1 && strstr(last_warning, path) && strstr(last_warning, "checksum"));
    if (!strstr(last_warning, "checksum")) fprintf(stderr, "  seen: %s\n", last_warning);
    /* Cut to half its length: rebuilt with a warning, written whole again. */
    truncate_half(path);
    pelt_atlas_destroy(c);
    warnings = 0;
    CHECK(pelt_atlas_create(m, &logged, &c, NULL) == PELT_OK);
    CHECK(!pelt_atlas_get_stats(c)->from_cache);
    CHECK(warnings == 1 && strstr(last_warning, path) && strstr(last_warning, "truncated"));
    if (!strstr(last_warning, "truncated")) fprintf(stderr, "  seen: %s\n", last_warning);
    CHECK(same_mesh(pelt_atlas_mesh(a), pelt_atlas_mesh(c)));
    /* A foreign file (not a cache at all): also rejected with a warning. Then
     * the rewritten file is trusted again. */
    f = fopen(path, "wb");
    if (f) fputs("PELTATL", f), fclose(f);
    pelt_atlas_destroy(c);
    warnings = 0;
    CHECK(pelt_atlas_create(m, &logged, &c, NULL) == PELT_OK);
    CHECK(!pelt_atlas_get_stats(c)->from_cache);
    CHECK(warnings == 1 && strstr(last_warning, path));
    CHECK(pelt_atlas_create(m, &d, &e, NULL) == PELT_OK);
    CHECK(pelt_atlas_get_stats(e)->from_cache);
    pelt_atlas_destroy(a), pelt_atlas_destroy(b), pelt_atlas_destroy(c), pelt_atlas_destroy(e);
    pelt_mesh_destroy(m);
}

/* A child of the concurrency test: builds the atlas `rounds` times, each
 * time after removing the cache file (so every round writes it), and fails
 * when any build saw a damaged file. */
static int cache_writer(const pelt_mesh *m, const pelt_atlas_desc *d, const char *path, int rounds)
{
    pelt_atlas_desc logged = *d;
    logged.hooks.logger.func = keep_warning;
    warnings = 0;
    for (int i = 0; i < rounds; i++) {
        remove(path);
        pelt_atlas *a = NULL;
        if (pelt_atlas_create(m, &logged, &a, NULL) != PELT_OK) return 2;
        pelt_atlas_destroy(a);
    }
    if (warnings) fprintf(stderr, "  writer %d saw: %s\n", (int)getpid(), last_warning);
    return warnings ? 1 : 0;
}

/* A child of the concurrency test: reads the cache file as fast as it can
 * until the file `done` appears (the writers have finished); any cache file
 * it finds must be whole, and it must find some. */
static int cache_reader(const char *dir, uint64_t key, const pelt_mesh *m, const char *done, int *hits)
{
    const pelt_mesh_data md = pelt_mesh_get_data(m);
    for (long i = 0; access(done, F_OK) != 0 && i < 10000000; i++) {
        pelt__atlas_record r;
        char why[128];
        if (pelt__atlas_cache_load(dir, key, md.vertex_count, md.triangle_count, &r, why, sizeof why)) {
            (*hits)++;
            pelt__atlas_record_free(&r);
        } else if (why[0]) {
            fprintf(stderr, "  reader saw a cache file that %s\n", why);
            return 1;
        }
    }
    return *hits > 0 ? 0 : 3;
}

/* Two processes building the same atlas at once (here three writers and a
 * reader) never leave or show a damaged cache file, and no temporary file
 * is left behind. */
static void atlas_cache_survives_concurrent_builders(void)
{
    const char *dir = PELT_TEST_OUT "/atlas_cache_concurrent";
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.35f, 24, 12, &m, NULL) == PELT_OK);
    if (!m) return;
    pelt_atlas_desc d = {.mode = PELT_ATLAS_PATCHES, .cache_dir = dir, .seed = 3, .max_patch_faces = 200};
    pelt_atlas *first = NULL;
    CHECK(pelt_atlas_create(m, &d, &first, NULL) == PELT_OK);
    if (!first) return;
    const pelt_atlas_stats *st = pelt_atlas_get_stats(first);
    pelt_atlas_desc keyed = d;
    keyed.max_stretch = 2.0f, keyed.smoothing_iterations = 4;
    uint64_t key = pelt__atlas_key(m, &keyed, st->mask_size, st->texel_density);
    char path[4200];
    pelt__atlas_cache_path(dir, key, path, sizeof path);
    char done[4300];
    snprintf(done, sizeof done, "%s.done", dir);
    remove(done);
    enum { WRITERS = 3 };
    pid_t kids[WRITERS + 1];
    for (int k = 0; k <= WRITERS; k++) {
        kids[k] = fork();
        if (kids[k] == 0) {
            int hits = 0, rc = k < WRITERS ? cache_writer(m, &d, path, 12) : cache_reader(dir, key, m, done, &hits);
            if (k == WRITERS) printf("  reader: %d whole files seen\n", hits);
            fflush(stdout);
            _exit(rc);
        }
        CHECK(kids[k] > 0);
    }
    for (int k = 0; k <= WRITERS; k++) {
        if (k == WRITERS) fclose(fopen(done, "w")); /* the reader may stop */
        int status = -1;
        if (kids[k] > 0) waitpid(kids[k], &status, 0);
        CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    }
    remove(done);
    /* What is left is a whole file that gives the same atlas. */
    pelt_atlas *after = NULL;
    CHECK(pelt_atlas_create(m, &d, &after, NULL) == PELT_OK);
    CHECK(after && pelt_atlas_get_stats(after)->from_cache);
    CHECK(after && same_mesh(pelt_atlas_mesh(first), pelt_atlas_mesh(after)));
    DIR *dd = opendir(dir);
    int files = 0;
    for (struct dirent *e; dd && (e = readdir(dd));) {
        if (e->d_name[0] == '.') continue;
        files++;
        if (strstr(e->d_name, ".tmp")) fprintf(stderr, "  left behind: %s\n", e->d_name);
        CHECK(strstr(e->d_name, ".tmp") == NULL);
    }
    if (dd) closedir(dd);
    CHECK(files == 1);
    pelt_atlas_destroy(first), pelt_atlas_destroy(after);
    pelt_mesh_destroy(m);
}

static void atlas_draw_paints_patches_and_borders(void)
{
    pelt_mesh *m = torus();
    pelt_atlas *a = patches(m, 256);
    if (!a) return;
    enum { W = 128 };
    uint8_t *img = malloc(W * W * 4);
    CHECK(pelt_atlas_draw(a, img, W, W, 1, NULL) == PELT_OK);
    size_t background = 0, dark = 0, bright = 0;
    for (size_t i = 0; i < W * W; i++) {
        const uint8_t *p = img + 4 * i;
        CHECK(p[3] == 255);
        if (p[0] == 24 && p[1] == 24 && p[2] == 24) background++;
        else if (p[0] == 10 && p[1] == 10 && p[2] == 10) dark++;
        else if (p[0] >= 80 || p[1] >= 80 || p[2] >= 80) bright++;
    }
    CHECK(background > 0);
    CHECK(dark > 0);
    CHECK(bright > W * W / 4);
    pelt_mesh *taken = pelt_atlas_take_mesh(a);
    CHECK(pelt_atlas_draw(a, img, W, W, 1, NULL) == PELT_ERR_INVALID_ARGUMENT);
    free(img);
    pelt_mesh_destroy(taken);
    pelt_atlas_destroy(a);
    pelt_mesh_destroy(m);
}

static void atlas_rejects_bad_desc_with_named_field(void)
{
    pelt_mesh *m = torus();
    pelt_atlas_desc d = {.mode = 7};
    pelt_atlas *a = NULL;
    pelt_error err = {0};
    CHECK(pelt_atlas_create(m, &d, &a, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "mode") != NULL && strstr(err.message, "got 7") != NULL);
    d.mode = 0, d.max_stretch = 0.5f;
    CHECK(pelt_atlas_create(m, &d, &a, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "max_stretch") != NULL);
    d.max_stretch = 0, d.mode = PELT_ATLAS_PATCHES, d.mask_size = 8, d.max_patch_faces = 20;
    CHECK(pelt_atlas_create(m, &d, &a, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "mask_size 8") != NULL);
    CHECK(a == NULL);
    /* The rows' ranges (pelt/params.h), each refused by name just outside. */
    const struct { const char *name; pelt_atlas_desc d; } outside[] = {
        {"texel_density", {.texel_density = -1.0f}},
        {"max_patch_faces", {.max_patch_faces = 1000001}},
        {"smoothing_iterations", {.smoothing_iterations = 1001}},
        {"mask_size", {.mask_size = 16385}},
        {"max_stretch", {.max_stretch = 1.05f}},
    };
    for (size_t i = 0; i < sizeof outside / sizeof outside[0]; i++) {
        CHECK(pelt_atlas_create(m, &outside[i].d, &a, &err) == PELT_ERR_INVALID_ARGUMENT && a == NULL);
        CHECK(strstr(err.message, outside[i].name) != NULL);
        CHECK(pelt_atlas_param(outside[i].name) != NULL);
    }
    size_t rows = 0;
    const pelt_param *p = pelt_atlas_params(&rows);
    for (size_t i = 0; i < rows; i++) {
        if (!pelt_param_zero_is_default(&p[i]) || p[i].derived) continue;
        CHECK(p[i].def[0] >= p[i].min && p[i].def[0] <= p[i].max); /* defaults in range */
    }
    pelt_mesh_destroy(m);
}

int main(void)
{
    RUN(check_counts_shared_edge_once);
    RUN(check_accepts_square_uvs);
    RUN(check_rejects_overlapping_uvs_with_reason);
    RUN(check_rejects_flipped_uvs_with_reason);
    RUN(direction_field_stands_up_at_poles);
    RUN(direction_field_uses_per_vertex_vectors);
    RUN(atlas_flat_square_has_no_stretch);
    RUN(atlas_torus_faces_in_one_patch_no_flip_no_overlap);
    RUN(atlas_sphere_faces_in_one_patch_no_flip_no_overlap);
    RUN(atlas_sphere_stretch_bounded);
    RUN(atlas_direction_field_runs_along_u);
    RUN(atlas_gutter_separates_patches);
    RUN(atlas_split_vertices_keep_original_normals);
    RUN(atlas_mesh_rebuilds_from_its_arrays);
    RUN(atlas_cache_round_trip_and_rejects_corruption);
    RUN(atlas_cache_survives_concurrent_builders);
    RUN(atlas_draw_paints_patches_and_borders);
    RUN(atlas_rejects_bad_desc_with_named_field);
    return check_summary();
}
