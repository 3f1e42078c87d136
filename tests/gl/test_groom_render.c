/* Grooming rendered (Lengyel et al. 2001 §3): a length map of stripes
 * gives stripes of long and short fur, density 0 shows bare skin only,
 * vertex colours interpolate across a triangle, a comb stroke leans the
 * fur under the brush and nowhere else, and a saved groom renders the same
 * when loaded again. A furry 2x2 square, fur at rest (no dynamics). */
#include "support/gl_test.h"

#include "core/base/vec.h"

enum { W = 320, H = 240 };

static pelt_headless *gl;
static const char *groom_path;

static pelt_mesh *square(unsigned subdivisions)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_square(2.0f, subdivisions, &m, NULL) == PELT_OK);
    return m;
}

/* A strip 2 long in X and 0.3 deep in Z, normal +Y, `n` quads long: seen
 * from +Z, little fur hides behind other fur. */
static pelt_mesh *strip(unsigned n)
{
    size_t nv = 2 * ((size_t)n + 1);
    float *pos = calloc(nv * 3, sizeof(float)), *nrm = calloc(nv * 3, sizeof(float));
    float *uv = calloc(nv * 2, sizeof(float));
    uint32_t *idx = calloc((size_t)n * 6, sizeof(uint32_t));
    for (size_t i = 0; i <= n; i++)
        for (size_t j = 0; j < 2; j++) {
            size_t v = 2 * i + j;
            pos[3 * v] = -1.0f + 2.0f * (float)i / (float)n;
            pos[3 * v + 2] = j ? -0.15f : 0.15f;
            nrm[3 * v + 1] = 1.0f;
            uv[2 * v] = (float)i / (float)n;
            uv[2 * v + 1] = j ? 0.15f : 0.0f;
        }
    for (uint32_t i = 0; i < n; i++) {
        uint32_t a = 2 * i, b = a + 1, c = a + 2, d = a + 3;
        uint32_t *t = idx + 6 * (size_t)i;
        t[0] = a, t[1] = c, t[2] = b, t[3] = b, t[4] = c, t[5] = d;
    }
    pelt_mesh_data md = {pos, nrm, uv, nv, idx, (size_t)n * 2, NULL, NULL, NULL, NULL};
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_create(&md, &m, NULL) == PELT_OK);
    free(pos), free(nrm), free(uv), free(idx);
    return m;
}

static const pelt_fur_desc fur_desc = {.layers = 24, .length = 0.25f, .look.skin_color = {0.2f, 0.4f, 0.9f}};

/* From +Z, 30 degrees above the skin (shells seen edge-on vanish: that
 * is what fins are for), far away through a narrow lens (nearly
 * orthographic): world +X is screen right and a column is one X whatever
 * the depth. The strip's far edge (z = -0.15) is its highest skin row. */
static const pelt_camera side = {0.0f, 30.0f, 40.0f, 4.0f, {0.0f, 0.0f, 0.0f}};
/* Straight down (nearly: the orbit camera keeps pitch below 90). */
static const pelt_camera top = {0.0f, 89.0f, 3.0f, 40.0f, {0.0f, 0.0f, 0.0f}};

/* Screen column and row of a world point under camera `cam`. */
static void project(const pelt_camera *cam, float x, float y, float z, float *col, float *row)
{
    pelt_view v;
    pelt_camera_to_view(cam, (float)W / (float)H, &v);
    float vp[16];
    pelt__mat4_mul(vp, v.proj, v.view);
    pelt_vec3 p = v3(x, y, z);
    float cx = vp[0] * p.x + vp[4] * p.y + vp[8] * p.z + vp[12];
    float cy = vp[1] * p.x + vp[5] * p.y + vp[9] * p.z + vp[13];
    float cw = vp[3] * p.x + vp[7] * p.y + vp[11] * p.z + vp[15];
    *col = (cx / cw * 0.5f + 0.5f) * (float)W;
    *row = (1.0f - (cy / cw * 0.5f + 0.5f)) * (float)H;
}

static bool is_background(const uint8_t *p)
{
    for (int k = 0; k < 3; k++)
        if (abs((int)p[k] - (int)(gl_test_background[k] * 255.0f + 0.5f)) > 6) return false;
    return true;
}

/* Topmost row of fur in column x, or H when the column is empty. */
static int top_row(const uint8_t *px, int x)
{
    for (int y = 0; y < H; y++)
        if (!is_background(px + 4 * (y * W + x))) return y;
    return H;
}

/* ---- tweaks: groom the fur before it is drawn ------------------------------ */

typedef struct groom_job {
    const pelt_mesh *mesh;
    int what;
} groom_job;

enum { STRIPES, BALD, CORNER_RED, COMB, PAINT_AND_SAVE, LOAD };

/* Stripes of x 0.25 wide alternate long (2.0) and short (0.5) fur. */
static bool long_stripe(float x) { return ((int)floorf((x + 1.0f) / 0.25f)) % 2 == 0; }

static void groom(pelt_fur *f, void *user)
{
    const groom_job *job = user;
    const pelt_mesh_data md = pelt_mesh_get_data(job->mesh);
    const float centre[3] = {0.0f, 0.0f, 0.0f};
    switch (job->what) {
    case STRIPES:
    case BALD:
    case CORNER_RED:
        for (size_t i = 0; i < md.vertex_count; i++) {
            pelt_groom_value v = pelt_groom_value_default();
            float x = md.positions[3 * i], z = md.positions[3 * i + 2];
            if (job->what == STRIPES) v.length = long_stripe(x) ? 2.0f : 0.5f;
            if (job->what == BALD && fabsf(x) < 0.3f) v.density = 0.0f;
            if (job->what == CORNER_RED) {
                bool red = x < 0.0f && z < 0.0f;
                v.color[0] = red ? 1.0f : 0.0f;
                v.color[2] = red ? 0.0f : 1.0f;
                v.color[3] = 1.0f;
            }
            CHECK(pelt_fur_set_groom(f, i, 1, &v, NULL) == PELT_OK);
        }
        break;
    case COMB: {
        pelt_brush b = {.tool = PELT_BRUSH_COMB, .radius = 0.5f, .delta = {0.0f, 0.0f, -0.2f}};
        CHECK(pelt_fur_brush(f, centre, &b, NULL, NULL) == PELT_OK);
        break;
    }
    case PAINT_AND_SAVE: {
        const float a[3] = {0.4f, 0.0f, 0.3f}, b[3] = {-0.5f, 0.0f, -0.2f};
        pelt_brush comb = {.tool = PELT_BRUSH_COMB, .radius = 0.6f, .delta = {0.1f, 0.0f, -0.1f}};
        pelt_brush col = {.tool = PELT_BRUSH_COLOR, .radius = 0.7f, .color = {0.9f, 0.9f, 0.95f}};
        pelt_brush len = {.tool = PELT_BRUSH_LENGTH, .radius = 0.5f, .amount = 1.0f};
        pelt_brush den = {.tool = PELT_BRUSH_DENSITY, .radius = 0.3f, .amount = 0.0f};
        CHECK(pelt_fur_brush(f, a, &comb, NULL, NULL) == PELT_OK);
        CHECK(pelt_fur_brush(f, b, &col, NULL, NULL) == PELT_OK);
        CHECK(pelt_fur_brush(f, b, &len, NULL, NULL) == PELT_OK);
        CHECK(pelt_fur_brush(f, a, &den, NULL, NULL) == PELT_OK);
        CHECK(pelt_fur_save_groom(f, groom_path, NULL) == PELT_OK);
        break;
    }
    case LOAD: {
        pelt_error err = {0};
        CHECK(pelt_fur_load_groom(f, groom_path, &err) == PELT_OK);
        break;
    }
    }
}

static uint8_t *render(const pelt_mesh *m, const pelt_camera *cam, int what)
{
    groom_job job = {m, what};
    uint8_t *px = gl_test_render(gl, m, &fur_desc, cam, NULL, what >= 0 ? groom : NULL, &job);
    CHECK(px != NULL);
    return px;
}

static void save(const char *name, const uint8_t *px)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.png", PELT_TEST_OUT, name);
    stbi_write_png(path, W, H, 4, px, W * 4);
}

/* ---- the tests ---------------------------------------------------------------- */

/* Seen edge-on, the fur's height above the horizon follows the stripes:
 * over long stripes (2 x the length) it stands at least 2.5 times as high
 * as over short ones (0.5 x), where 4 is exact. */
static void length_map_stripes_give_long_and_short_fur(void)
{
    pelt_mesh *m = strip(128);
    uint8_t *px = render(m, &side, STRIPES);
    if (!px) return;
    save("groom_stripes", px);
    float col, horizon;
    project(&side, 0.0f, 0.0f, -0.15f, &col, &horizon);
    double sum[2] = {0, 0};
    int count[2] = {0, 0};
    /* Stripe middles only, away from the blended edges and the square's ends. */
    for (int x = 0; x < W; x++) {
        for (float wx = -0.875f; wx < 0.9f; wx += 0.25f) {
            float c0, c1, r;
            project(&side, wx - 0.04f, 0.0f, 0.0f, &c0, &r);
            project(&side, wx + 0.04f, 0.0f, 0.0f, &c1, &r);
            if (x < c0 || x > c1) continue;
            int top_y = top_row(px, x);
            bool lng = long_stripe(wx);
            sum[lng] += horizon - (float)top_y;
            count[lng]++;
        }
    }
    double shrt = count[0] ? sum[0] / count[0] : 0.0, lng = count[1] ? sum[1] / count[1] : 0.0;
    printf("  fur height above the skin: %.1f px over long stripes, %.1f px over short ones "
           "(ratio %.2f; columns %d / %d)\n", lng, shrt, shrt > 0 ? lng / shrt : 0.0, count[1], count[0]);
    CHECK(count[0] > 10 && count[1] > 10);
    CHECK(shrt > 2.0);
    CHECK(lng > 2.5 * shrt);
    free(px);
    pelt_mesh_destroy(m);
}

/* Seen from above, where density is 0 every pixel is the skin colour (a
 * blue chosen to tell it from hair: blue above red), while the same place
 * with the full density shows hair (red above blue) and the fur beside the
 * bald stripe keeps its hair. */
static void density_zero_shows_skin_only(void)
{
    pelt_mesh *m = square(48);
    uint8_t *bald = render(m, &top, BALD), *full = render(m, &top, -1);
    if (!bald || !full) return;
    save("groom_bald", bald);
    float c0, c1, r0, r1;
    project(&top, -0.2f, 0.0f, 0.6f, &c0, &r0);
    project(&top, 0.2f, 0.0f, -0.6f, &c1, &r1);
    size_t in = 0, skin = 0, hair_full = 0, beside = 0, hair_beside = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const uint8_t *b = bald + 4 * (y * W + x), *f = full + 4 * (y * W + x);
            bool inside = x > c0 && x < c1 && y > fminf(r0, r1) && y < fmaxf(r0, r1);
            if (inside) {
                in++;
                skin += b[2] > b[0];
                hair_full += f[0] > f[2];
            }
            float cl, rl;
            project(&top, -0.7f, 0.0f, 0.0f, &cl, &rl);
            if (fabsf((float)x - cl) < 8 && fabsf((float)y - rl) < 30) {
                beside++;
                hair_beside += b[0] > b[2];
            }
        }
    printf("  bald stripe: %zu of %zu pixels skin-coloured (full density: %zu hair); beside it "
           "%zu of %zu hair\n", skin, in, hair_full, hair_beside, beside);
    CHECK(in > 2000);
    CHECK(skin == in);
    CHECK(hair_full > in * 95 / 100);
    CHECK(hair_beside > beside * 95 / 100);
    free(bald);
    free(full);
    pelt_mesh_destroy(m);
}

/* Mean colour of a (2r+1)^2 window. */
static void window_mean(const uint8_t *px, int cx, int cy, int r, double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    int n = 0;
    for (int y = cy - r; y <= cy + r; y++)
        for (int x = cx - r; x <= cx + r; x++) {
            if (x < 0 || y < 0 || x >= W || y >= H) continue;
            for (int k = 0; k < 3; k++) out[k] += px[4 * (y * W + x) + k];
            n++;
        }
    for (int k = 0; k < 3; k++) out[k] /= n > 0 ? n : 1;
}

/* A 2x2 grid of quads, one vertex in four red, the rest blue: along the
 * edge from the red corner vertex (-1, -1) to its blue neighbour (0, -1)
 * the hair turns from red to blue steadily, half-way in the middle. */
static void vertex_colour_interpolates_across_a_triangle(void)
{
    pelt_mesh *m = square(2);
    uint8_t *px = render(m, &top, CORNER_RED);
    if (!px) return;
    save("groom_corner_red", px);
    double red[5];
    for (int i = 0; i < 5; i++) {
        float wx = -0.9f + 0.2f * (float)i, col, row;
        project(&top, wx, 0.0f, -0.9f, &col, &row);
        double c[3];
        window_mean(px, (int)col, (int)row, 6, c);
        red[i] = c[0] / (c[0] + c[2] + 1e-9);
    }
    printf("  red share along the edge: %.2f %.2f %.2f %.2f %.2f\n", red[0], red[1], red[2],
           red[3], red[4]);
    for (int i = 1; i < 5; i++) CHECK(red[i] < red[i - 1]);
    /* White highlights dilute the share; the middle lies between a quarter
     * and three quarters of the way from one end to the other. */
    double span = red[0] - red[4];
    CHECK(span > 0.4);
    CHECK(red[2] > red[4] + 0.25 * span && red[2] < red[0] - 0.25 * span);
    free(px);
    pelt_mesh_destroy(m);
}

/* A comb stroke of radius 0.5 at the centre pushing the tips 0.2 away
 * from the viewer (-Z) changes pixels only over |x| < 0.5, and there the
 * fur leans along the stroke: seen from above the near side, fur leaning
 * away stands higher on the screen (at the centre, 1.27 times as high as
 * upright fur: sheared tips at (0, L, -0.8 L) seen from 30 degrees). */
static void comb_stroke_leans_only_under_the_brush(void)
{
    pelt_mesh *m = strip(128);
    uint8_t *plain = render(m, &side, -1), *combed = render(m, &side, COMB);
    if (!plain || !combed) return;
    save("groom_comb_side", combed);
    float lo, hi, c0, c1, r, horizon;
    project(&side, -0.5f, 0.0f, 0.0f, &lo, &r);
    project(&side, 0.5f, 0.0f, 0.0f, &hi, &r);
    project(&side, -0.15f, 0.0f, -0.15f, &c0, &horizon);
    project(&side, 0.15f, 0.0f, -0.15f, &c1, &r);
    size_t outside = 0, changed_outside = 0, changed_inside = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const uint8_t *a = plain + 4 * (y * W + x), *b = combed + 4 * (y * W + x);
            bool differ = memcmp(a, b, 3) != 0;
            if (x >= lo - 2.0f && x <= hi + 2.0f) changed_inside += differ;
            else outside++, changed_outside += differ;
        }
    double up_plain = 0, up_combed = 0;
    int n = 0;
    for (int x = (int)ceilf(c0); x <= (int)c1; x++, n++) {
        up_plain += horizon - (float)top_row(plain, x);
        up_combed += horizon - (float)top_row(combed, x);
    }
    up_plain /= n > 0 ? n : 1;
    up_combed /= n > 0 ? n : 1;
    printf("  changed pixels: %zu over the brush, %zu of %zu elsewhere; fur height at the centre "
           "%.1f -> %.1f px (x%.2f)\n", changed_inside, changed_outside, outside, up_plain, up_combed,
           up_plain > 0 ? up_combed / up_plain : 0.0);
    CHECK(changed_inside > 500);
    CHECK(changed_outside == 0);
    CHECK(n > 10);
    CHECK(up_combed > 1.15 * up_plain);
    free(plain);
    free(combed);
    pelt_mesh_destroy(m);
}

/* Strokes, saved; a fresh fur that loads the file renders the same
 * picture, byte for byte. */
static void saved_groom_renders_the_same(void)
{
    pelt_mesh *m = square(48);
    const pelt_camera cam = {25.0f, 35.0f, 3.4f, 40.0f, {0.0f, 0.0f, 0.0f}};
    uint8_t *painted = render(m, &cam, PAINT_AND_SAVE), *loaded = render(m, &cam, LOAD);
    uint8_t *plain = render(m, &cam, -1);
    if (!painted || !loaded || !plain) return;
    save("groom_painted", painted);
    size_t n = (size_t)W * H, differ = 0, groomed = 0;
    for (size_t i = 0; i < n; i++) {
        differ += memcmp(painted + 4 * i, loaded + 4 * i, 3) != 0;
        groomed += memcmp(painted + 4 * i, plain + 4 * i, 3) != 0;
    }
    printf("  %zu pixels groomed, %zu differ after the round trip\n", groomed, differ);
    CHECK(groomed > n / 20);
    CHECK(differ == 0);
    free(painted);
    free(loaded);
    free(plain);
    pelt_mesh_destroy(m);
}

int main(void)
{
    gl = gl_test_open(W, H, false);
    if (!gl) return check_skip("no OpenGL context");
    static char path[1024];
    snprintf(path, sizeof path, "%s/groom_render.groom.ply", PELT_TEST_OUT);
    groom_path = path;
    RUN(length_map_stripes_give_long_and_short_fur);
    RUN(density_zero_shows_skin_only);
    RUN(vertex_colour_interpolates_across_a_triangle);
    RUN(comb_stroke_leans_only_under_the_brush);
    RUN(saved_groom_renders_the_same);
    pelt_headless_destroy(gl);
    return check_summary();
}
