/* Grooming (Lengyel et al. 2001 §3): brushes touch exactly the vertices
 * inside them with the stated falloff, maps land on the vertices under
 * them, and groom files round-trip, survive a different vertex order and
 * refuse corrupt or foreign files with a message. No GL. */
#include "pelt/pelt.h"
#include "support/check.h"

#include "core/fur/shading.h"

#include <stdlib.h>
#include <string.h>

static pelt_mesh *square(unsigned subdivisions)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_square(2.0f, subdivisions, &m, NULL) == PELT_OK);
    return m;
}

static pelt_fur *fur_for(const pelt_mesh *m)
{
    pelt_fur *f = NULL;
    pelt_fur_desc d = {.layers = 4, .look.texture_size = 16, .length = 0.1f};
    CHECK(pelt_fur_create(m, &d, &f, NULL) == PELT_OK);
    return f;
}

static bool same_value(pelt_groom_value a, pelt_groom_value b)
{
    return !memcmp(&a, &b, sizeof a);
}

static float distance(const float *p, const float c[3])
{
    float d2 = 0.0f;
    for (int k = 0; k < 3; k++) d2 += (p[k] - c[k]) * (p[k] - c[k]);
    return sqrtf(d2);
}

/* A comb stroke changes exactly the vertices closer than the radius (the
 * set a scan of every vertex finds), by delta / length times the falloff,
 * along the tangent; the rest keep their value bit for bit. */
static void comb_touches_exactly_the_ball(void)
{
    pelt_mesh *m = square(40);
    pelt_fur *f = fur_for(m);
    pelt_mesh_data md = pelt_mesh_get_data(m);
    const float *tan = pelt_mesh_tangents(m);
    const float c[3] = {0.13f, 0.0f, -0.21f};
    pelt_brush b = {.tool = PELT_BRUSH_COMB, .radius = 0.4f, .delta = {0.05f, 0.3f, 0.0f}};
    size_t touched = 0;
    CHECK(pelt_fur_brush(f, c, &b, &touched, NULL) == PELT_OK);
    size_t inside = 0, wrong = 0;
    double worst = 0.0;
    for (size_t i = 0; i < md.vertex_count; i++) {
        float d = distance(md.positions + 3 * i, c);
        pelt_groom_value v = pelt_fur_get_groom(f, i);
        if (d >= b.radius) {
            if (!same_value(v, pelt_groom_value_default())) wrong++;
            continue;
        }
        inside++;
        float q = 1.0f - (d / b.radius) * (d / b.radius);
        /* The square's normal is +Y: delta's tangential part is (dx, 0, dz);
         * lean along u = tangent . delta / L. */
        const float *u = tan + 4 * i;
        float du = u[0] * b.delta[0] + u[2] * b.delta[2];
        double e = fabs(v.lean[0] * 0.1f - q * q * du);
        if (e > worst) worst = e;
    }
    printf("  %zu vertices inside the brush, %zu touched, %zu outside changed, worst lean error %.2g\n",
           inside, touched, wrong, worst);
    CHECK(inside > 100);
    CHECK(touched == inside);
    CHECK(wrong == 0);
    CHECK(worst < 1e-5);
    pelt_fur_destroy(f);
    pelt_mesh_destroy(m);
}

/* Length adds amount x falloff; density moves towards its target; colour
 * paints over: the centre takes the paint, the weight rises towards 1. */
static void length_density_and_colour_strokes(void)
{
    pelt_mesh *m = square(20);
    pelt_fur *f = fur_for(m);
    pelt_mesh_data md = pelt_mesh_get_data(m);
    const float c[3] = {0.0f, 0.0f, 0.0f};
    size_t centre = 0;
    for (size_t i = 0; i < md.vertex_count; i++)
        if (distance(md.positions + 3 * i, c) < distance(md.positions + 3 * centre, c)) centre = i;
    CHECK(distance(md.positions + 3 * centre, c) < 1e-6f);

    pelt_brush len = {.tool = PELT_BRUSH_LENGTH, .radius = 0.5f, .amount = 1.5f};
    CHECK(pelt_fur_brush(f, c, &len, NULL, NULL) == PELT_OK);
    CHECK_NEAR(pelt_fur_get_groom(f, centre).length, 2.5f, 1e-6);
    len.amount = -10.0f; /* shortened below 0: clamped to bare skin length */
    CHECK(pelt_fur_brush(f, c, &len, NULL, NULL) == PELT_OK);
    CHECK_NEAR(pelt_fur_get_groom(f, centre).length, 0.0f, 0.0);

    pelt_brush den = {.tool = PELT_BRUSH_DENSITY, .radius = 0.5f, .amount = 0.2f, .strength = 0.5f};
    CHECK(pelt_fur_brush(f, c, &den, NULL, NULL) == PELT_OK);
    CHECK_NEAR(pelt_fur_get_groom(f, centre).density, 0.6f, 1e-6); /* halfway from 1 to 0.2 */

    pelt_brush col = {.tool = PELT_BRUSH_COLOR, .radius = 0.5f, .color = {0.0f, 0.4f, 1.0f}};
    CHECK(pelt_fur_brush(f, c, &col, NULL, NULL) == PELT_OK);
    pelt_groom_value v = pelt_fur_get_groom(f, centre);
    CHECK_NEAR(v.color[3], 1.0f, 1e-6);
    CHECK_NEAR(v.color[1], 0.4f, 1.0 / 255.0);
    CHECK_NEAR(v.color[2], 1.0f, 1.0 / 255.0);
    /* Halfway out the weight is the falloff (painted over nothing). */
    size_t mid = centre;
    for (size_t i = 0; i < md.vertex_count; i++) {
        float d = distance(md.positions + 3 * i, c);
        if (fabsf(d - 0.25f) < fabsf(distance(md.positions + 3 * mid, c) - 0.25f)) mid = i;
    }
    float d = distance(md.positions + 3 * mid, c), q = 1.0f - (d / 0.5f) * (d / 0.5f);
    CHECK_NEAR(pelt_fur_get_groom(f, mid).color[3], q * q, 1.0 / 255.0);
    CHECK_NEAR(pelt_fur_get_groom(f, mid).color[2], 1.0f, 1.0 / 255.0);
    pelt_fur_destroy(f);
    pelt_mesh_destroy(m);
}

static void bad_brushes_and_values_change_nothing(void)
{
    pelt_mesh *m = square(4);
    pelt_fur *f = fur_for(m);
    const float c[3] = {0, 0, 0};
    pelt_error err = {0};
    pelt_brush b = {.tool = PELT_BRUSH_COMB, .radius = -1.0f};
    CHECK(pelt_fur_brush(f, c, &b, NULL, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "radius") != NULL);
    b.radius = 1.0f;
    b.delta[1] = NAN;
    CHECK(pelt_fur_brush(f, c, &b, NULL, &err) == PELT_ERR_INVALID_ARGUMENT);
    b.delta[1] = 0.0f;
    b.tool = (pelt_brush_tool)99;
    CHECK(pelt_fur_brush(f, c, &b, NULL, &err) == PELT_ERR_INVALID_ARGUMENT);
    pelt_groom_value v = pelt_groom_value_default();
    v.length = INFINITY;
    CHECK(pelt_fur_set_groom(f, 0, 1, &v, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(pelt_fur_set_groom(f, pelt_fur_vertex_count(f), 1, &v, &err) == PELT_ERR_INVALID_ARGUMENT);
    for (size_t i = 0; i < pelt_fur_vertex_count(f); i++)
        CHECK(same_value(pelt_fur_get_groom(f, i), pelt_groom_value_default()));
    /* A ray that misses touches nothing. */
    const float o[3] = {0, 1, 0}, up[3] = {0, 1, 0};
    b.tool = PELT_BRUSH_LENGTH;
    b.amount = 1.0f;
    CHECK(!pelt_fur_brush_ray(f, o, up, &b, NULL));
    const float down[3] = {0, -1, 0};
    float hit[3];
    CHECK(pelt_fur_brush_ray(f, o, down, &b, hit));
    CHECK_NEAR(hit[1], 0.0f, 1e-6);
    pelt_fur_destroy(f);
    pelt_mesh_destroy(m);
}

/* A length map of vertical stripes (row 0 at the top) gives each vertex
 * the stripe under its uv. */
static void length_map_lands_on_the_vertices(void)
{
    pelt_mesh *m = square(32);
    pelt_fur *f = fur_for(m);
    enum { W = 64, H = 8 };
    uint8_t img[W * H * 4];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int k = 0; k < 4; k++) img[(y * W + x) * 4 + k] = (x / 8) % 2 ? 255 : 0;
    CHECK(pelt_fur_groom_from_image(f, PELT_GROOM_LENGTH, img, W, H, 0.5f, 2.0f, NULL) == PELT_OK);
    pelt_mesh_data md = pelt_mesh_get_data(m);
    size_t checked = 0, wrong = 0;
    for (size_t i = 0; i < md.vertex_count; i++) {
        float u = md.uvs[2 * i] * W;
        float into = fmodf(u, 8.0f);
        if (into < 1.0f || into > 7.0f) continue; /* near a stripe edge: blended */
        float want = ((int)(u / 8.0f) % 2) ? 2.0f : 0.5f;
        checked++;
        if (fabsf(pelt_fur_get_groom(f, i).length - want) > 1e-4f) wrong++;
    }
    printf("  %zu vertices away from stripe edges, %zu wrong\n", checked, wrong);
    CHECK(checked > 500);
    CHECK(wrong == 0);
    pelt_error err = {0};
    CHECK(pelt_fur_groom_from_image(f, PELT_GROOM_LENGTH, img, 0, H, 0, 1, &err) != PELT_OK);
    pelt_fur_destroy(f);
    pelt_mesh_destroy(m);
}

static const char *out_path(const char *name)
{
    static char buf[1024];
    snprintf(buf, sizeof buf, "%s/%s", PELT_TEST_OUT, name);
    return buf;
}

static void paint_something(pelt_fur *f)
{
    const float a[3] = {0.3f, 0.0f, 0.2f}, b[3] = {-0.4f, 0.0f, -0.1f};
    pelt_brush comb = {.tool = PELT_BRUSH_COMB, .radius = 0.5f, .delta = {0.02f, 0, 0.05f}};
    pelt_brush col = {.tool = PELT_BRUSH_COLOR, .radius = 0.6f, .color = {0.9f, 0.1f, 0.3f}, .strength = 0.7f};
    pelt_brush den = {.tool = PELT_BRUSH_DENSITY, .radius = 0.3f, .amount = 0.0f};
    pelt_brush len = {.tool = PELT_BRUSH_LENGTH, .radius = 0.7f, .amount = 0.8f};
    CHECK(pelt_fur_brush(f, a, &comb, NULL, NULL) == PELT_OK);
    CHECK(pelt_fur_brush(f, b, &col, NULL, NULL) == PELT_OK);
    CHECK(pelt_fur_brush(f, a, &den, NULL, NULL) == PELT_OK);
    CHECK(pelt_fur_brush(f, b, &len, NULL, NULL) == PELT_OK);
}

/* Save, reset, load: every value back bit for bit. */
static void groom_file_round_trip(void)
{
    pelt_mesh *m = square(24);
    pelt_fur *f = fur_for(m);
    paint_something(f);
    size_t n = pelt_fur_vertex_count(f);
    pelt_groom_value *before = malloc(n * sizeof *before);
    for (size_t i = 0; i < n; i++) before[i] = pelt_fur_get_groom(f, i);
    const char *path = out_path("round_trip.groom.ply");
    pelt_error err = {0};
    CHECK(pelt_fur_save_groom(f, path, &err) == PELT_OK);
    pelt_fur_reset_groom(f);
    CHECK(same_value(pelt_fur_get_groom(f, n / 2), pelt_groom_value_default()));
    CHECK(pelt_fur_load_groom(f, path, &err) == PELT_OK);
    size_t differ = 0;
    for (size_t i = 0; i < n; i++) differ += !same_value(before[i], pelt_fur_get_groom(f, i));
    CHECK(differ == 0);
    free(before);
    pelt_fur_destroy(f);
    pelt_mesh_destroy(m);
}

/* The same surface with its vertices numbered backwards (another file
 * order, another validation): the groom follows the positions. */
static void groom_file_survives_another_vertex_order(void)
{
    pelt_mesh *m = square(24);
    pelt_fur *f = fur_for(m);
    paint_something(f);
    const char *path = out_path("reordered.groom.ply");
    CHECK(pelt_fur_save_groom(f, path, NULL) == PELT_OK);

    pelt_mesh_data md = pelt_mesh_get_data(m);
    size_t n = md.vertex_count;
    float *pos = malloc(n * 3 * sizeof(float)), *nrm = malloc(n * 3 * sizeof(float));
    float *uv = malloc(n * 2 * sizeof(float));
    uint32_t *idx = malloc(md.triangle_count * 3 * sizeof(uint32_t));
    for (size_t i = 0; i < n; i++) {
        size_t j = n - 1 - i;
        memcpy(pos + 3 * j, md.positions + 3 * i, 3 * sizeof(float));
        memcpy(nrm + 3 * j, md.normals + 3 * i, 3 * sizeof(float));
        memcpy(uv + 2 * j, md.uvs + 2 * i, 2 * sizeof(float));
    }
    /* Triangles in reverse too, so validation numbers vertices differently. */
    for (size_t t = 0; t < md.triangle_count; t++)
        for (int k = 0; k < 3; k++)
            idx[3 * (md.triangle_count - 1 - t) + (size_t)k] =
                (uint32_t)(n - 1 - md.indices[3 * t + (size_t)k]);
    pelt_mesh_data rd = {pos, nrm, uv, n, idx, md.triangle_count, NULL, NULL, NULL, NULL};
    pelt_mesh *m2 = NULL;
    CHECK(pelt_mesh_create(&rd, &m2, NULL) == PELT_OK);
    pelt_mesh_data md2 = pelt_mesh_get_data(m2);
    CHECK(memcmp(md2.positions, md.positions, n * 3 * sizeof(float)) != 0); /* really reordered */
    pelt_fur *f2 = fur_for(m2);
    pelt_error err = {0};
    CHECK(pelt_fur_load_groom(f2, path, &err) == PELT_OK);
    size_t differ = 0;
    for (size_t i = 0; i < n; i++) {
        /* Find vertex i of the first mesh in the second by position. */
        size_t j = 0;
        while (j < n && memcmp(md2.positions + 3 * j, md.positions + 3 * i, 3 * sizeof(float))) j++;
        CHECK(j < n);
        if (j < n) differ += !same_value(pelt_fur_get_groom(f, i), pelt_fur_get_groom(f2, j));
    }
    printf("  %zu of %zu vertices differ after loading into the reordered mesh\n", differ, n);
    CHECK(differ == 0);
    free(pos), free(nrm), free(uv), free(idx);
    pelt_fur_destroy(f2);
    pelt_mesh_destroy(m2);
    pelt_fur_destroy(f);
    pelt_mesh_destroy(m);
}

static unsigned char *slurp(const char *path, size_t *size)
{
    FILE *in = fopen(path, "rb");
    if (!in) return NULL;
    fseek(in, 0, SEEK_END);
    *size = (size_t)ftell(in);
    fseek(in, 0, SEEK_SET);
    unsigned char *data = malloc(*size + 1);
    if (data && fread(data, 1, *size, in) != *size) *size = 0;
    fclose(in);
    return data;
}

/* Loads `data` into a freshly groomed fur: must fail with PELT_ERR_FORMAT,
 * a message naming the file and holding `why`, and change nothing. */
static void refused(pelt_fur *f, const void *data, size_t size, const char *why)
{
    pelt_groom_value before = pelt_fur_get_groom(f, 7);
    pelt_error err = {0};
    pelt_status st = pelt_fur_load_groom_memory(f, data, size, "furry.ply", &err);
    printf("  %s\n", err.message);
    CHECK(st == PELT_ERR_FORMAT);
    CHECK(strstr(err.message, "furry.ply") != NULL);
    CHECK(strstr(err.message, why) != NULL);
    CHECK(same_value(before, pelt_fur_get_groom(f, 7)));
}

static void corrupt_and_foreign_groom_files_are_refused(void)
{
    pelt_mesh *m = square(8);
    pelt_fur *f = fur_for(m);
    paint_something(f);
    const char *path = out_path("corrupt.groom.ply");
    CHECK(pelt_fur_save_groom(f, path, NULL) == PELT_OK);
    size_t size = 0;
    unsigned char *good = slurp(path, &size);
    CHECK(good && size > 500);
    if (!good) return;
    unsigned char *bad = malloc(size + 16);
    size_t header = (size_t)((unsigned char *)strstr((char *)good, "end_header\n") - good) + 11;

    refused(f, good, size - 5, "truncated");
    refused(f, good, 3, "header ends");
    refused(f, "solid x\n", 8, "not a PLY");
    memcpy(bad, good, size);
    memcpy(bad + 4, "format ascii 1.0\n", 17); /* the format line, overwritten */
    refused(f, bad, size, "binary_little_endian");
    /* A plain PLY mesh, not a groom. */
    const char *plain = "ply\nformat binary_little_endian 1.0\nelement vertex 0\nend_header\n";
    refused(f, plain, strlen(plain), "not a pelt groom");
    /* A NaN length in vertex 3. */
    memcpy(bad, good, size);
    float nan = NAN;
    memcpy(bad + header + 3 * 32 + 12, &nan, 4);
    refused(f, bad, size, "not finite");
    /* Extra bytes at the end. */
    memcpy(bad, good, size);
    memset(bad + size, 0, 16);
    refused(f, bad, size + 16, "bytes after");
    /* A face index out of range. */
    memcpy(bad, good, size);
    uint32_t huge = 0xfffffff0u;
    memcpy(bad + size - 12, &huge, 4);
    refused(f, bad, size, "out of range");

    /* A groom saved for another mesh. */
    pelt_mesh *other = NULL;
    CHECK(pelt_mesh_sphere(1.0f, 16, 8, &other, NULL) == PELT_OK);
    pelt_fur *fo = fur_for(other);
    pelt_groom_value before = pelt_fur_get_groom(fo, 3);
    pelt_error err = {0};
    CHECK(pelt_fur_load_groom(fo, path, &err) == PELT_ERR_FORMAT);
    printf("  %s\n", err.message);
    CHECK(strstr(err.message, "does not match") != NULL);
    CHECK(strstr(err.message, path) != NULL);
    CHECK(same_value(before, pelt_fur_get_groom(fo, 3)));
    CHECK(pelt_fur_load_groom(fo, out_path("no-such.ply"), &err) == PELT_ERR_IO);
    pelt_fur_destroy(fo);
    pelt_mesh_destroy(other);
    free(bad);
    free(good);
    pelt_fur_destroy(f);
    pelt_mesh_destroy(m);
}

/* The colour and density formulas the shaders mirror. */
static void colour_and_density_references(void)
{
    const float none[4] = {0.3f, 0.9f, 0.1f, 0.0f}, white[4] = {1, 1, 1, 1};
    pelt_vec3 root = v3(0.5f, 0.25f, 0.1f), tip = v3(1.0f, 0.5f, 0.3f);
    pelt_vec3 r = pelt__groom_root_color(root, none), t = pelt__groom_tip_color(root, tip, none);
    CHECK(r.x == root.x && r.y == root.y && r.z == root.z); /* weight 0: the look's own */
    CHECK(t.x == tip.x && t.y == tip.y && t.z == tip.z);
    r = pelt__groom_root_color(root, white);
    t = pelt__groom_tip_color(root, tip, white);
    CHECK_NEAR(r.x, 1.0f, 0) ;
    CHECK_NEAR(t.y, 1.0f, 0); /* white stays white at the tip (clamped) */
    const float grey[4] = {0.2f, 0.2f, 0.2f, 1.0f};
    t = pelt__groom_tip_color(root, tip, grey);
    /* The groom's colour is sRGB: 0.2 is 0.0331 in linear light. */
    r = pelt__groom_root_color(root, grey);
    CHECK_NEAR(r.x, 0.033105, 1e-5);
    CHECK_NEAR(t.x, 2.0 * 0.033105, 2e-5); /* brightened by tip / root = 2 */
    CHECK_NEAR(t.z, 3.0 * 0.033105, 2e-5);
    CHECK(pelt__groom_keeps(0.99f, 1.0f));
    CHECK(!pelt__groom_keeps(0.0f, 0.0f));
    CHECK(pelt__groom_keeps(0.3f, 0.5f) && !pelt__groom_keeps(0.5f, 0.5f));
}

int main(void)
{
    RUN(comb_touches_exactly_the_ball);
    RUN(length_density_and_colour_strokes);
    RUN(bad_brushes_and_values_change_nothing);
    RUN(length_map_lands_on_the_vertices);
    RUN(groom_file_round_trip);
    RUN(groom_file_survives_another_vertex_order);
    RUN(corrupt_and_foreign_groom_files_are_refused);
    RUN(colour_and_density_references);
    return check_summary();
}
