/* Mesh validation, procedural shapes, frames and file import. */
#include "support/check.h"

#include "core/mesh/mesh_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- helpers ------------------------------------------------------------ */

static pelt_status create(const float *pos, const float *nrm, const float *uv, size_t nv,
                          const uint32_t *idx, size_t nt, pelt_mesh **out, pelt_error *err)
{
    pelt_mesh_data d = {pos, nrm, uv, nv, idx, nt};
    return pelt_mesh_create(&d, out, err);
}

static float len3(const float *v) { return sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
static float dot3(const float *a, const float *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void check_frames_valid(const pelt_mesh *m)
{
    int bad_n = 0, bad_t = 0, bad_ortho = 0, bad_w = 0;
    for (size_t i = 0; i < m->vertex_count; i++) {
        const float *n = m->normals + 3 * i, *t = m->tangents + 4 * i;
        if (fabsf(len3(n) - 1.0f) > 1e-5f) bad_n++;
        if (fabsf(len3(t) - 1.0f) > 1e-5f) bad_t++;
        if (fabsf(dot3(n, t)) > 1e-5f) bad_ortho++;
        if (t[3] != 1.0f && t[3] != -1.0f) bad_w++;
    }
    CHECK(bad_n == 0);
    CHECK(bad_t == 0);
    CHECK(bad_ortho == 0);
    CHECK(bad_w == 0);
}

/* Every triangle's geometric normal agrees with its vertex normals. */
static void check_faces_outward(const pelt_mesh *m)
{
    size_t bad = 0;
    for (size_t t = 0; t < m->triangle_count; t++) {
        const uint32_t *tri = m->indices + 3 * t;
        const float *a = m->positions + 3 * tri[0], *b = m->positions + 3 * tri[1],
                    *c = m->positions + 3 * tri[2];
        float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        float cr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
        float ns[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++) ns[j] += m->normals[3 * tri[k] + j];
        if (!(dot3(cr, ns) > 0.0f)) bad++;
    }
    CHECK(bad == 0);
}

/* ---- pelt_mesh_create ---------------------------------------------------- */

static const float tri_pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
static const uint32_t tri_idx[] = {0, 1, 2};

static void create_rejects_null_and_zero_counts(void)
{
    pelt_mesh *m = NULL;
    pelt_error e = {0};
    CHECK(pelt_mesh_create(NULL, &m, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(create(NULL, NULL, NULL, 3, tri_idx, 1, &m, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(e.message, "positions") != NULL);
    CHECK(create(tri_pos, NULL, NULL, 3, NULL, 1, &m, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(create(tri_pos, NULL, NULL, 0, tri_idx, 1, &m, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(e.message, "vertex_count") != NULL);
    CHECK(create(tri_pos, NULL, NULL, 3, tri_idx, 0, &m, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(e.message, "triangle_count") != NULL);
    pelt_mesh_data d = {tri_pos, NULL, NULL, 3, tri_idx, 1};
    CHECK(pelt_mesh_create(&d, NULL, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(pelt_mesh_create(&d, &m, NULL) == PELT_OK); /* err is optional */
    pelt_mesh_destroy(m);
    pelt_mesh_destroy(NULL);
}

static void create_rejects_nonfinite_coordinate_naming_vertex(void)
{
    float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    uint32_t idx[] = {0, 1, 2, 0, 2, 3};
    pelt_mesh *m = NULL;
    pelt_error e = {0};
    pos[3 * 2 + 1] = NAN;
    CHECK(create(pos, NULL, NULL, 4, idx, 2, &m, &e) == PELT_ERR_FORMAT);
    CHECK(m == NULL);
    CHECK(strstr(e.message, "vertex 2") != NULL);
    pos[3 * 2 + 1] = 1;
    pos[3 * 3 + 2] = -INFINITY;
    CHECK(create(pos, NULL, NULL, 4, idx, 2, &m, &e) == PELT_ERR_FORMAT);
    CHECK(strstr(e.message, "vertex 3") != NULL);
}

static void create_rejects_absurd_coordinates(void)
{
    float pos[] = {0, 0, 0, 3e38f, 0, 0, 0, 1, 0};
    pelt_mesh *m = NULL;
    pelt_error e = {0};
    CHECK(create(pos, NULL, NULL, 3, tri_idx, 1, &m, &e) == PELT_ERR_FORMAT);
    CHECK(strstr(e.message, "vertex 1") != NULL);
    CHECK(m == NULL);
}

static void microscopic_and_huge_meshes_get_valid_frames(void)
{
    const float scales[] = {1e-25f, 1e25f};
    for (int c = 0; c < 2; c++) {
        float pos[9];
        for (int k = 0; k < 9; k++) pos[k] = tri_pos[k] * scales[c];
        pelt_mesh *m = NULL;
        CHECK(create(pos, NULL, NULL, 3, tri_idx, 1, &m, NULL) == PELT_OK);
        for (int v = 0; m && v < 3; v++) CHECK_NEAR(m->normals[3 * v + 2], 1.0, 1e-6);
        if (m) check_frames_valid(m);
        pelt_mesh_destroy(m);
    }
}

static void create_rejects_index_out_of_range_naming_triangle(void)
{
    uint32_t idx[] = {0, 1, 2, 0, 2, 3};
    pelt_mesh *m = NULL;
    pelt_error e = {0};
    CHECK(create(tri_pos, NULL, NULL, 3, idx, 2, &m, &e) == PELT_ERR_FORMAT);
    CHECK(m == NULL);
    CHECK(strstr(e.message, "triangle 1") != NULL);
    uint32_t huge[] = {0, 1, 0xffffffffu};
    CHECK(create(tri_pos, NULL, NULL, 3, huge, 1, &m, &e) == PELT_ERR_FORMAT);
    CHECK(strstr(e.message, "triangle 0") != NULL);
}

static void create_drops_repeated_index_and_zero_area_triangles(void)
{
    /* A unit square (two triangles), a repeated-index triangle and a
     * triangle on three collinear points. */
    float pos[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0, 3, 0, 0};
    uint32_t idx[] = {0, 1, 2, 0, 2, 3, 1, 1, 2, 0, 4, 5};
    pelt_mesh *m = NULL;
    pelt_error e = {0};
    CHECK(create(pos, NULL, NULL, 6, idx, 4, &m, &e) == PELT_OK);
    pelt_mesh_stats s = pelt_mesh_get_stats(m);
    CHECK(s.dropped_degenerate == 2);
    CHECK(s.triangle_count == 2);
    CHECK(s.vertex_count == 4); /* vertices 4 and 5 were used only by the dropped one */
    pelt_mesh_destroy(m);
}

static void create_all_degenerate_is_format_error(void)
{
    float pos[] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
    uint32_t idx[] = {0, 1, 2, 0, 0, 1};
    pelt_mesh *m = NULL;
    pelt_error e = {0};
    CHECK(create(pos, NULL, NULL, 3, idx, 2, &m, &e) == PELT_ERR_FORMAT);
    CHECK(m == NULL);
    CHECK(strstr(e.message, "no usable triangles") != NULL);
}

static void create_keeps_unit_input_normals(void)
{
    float nrm[] = {0, 0, 2, 0, 0, 0.5f, 0, 0.6f, 0.8f};
    pelt_mesh *m = NULL;
    CHECK(create(tri_pos, nrm, NULL, 3, tri_idx, 1, &m, NULL) == PELT_OK);
    CHECK(!pelt_mesh_get_stats(m).computed_normals);
    CHECK_NEAR(m->normals[2], 1.0, 1e-6);
    CHECK_NEAR(m->normals[5], 1.0, 1e-6);
    CHECK_NEAR(m->normals[7], 0.6, 1e-6);
    CHECK_NEAR(m->normals[8], 0.8, 1e-6);
    pelt_mesh_destroy(m);
}

static void create_computes_normals_when_one_is_zero_or_nan(void)
{
    float zero[] = {0, 0, 1, 0, 0, 0, 0, 0, 1};
    float nan[] = {0, 0, 1, NAN, 0, 0, 0, 0, 1};
    const float *cases[] = {zero, nan};
    for (int c = 0; c < 2; c++) {
        pelt_mesh *m = NULL;
        /* Clockwise seen from +z: the computed normal is -z, unlike the input. */
        uint32_t cw[] = {0, 2, 1};
        CHECK(create(tri_pos, cases[c], NULL, 3, cw, 1, &m, NULL) == PELT_OK);
        CHECK(pelt_mesh_get_stats(m).computed_normals);
        for (int v = 0; v < 3; v++) CHECK_NEAR(m->normals[3 * v + 2], -1.0, 1e-6);
        pelt_mesh_destroy(m);
    }
}

static void computed_normal_is_area_weighted(void)
{
    /* Vertex 0 is in a +z triangle of area 2 (cross (0,0,4)) and a +x
     * triangle of area 1/2 (cross (1,0,0)): n0 = (1,0,4)/sqrt(17). */
    float pos[] = {0, 0, 0, 2, 0, 0, 0, 2, 0, 0, 1, 0, 0, 0, 1};
    uint32_t idx[] = {0, 1, 2, 0, 3, 4};
    pelt_mesh *m = NULL;
    CHECK(create(pos, NULL, NULL, 5, idx, 2, &m, NULL) == PELT_OK);
    CHECK_NEAR(m->normals[0], 1.0 / sqrt(17.0), 1e-6);
    CHECK_NEAR(m->normals[1], 0.0, 1e-6);
    CHECK_NEAR(m->normals[2], 4.0 / sqrt(17.0), 1e-6);
    pelt_mesh_destroy(m);
}

static void computed_normals_are_welded_by_position(void)
{
    /* Two triangles meeting at a right angle whose shared edge is stored
     * twice (as a uv seam would): 0~3 and 2~4 share positions. */
    float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1};
    uint32_t idx[] = {0, 1, 2, 3, 4, 5};
    pelt_mesh *m = NULL;
    CHECK(create(pos, NULL, NULL, 6, idx, 2, &m, NULL) == PELT_OK);
    CHECK(m->vertex_count == 6);
    const float r = (float)(1.0 / sqrt(2.0));
    const int shared[] = {0, 2, 3, 4};
    for (int k = 0; k < 4; k++) {
        const float *n = m->normals + 3 * shared[k];
        CHECK_NEAR(n[0], r, 1e-6);
        CHECK_NEAR(n[1], 0.0, 1e-6);
        CHECK_NEAR(n[2], r, 1e-6);
    }
    CHECK_NEAR(m->normals[3 * 1 + 2], 1.0, 1e-6); /* only in the +z triangle */
    CHECK_NEAR(m->normals[3 * 5 + 0], 1.0, 1e-6); /* only in the +x triangle */
    pelt_mesh_destroy(m);
}

static void missing_uvs_get_fallback_map_in_unit_square(void)
{
    float pos[] = {-1, -1, -1, 1, -1, -1, 0, 1, 0, 0, -1, 1};
    uint32_t idx[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    pelt_mesh *m = NULL;
    CHECK(create(pos, NULL, NULL, 4, idx, 4, &m, NULL) == PELT_OK);
    CHECK(pelt_mesh_get_stats(m).fallback_uvs);
    for (size_t i = 0; i < 2 * m->vertex_count; i++) CHECK(m->uvs[i] >= 0.0f && m->uvs[i] <= 1.0f);
    CHECK(m->fur_uvs == NULL);
    check_frames_valid(m);
    pelt_mesh_destroy(m);

    float uv[] = {0, 0, 1, 0, 0, 1};
    CHECK(create(tri_pos, NULL, uv, 3, tri_idx, 1, &m, NULL) == PELT_OK);
    CHECK(!pelt_mesh_get_stats(m).fallback_uvs);
    CHECK(m->uvs[2] == 1.0f && m->uvs[5] == 1.0f);
    pelt_mesh_destroy(m);
}

static void tangent_follows_plus_u_with_handedness(void)
{
    /* u along +x, v along +y, normal +z: t = +x, n x t = +y = +v, w = +1.
     * Mirroring v (v along -y) flips w only. */
    float uv[] = {0, 0, 1, 0, 0, 1};
    float uv_mirror[] = {0, 1, 1, 1, 0, 0};
    const float *cases[] = {uv, uv_mirror};
    const float want_w[] = {1.0f, -1.0f};
    for (int c = 0; c < 2; c++) {
        pelt_mesh *m = NULL;
        CHECK(create(tri_pos, NULL, cases[c], 3, tri_idx, 1, &m, NULL) == PELT_OK);
        for (int v = 0; v < 3; v++) {
            CHECK_NEAR(m->tangents[4 * v + 0], 1.0, 1e-6);
            CHECK_NEAR(m->tangents[4 * v + 1], 0.0, 1e-6);
            CHECK_NEAR(m->tangents[4 * v + 3], want_w[c], 0.0);
        }
        pelt_mesh_destroy(m);
    }
}

static void tangent_has_fallback_where_uvs_are_degenerate(void)
{
    float uv[] = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
    pelt_mesh *m = NULL;
    CHECK(create(tri_pos, NULL, uv, 3, tri_idx, 1, &m, NULL) == PELT_OK);
    check_frames_valid(m);
    pelt_mesh_destroy(m);
}

static void bounds_cover_positions(void)
{
    float pos[] = {-1, 2, 3, 4, -5, 6, 7, 8, -9};
    pelt_mesh *m = NULL;
    CHECK(create(pos, NULL, NULL, 3, tri_idx, 1, &m, NULL) == PELT_OK);
    float lo[3], hi[3];
    pelt_mesh_bounds(m, lo, hi);
    CHECK(lo[0] == -1 && lo[1] == -5 && lo[2] == -9);
    CHECK(hi[0] == 7 && hi[1] == 8 && hi[2] == 6);
    pelt_mesh_destroy(m);
}

/* ---- procedural ------------------------------------------------------ */

static void default_torus_has_9360_triangles(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 78, 60, &m, NULL) == PELT_OK);
    CHECK(pelt_mesh_get_stats(m).triangle_count == 9360);
    CHECK(m->triangle_count == 9360);
    CHECK(m->vertex_count == 79 * 61); /* seam rows duplicated */
    CHECK(pelt_mesh_get_stats(m).dropped_degenerate == 0);
    CHECK(!pelt_mesh_get_stats(m).fallback_uvs);
    float lo[3], hi[3];
    pelt_mesh_bounds(m, lo, hi);
    CHECK_NEAR(hi[1], 0.4, 1e-4); /* axis +Y: the tube's top is at y = minor */
    CHECK_NEAR(lo[1], -0.4, 1e-4);
    CHECK_NEAR(hi[0], 1.4, 1e-4);
    CHECK_NEAR(hi[2], 1.4 * cos(3.14159265358979 / 78.0), 1e-4); /* 78/4 is no vertex */
    pelt_mesh_destroy(m);
}

static void torus_normals_point_away_from_the_tube_centre(void)
{
    const float R = 2.0f, r = 0.5f;
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_torus(R, r, 24, 12, &m, NULL) == PELT_OK);
    size_t bad = 0;
    for (size_t i = 0; i < m->vertex_count; i++) {
        const float *p = m->positions + 3 * i, *n = m->normals + 3 * i;
        float h = sqrtf(p[0] * p[0] + p[2] * p[2]);
        float c[3] = {R * p[0] / h, 0.0f, R * p[2] / h};
        for (int k = 0; k < 3; k++)
            if (fabsf((p[k] - c[k]) / r - n[k]) > 1e-4f) bad++;
    }
    CHECK(bad == 0);
    check_frames_valid(m);
    check_faces_outward(m);
    pelt_mesh_destroy(m);
}

/* The vertices at u = 0 and u = 1 (and v = 0, v = 1) are the same points. */
static void check_torus_seams(const pelt_mesh *m, unsigned M, unsigned n_minor, int tangents_too)
{
    size_t row = n_minor + 1, bad = 0;
    for (unsigned j = 0; j <= n_minor; j++) {
        size_t a = j, b = (size_t)M * row + j;
        if (memcmp(m->positions + 3 * a, m->positions + 3 * b, 3 * sizeof(float))) bad++;
        if (memcmp(m->normals + 3 * a, m->normals + 3 * b, 3 * sizeof(float))) bad++;
        if (tangents_too && memcmp(m->tangents + 4 * a, m->tangents + 4 * b, 4 * sizeof(float))) bad++;
    }
    for (unsigned i = 0; i <= M; i++) {
        size_t a = i * row, b = i * row + n_minor;
        if (memcmp(m->positions + 3 * a, m->positions + 3 * b, 3 * sizeof(float))) bad++;
        if (memcmp(m->normals + 3 * a, m->normals + 3 * b, 3 * sizeof(float))) bad++;
        if (tangents_too && memcmp(m->tangents + 4 * a, m->tangents + 4 * b, 4 * sizeof(float))) bad++;
    }
    CHECK(bad == 0);
}

static void torus_seam_vertices_share_normals_and_tangents(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 78, 60, &m, NULL) == PELT_OK);
    check_torus_seams(m, 78, 60, 1);
    pelt_mesh_destroy(m);
}

static void torus_without_normals_gets_welded_seam_normals(void)
{
    pelt_mesh *t = NULL, *m = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 30, 20, &t, NULL) == PELT_OK);
    CHECK(create(t->positions, NULL, t->uvs, t->vertex_count, t->indices, t->triangle_count, &m,
                 NULL) == PELT_OK);
    CHECK(pelt_mesh_get_stats(m).computed_normals);
    /* Vertices were renumbered: pair the seam copies by uv instead. */
    size_t pairs = 0, bad = 0;
    for (size_t a = 0; a < m->vertex_count; a++) {
        if (m->uvs[2 * a] != 0.0f) continue;
        for (size_t b = 0; b < m->vertex_count; b++) {
            if (m->uvs[2 * b] != 1.0f || m->uvs[2 * b + 1] != m->uvs[2 * a + 1]) continue;
            pairs++;
            if (memcmp(m->positions + 3 * a, m->positions + 3 * b, 3 * sizeof(float))) bad++;
            if (memcmp(m->normals + 3 * a, m->normals + 3 * b, 3 * sizeof(float))) bad++;
            if (memcmp(m->tangents + 4 * a, m->tangents + 4 * b, 4 * sizeof(float))) bad++;
        }
    }
    CHECK(pairs == 21);
    CHECK(bad == 0);
    /* Computed normals stay close to the analytic ones. */
    size_t far = 0;
    for (size_t i = 0; i < m->vertex_count; i++) {
        const float *p = m->positions + 3 * i;
        float h = sqrtf(p[0] * p[0] + p[2] * p[2]);
        float d[3] = {p[0] - p[0] / h, p[1], p[2] - p[2] / h};
        float l = len3(d);
        float nd[3] = {d[0] / l, d[1] / l, d[2] / l};
        if (dot3(nd, m->normals + 3 * i) < 0.99f) far++;
    }
    CHECK(far == 0);
    check_frames_valid(m);
    pelt_mesh_destroy(m);
    pelt_mesh_destroy(t);
}

/* pelt_mesh_get_data of a created mesh creates the same mesh again: unit
 * normals (computed ones here) are kept as given, not normalised anew. */
static void create_of_get_data_gives_the_same_mesh(void)
{
    pelt_mesh *t = NULL, *m = NULL, *r = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 30, 20, &t, NULL) == PELT_OK);
    CHECK(create(t->positions, NULL, t->uvs, t->vertex_count, t->indices, t->triangle_count, &m,
                 NULL) == PELT_OK);
    pelt_mesh_destroy(m), m = NULL;
    /* An up axis other than +Y (as an FBX file declares it) is normalised
     * and travels through the arrays too. */
    const float up[3] = {0.0f, 0.0f, -2.0f};
    pelt_mesh_data in = pelt_mesh_get_data(t);
    in.normals = NULL, in.fur_uvs = NULL, in.comb = NULL, in.up = up;
    CHECK(pelt_mesh_create(&in, &m, NULL) == PELT_OK);
    pelt_mesh_data d = pelt_mesh_get_data(m);
    CHECK(d.up && d.up[0] == 0.0f && d.up[1] == 0.0f && d.up[2] == -1.0f);
    CHECK(pelt_mesh_create(&d, &r, NULL) == PELT_OK);
    if (r) {
        size_t n = m->vertex_count;
        float ru[3];
        pelt_mesh_up(r, ru);
        CHECK(ru[0] == 0.0f && ru[1] == 0.0f && ru[2] == -1.0f);
        CHECK(r->vertex_count == n && r->triangle_count == m->triangle_count);
        CHECK(!memcmp(r->positions, m->positions, n * 12));
        CHECK(!memcmp(r->normals, m->normals, n * 12));
        CHECK(!memcmp(r->tangents, m->tangents, n * 16));
        CHECK(!memcmp(r->indices, m->indices, m->triangle_count * 12));
    }
    pelt_mesh_destroy(r), r = NULL;
    /* A zero or non-finite up is an error, not a silent +Y. */
    const float zero[3] = {0.0f, 0.0f, 0.0f};
    in.up = zero;
    pelt_error err = {0};
    CHECK(pelt_mesh_create(&in, &r, &err) == PELT_ERR_FORMAT && r == NULL);
    CHECK(strstr(err.message, "up axis") != NULL);
    pelt_mesh_destroy(m);
    pelt_mesh_destroy(t);
}

static void sphere_counts_radius_and_frames(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_sphere(1.5f, 16, 8, &m, NULL) == PELT_OK);
    CHECK(m->triangle_count == 2 * 16 * (8 - 1));
    CHECK(pelt_mesh_get_stats(m).dropped_degenerate == 0);
    size_t bad = 0;
    for (size_t i = 0; i < m->vertex_count; i++)
        if (fabsf(len3(m->positions + 3 * i) - 1.5f) > 1e-5f) bad++;
    CHECK(bad == 0);
    check_frames_valid(m);
    check_faces_outward(m);
    pelt_mesh_destroy(m);
}

static void square_lies_in_xz_with_normal_up(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_square(2.0f, 4, &m, NULL) == PELT_OK);
    CHECK(m->triangle_count == 32);
    CHECK(m->vertex_count == 25);
    float lo[3], hi[3];
    pelt_mesh_bounds(m, lo, hi);
    CHECK(lo[0] == -1.0f && hi[0] == 1.0f && lo[2] == -1.0f && hi[2] == 1.0f);
    CHECK(lo[1] == 0.0f && hi[1] == 0.0f);
    for (size_t i = 0; i < m->vertex_count; i++) {
        CHECK(m->normals[3 * i + 1] == 1.0f);
        CHECK_NEAR(m->tangents[4 * i], 1.0, 1e-6); /* u grows with x */
        CHECK(m->tangents[4 * i + 3] == 1.0f);
        CHECK(m->uvs[2 * i] >= 0.0f && m->uvs[2 * i] <= 1.0f);
        CHECK(m->uvs[2 * i + 1] >= 0.0f && m->uvs[2 * i + 1] <= 1.0f);
    }
    check_faces_outward(m);
    pelt_mesh_destroy(m);
}

static void procedural_rejects_bad_arguments(void)
{
    pelt_mesh *m = NULL;
    pelt_error e = {0};
    CHECK(pelt_mesh_torus(0.0f, 0.4f, 78, 60, &m, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(e.message, "major_radius") != NULL);
    CHECK(pelt_mesh_torus(1.0f, NAN, 78, 60, &m, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 2, 60, &m, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(e.message, "major_segments") != NULL);
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 78, 4000000000u, &m, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(pelt_mesh_sphere(1.0f, 16, 1, &m, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(pelt_mesh_sphere(-1.0f, 16, 8, &m, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(pelt_mesh_square(1.0f, 0, &m, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(pelt_mesh_square(INFINITY, 1, &m, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(m == NULL);
}

/* ---- import ---------------------------------------------------------- */

#define MESH_DIR PELT_TEST_DATA "/meshes/"

static void good_files_load_with_expected_counts(void)
{
    static const struct {
        const char *name;
        size_t vertices, triangles;
        bool fallback_uvs;
    } cases[] = {
        {"cube_quads.obj", 8, 12, true},     /* 6 quads, triangulated */
        {"square_uv.obj", 4, 2, false},      /* one quad with vt */
        {"mixed_primitives.obj", 3, 1, true}, /* the line and point are dropped */
        {"tetra.off", 4, 4, true},
        {"tetra.ply", 4, 4, true},
        {"two_facets.stl", 4, 2, true},       /* corners joined by position */
        {"one_triangle_binary.stl", 3, 1, true},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        pelt_mesh *m = NULL;
        pelt_error e = {0};
        char path[1024];
        snprintf(path, sizeof path, "%s%s", MESH_DIR, cases[i].name);
        pelt_status st = pelt_mesh_load(path, &m, &e);
        if (st != PELT_OK) fprintf(stderr, "  %s: %s\n", cases[i].name, e.message);
        CHECK(st == PELT_OK);
        pelt_mesh_stats s = pelt_mesh_get_stats(m);
        CHECK(s.vertex_count == cases[i].vertices);
        CHECK(s.triangle_count == cases[i].triangles);
        CHECK(s.fallback_uvs == cases[i].fallback_uvs);
        CHECK(s.dropped_degenerate == 0);
        if (m) check_frames_valid(m);
        if (m && s.computed_normals) check_faces_outward(m);
        pelt_mesh_destroy(m);
    }
}

static void cube_file_bounds_and_outward_normals(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_load(MESH_DIR "cube_quads.obj", &m, NULL) == PELT_OK);
    float lo[3], hi[3];
    pelt_mesh_bounds(m, lo, hi);
    for (int k = 0; k < 3; k++) CHECK(lo[k] == -0.5f && hi[k] == 0.5f);
    /* Each corner normal is a positive mix of its three outward face
     * normals, so it points away from the centre. */
    for (size_t i = 0; m && i < m->vertex_count; i++)
        CHECK(dot3(m->normals + 3 * i, m->positions + 3 * i) > 0.2f);
    check_faces_outward(m);
    pelt_mesh_destroy(m);
}

static void bad_files_fail_cleanly_naming_the_file(void)
{
    static const char *const bad[] = {
        "bad_all_degenerate.obj", "bad_empty.obj",           "bad_empty.off",
        "bad_empty.ply",          "bad_empty.stl",           "bad_garbage.obj",
        "bad_garbage.off",        "bad_garbage.ply",         "bad_garbage.stl",
        "bad_huge_count.off",     "bad_huge_count.ply",      "bad_huge_count.stl",
        "bad_index_huge.obj",     "bad_index_range.obj",     "bad_index_range.off",
        "bad_index_range.ply",    "bad_inf.obj",             "bad_inf.off",
        "bad_lines_only.obj",     "bad_nan.obj",             "bad_nan.off",
        "bad_nan.ply",            "bad_nan.stl",             "bad_negative_count.off",
        "bad_negative_index.obj", "bad_negative_index.off",  "bad_negative_index.ply",
        "bad_truncated.obj",      "bad_truncated.off",       "bad_truncated.ply",
        "bad_truncated.stl",      "bad_truncated_binary.ply", "bad_list_short.ply",
        "bad_list_long_count.ply", "bad_list_short_binary.ply", "bad_truncated_solid.stl",
        "bad_face_two_vertices.obj", "bad_face_one_vertex.obj", "bad_accessor_range.gltf",
        "bad_view_range.gltf",    "bad_accessor_offset.gltf", "bad_glb_chunk_length.glb",
        "bad_stl_misspelt.stl",   "bad_off_counts_two_lines.off", "bad_ply_carriage_return.ply",
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s%s", MESH_DIR, bad[i]);
        pelt_mesh *m = NULL;
        pelt_error e = {0};
        pelt_status st = pelt_mesh_load(path, &m, &e);
        printf("  %-26s -> %s\n", bad[i], e.message);
        CHECK(st == PELT_ERR_FORMAT);
        CHECK(m == NULL);
        CHECK(strstr(e.message, bad[i]) != NULL);
    }
}

static void specific_bad_files_say_what_is_wrong(void)
{
    static const struct {
        const char *name, *says;
    } cases[] = {
        {"bad_huge_count.off", "2000000000"},
        {"bad_huge_count.ply", "4294967295"},
        {"bad_index_range.off", "vertex '9'"},
        {"bad_negative_index.off", "vertex '-1'"},
        {"bad_nan.obj", "non-finite"},
        {"bad_lines_only.obj", "no triangles"},
        {"bad_empty.obj", "empty"},
        /* Strict, never a silently partial mesh. */
        {"bad_list_short.ply", "line 18: PLY 'face' 3: list 'vertex_indices' declares 4 entries but the line holds 3"},
        {"bad_list_long_count.ply", "declares 9 entries but the line holds 3"},
        {"bad_list_short_binary.ply", "'face' 1 of 2 declares 3 entries but the file ends first"},
        {"bad_truncated_solid.stl", "binary STL declares 2 triangles (184 bytes) but the file has 154 bytes"},
        {"bad_truncated_binary.ply", "file ends in 'vertex' 1 of 3"},
        {"bad_face_two_vertices.obj", "line 7: a face of 2 corners"},
        {"bad_face_one_vertex.obj", "line 5: a face of 1 corner;"},
        {"bad_index_range.obj", "line 4: face refers to vertex '99' but there are 3 vertices"},
        {"bad_negative_index.obj", "vertex '-5' but there are 3 vertices before it"},
        {"bad_accessor_range.gltf", "Accessor with offset/length (0/1600) is out of range"},
        {"bad_view_range.gltf", "Buffer view with offset/length (4000/12) is out of range"},
        {"bad_accessor_offset.gltf", "Accessor with offset/length (8/12) is out of range"},
        {"bad_glb_chunk_length.glb", "GLB chunk 0 declares 2734687028 bytes but only"},
        /* Found by fuzzing: inputs that made assimp leak or allocate gigabytes. */
        {"bad_stl_misspelt.stl", "line 2: STL facet 0 does not start with 'facet normal'"},
        {"bad_off_counts_two_lines.off", "declares 3 vertices and 3000000000 faces"},
        {"bad_ply_carriage_return.ply", "line 12: ASCII PLY holds control character 0x0d"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s%s", MESH_DIR, cases[i].name);
        pelt_mesh *m = NULL;
        pelt_error e = {0};
        pelt_mesh_load(path, &m, &e);
        CHECK(strstr(e.message, cases[i].says) != NULL);
        if (!strstr(e.message, cases[i].says))
            fprintf(stderr, "  expected '%s' in: %s\n", cases[i].says, e.message);
        pelt_mesh_destroy(m);
    }
}

static void missing_file_is_io_error_naming_it(void)
{
    pelt_mesh *m = NULL;
    pelt_error e = {0};
    CHECK(pelt_mesh_load(PELT_TEST_DATA "/meshes", &m, &e) == PELT_ERR_IO); /* a directory */
    CHECK(strstr(e.message, "meshes': Is a directory") != NULL);
    CHECK(pelt_mesh_load(MESH_DIR "no_such_mesh.obj", &m, &e) == PELT_ERR_IO);
    CHECK(strstr(e.message, "cannot open '") != NULL);
    CHECK(strstr(e.message, "no_such_mesh.obj': No such file") != NULL);
    CHECK(pelt_mesh_load(NULL, &m, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(pelt_mesh_load(MESH_DIR "tetra.off", NULL, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(m == NULL);
}

/* A whole file into memory (free it). */
static unsigned char *read_whole(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    CHECK(f != NULL);
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *buf = malloc((size_t)n + 1);
    *size = fread(buf, 1, (size_t)n, f);
    fclose(f);
    return buf;
}

/* pelt_mesh_load_memory gives what pelt_mesh_load gives, good or bad. */
static void memory_load_equals_file_load(void)
{
    static const char *const names[] = {
        "tetra.off", "tetra.ply", "swirl_colors.ply", "two_facets.stl", "one_triangle_binary.stl",
        "cube_quads.obj", "quad.gltf", "quad.glb", "bad_list_short.ply", "bad_face_two_vertices.obj",
        "bad_truncated_solid.stl", "bad_huge_count.off", "bad_accessor_range.gltf", "bad_empty.obj"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s%s", MESH_DIR, names[i]);
        size_t size = 0;
        unsigned char *data = read_whole(path, &size);
        pelt_mesh *a = NULL, *b = NULL;
        pelt_error ea = {0}, eb = {0};
        pelt_status sa = pelt_mesh_load(path, &a, &ea);
        pelt_status sb = pelt_mesh_load_memory(data, size, path, &b, &eb);
        CHECK(sa == sb);
        CHECK(!strcmp(ea.message, eb.message));
        if (sa != sb || strcmp(ea.message, eb.message))
            fprintf(stderr, "  %s: file '%s', memory '%s'\n", names[i], ea.message, eb.message);
        if (a && b) {
            pelt_mesh_data da = pelt_mesh_get_data(a), db = pelt_mesh_get_data(b);
            CHECK(da.vertex_count == db.vertex_count && da.triangle_count == db.triangle_count);
            CHECK(!memcmp(da.positions, db.positions, da.vertex_count * 3 * sizeof(float)));
        }
        pelt_mesh_destroy(a), pelt_mesh_destroy(b);
        free(data);
    }
    pelt_mesh *m = NULL;
    pelt_error e = {0};
    CHECK(pelt_mesh_load_memory("v 0 0 0", 7, "no_extension", &m, &e) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(e.message, "extension") != NULL);
}

int main(void)
{
    RUN(create_rejects_null_and_zero_counts);
    RUN(create_rejects_nonfinite_coordinate_naming_vertex);
    RUN(create_rejects_absurd_coordinates);
    RUN(microscopic_and_huge_meshes_get_valid_frames);
    RUN(create_rejects_index_out_of_range_naming_triangle);
    RUN(create_drops_repeated_index_and_zero_area_triangles);
    RUN(create_all_degenerate_is_format_error);
    RUN(create_keeps_unit_input_normals);
    RUN(create_computes_normals_when_one_is_zero_or_nan);
    RUN(computed_normal_is_area_weighted);
    RUN(computed_normals_are_welded_by_position);
    RUN(missing_uvs_get_fallback_map_in_unit_square);
    RUN(tangent_follows_plus_u_with_handedness);
    RUN(tangent_has_fallback_where_uvs_are_degenerate);
    RUN(bounds_cover_positions);
    RUN(default_torus_has_9360_triangles);
    RUN(torus_normals_point_away_from_the_tube_centre);
    RUN(torus_seam_vertices_share_normals_and_tangents);
    RUN(torus_without_normals_gets_welded_seam_normals);
    RUN(create_of_get_data_gives_the_same_mesh);
    RUN(sphere_counts_radius_and_frames);
    RUN(square_lies_in_xz_with_normal_up);
    RUN(procedural_rejects_bad_arguments);
    RUN(good_files_load_with_expected_counts);
    RUN(cube_file_bounds_and_outward_normals);
    RUN(bad_files_fail_cleanly_naming_the_file);
    RUN(specific_bad_files_say_what_is_wrong);
    RUN(missing_file_is_io_error_naming_it);
    RUN(memory_load_equals_file_load);
    return check_summary();
}
