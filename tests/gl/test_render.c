/* Images rendered on Mesa llvmpipe headless: golden references under a
 * tolerance, and properties that need no reference. */
#include "support/gl_test.h"

enum { W = 160, H = 120 };

static pelt_headless *gl;
static pelt_mesh *torus, *square;
static const pelt_camera torus_cam = {30.0f, 25.0f, 4.2f, 40.0f, {0, 0, 0}};
static const pelt_camera square_cam = {20.0f, 40.0f, 3.2f, 40.0f, {0, 0, 0}};

static void golden_torus_default_fur(void)
{
    pelt_fur_desc d = {0};
    uint8_t *px = gl_test_render(gl, torus, &d, &torus_cam, NULL, NULL, NULL);
    CHECK(px != NULL);
    if (px) gl_test_golden("torus", px, W, H, 4.0, 0.03);
    free(px);
}

static void golden_square_default_fur(void)
{
    pelt_fur_desc d = {0};
    uint8_t *px = gl_test_render(gl, square, &d, &square_cam, NULL, NULL, NULL);
    CHECK(px != NULL);
    if (px) gl_test_golden("square", px, W, H, 4.0, 0.03);
    free(px);
}

/* Fur reaches beyond the bare mesh's silhouette: pixels covered with
 * shells that the skin alone leaves as background. */
static void fur_covers_beyond_bare_silhouette(void)
{
    pelt_fur_desc d = {0};
    pelt_draw_desc bare = {.no_shells = true};
    uint8_t *skin = gl_test_render(gl, torus, &d, &torus_cam, &bare, NULL, NULL);
    uint8_t *fur = gl_test_render(gl, torus, &d, &torus_cam, NULL, NULL, NULL);
    CHECK(skin && fur);
    if (skin && fur) {
        size_t n = (size_t)W * H, outside = 0;
        for (size_t i = 0; i < n; i++)
            if (gl_test_coverage(skin + 4 * i, 1) == 0 && gl_test_coverage(fur + 4 * i, 1) == 1)
                outside++;
        size_t bare_cov = gl_test_coverage(skin, n);
        printf("  bare coverage %zu px, fur adds %zu px outside it\n", bare_cov, outside);
        CHECK(outside > bare_cov / 50);
    }
    free(skin);
    free(fur);
}

static void longer_fur_covers_more(void)
{
    pelt_fur_desc shorter = {.length = 0.06f}, longer = {.length = 0.18f};
    uint8_t *a = gl_test_render(gl, torus, &shorter, &torus_cam, NULL, NULL, NULL);
    uint8_t *b = gl_test_render(gl, torus, &longer, &torus_cam, NULL, NULL, NULL);
    CHECK(a && b);
    if (a && b) {
        size_t ca = gl_test_coverage(a, (size_t)W * H), cb = gl_test_coverage(b, (size_t)W * H);
        printf("  coverage: length 0.06 -> %zu px, length 0.18 -> %zu px\n", ca, cb);
        CHECK(cb > ca + ca / 50);
    }
    free(a);
    free(b);
}

/* All shells go out in one instanced draw, whatever the layer count; the
 * primitives GL generated prove every layer was drawn by it. */
static void shells_are_one_instanced_draw(void)
{
    const unsigned layer_counts[] = {1, 16, 64};
    for (size_t k = 0; k < 3; k++) {
        pelt_fur_desc d = {.layers = layer_counts[k]};
        pelt_fur *fur = NULL;
        pelt_renderer *r = NULL;
        pelt_draw_desc shells_only = {.no_skin = true};
        CHECK(pelt_fur_create(torus, &d, &fur, NULL) == PELT_OK);
        CHECK(pelt_renderer_create(torus, fur, NULL, &r, NULL) == PELT_OK);
        if (!r) {
            pelt_fur_destroy(fur);
            continue;
        }
        pelt_view v;
        memset(&v, 0, sizeof v);
        pelt_camera_to_view(&torus_cam, (float)W / H, &v);
        GLuint q;
        glGenQueries(1, &q);
        glBeginQuery(GL_PRIMITIVES_GENERATED, q);
        pelt_renderer_draw(r, &v, &shells_only);
        glEndQuery(GL_PRIMITIVES_GENERATED);
        GLuint prims = 0;
        glGetQueryObjectuiv(q, GL_QUERY_RESULT, &prims);
        glDeleteQueries(1, &q);
        pelt_render_stats st = pelt_renderer_get_stats(r);
        CHECK(st.shell_draw_calls == 1);
        CHECK(st.skin_draw_calls == 0);
        CHECK(st.shell_instances == layer_counts[k]);
        CHECK(st.triangles == (size_t)9360 * layer_counts[k]);
        CHECK_NEAR(prims, 9360.0 * layer_counts[k], 0.0);
        pelt_renderer_destroy(r);
        pelt_fur_destroy(fur);
    }
}

static void wet_left_half(pelt_fur *fur, void *user)
{
    (void)user;
    /* Rain-sized droplets over u < 0.5 only: each makes a clump (Silva
     * §3.1), overlapping ones merge or overwrite as Alg. 1 says. */
    pelt_rain r = {0.0f, 0.03f, 0.05f, 1.0f, 1.0f, 7};
    pelt_fur_add_random_droplets(fur, &r, 300);
    /* Dry the right half again with a hair dryer: negative droplets. */
    for (float v = 0.0f; v <= 1.0f; v += 0.02f)
        for (float u = 0.52f; u <= 1.0f; u += 0.02f) {
            pelt_droplet d = {{u, v}, 0.03f, -1.0f};
            pelt_fur_add_droplet(fur, &d, NULL);
        }
    for (float v = 0.0f; v <= 1.0f; v += 0.02f) {
        pelt_droplet d = {{0.5f + 0.03f, v}, 0.035f, -1.0f};
        pelt_fur_add_droplet(fur, &d, NULL);
    }
}

static double luma(const uint8_t *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Luminance below which `frac` of the fur pixels of columns [x0, x1) lie. */
static double luma_percentile(const uint8_t *px, int x0, int x1, double frac)
{
    static double v[W * H];
    size_t n = 0;
    for (int y = 0; y < H; y++)
        for (int x = x0; x < x1; x++) {
            const uint8_t *p = px + 4 * ((size_t)y * W + (size_t)x);
            if (gl_test_coverage(p, 1)) v[n++] = luma(p);
        }
    if (n == 0) return 0.0;
    qsort(v, n, sizeof v[0], cmp_double);
    return v[(size_t)(frac * (double)(n - 1))];
}

/* Fraction of the fur pixels of columns [x0, x1) darker than `level`. */
static double dark_fraction(const uint8_t *px, int x0, int x1, double level)
{
    size_t dark = 0, n = 0;
    for (int y = 0; y < H; y++)
        for (int x = x0; x < x1; x++) {
            const uint8_t *p = px + 4 * ((size_t)y * W + (size_t)x);
            if (!gl_test_coverage(p, 1)) continue;
            n++;
            if (luma(p) < level) dark++;
        }
    return n ? (double)dark / (double)n : 0.0;
}

static double mean_diff_in(const uint8_t *a, const uint8_t *b, int x0, int x1)
{
    double s = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = x0; x < x1; x++)
            for (int k = 0; k < 3; k++) {
                size_t i = 4 * ((size_t)y * W + (size_t)x) + (size_t)k;
                s += fabs((double)a[i] - (double)b[i]);
            }
    return s / (3.0 * (double)(x1 - x0) * H);
}

/* Clumps open gaps (Silva Fig. 8, 13): seen at an angle, dry fur hides
 * the skin; wet fur gathered into clumps shows skin and shadowed roots
 * between them. "Skin-coloured" = darker than the darkest tenth of the
 * dry fur in the same place; wet darkening is off so only the clump
 * geometry counts. The dry half of the square must render as before. */
static void wet_clumps_show_skin_and_leave_dry_fur_alone(void)
{
    /* Looking along -Z at the square, u along x. */
    const pelt_camera cam = {0.0f, 35.0f, 2.6f, 45.0f, {0, 0, 0}};
    pelt_fur_desc d = {.wet.darken = 1e-6f};
    uint8_t *dry = gl_test_render(gl, square, &d, &cam, NULL, NULL, NULL);
    uint8_t *wet = gl_test_render(gl, square, &d, &cam, NULL, wet_left_half, NULL);
    CHECK(dry && wet);
    if (dry && wet) {
        double left = mean_diff_in(dry, wet, 0, W / 2), right = mean_diff_in(dry, wet, W / 2, W);
        /* The wet half is the one that changed; look away from the middle. */
        int wet_is_left = left > right;
        int wx0 = wet_is_left ? W / 8 : W / 2 + W / 8, wx1 = wx0 + W / 4;
        int dx0 = wet_is_left ? W / 2 + W / 8 : W / 8, dx1 = dx0 + W / 4;
        double level = luma_percentile(dry, wx0, wx1, 0.10);
        double dark_dry = dark_fraction(dry, wx0, wx1, level);
        double dark_wet = dark_fraction(wet, wx0, wx1, level);
        double dry_half = mean_diff_in(dry, wet, dx0, dx1);
        printf("  halves changed by %.2f (left) / %.2f (right); skin-coloured fraction of the "
               "wet half: dry %.3f, wet %.3f; dry half changed by %.3f\n",
               left, right, dark_dry, dark_wet, dry_half);
        CHECK(dark_wet > 2.0 * dark_dry + 0.05);
        CHECK(dry_half < 0.5);
    }
    free(dry);
    free(wet);
}

static void wet_then_dry(pelt_fur *fur, void *user)
{
    (void)user;
    wet_left_half(fur, NULL);
    /* Dry at 0.5 per second for 3 s with no forces (tips stay at rest). */
    pelt_forces none = pelt_forces_default();
    none.gravity[1] = 0.0f;
    pelt_fur_set_dry_rate(fur, 0.5f);
    for (int i = 0; i < 180; i++) pelt_fur_step(fur, 1.0f / 60.0f, &none);
}

/* Dried to zero wetness, the fur renders as if it had never been wet:
 * clumps open and curls come back (Silva §1). */
static void dried_fur_matches_dry_render(void)
{
    const pelt_camera cam = {0.0f, 35.0f, 2.6f, 45.0f, {0, 0, 0}};
    pelt_fur_desc d = {.look.curl_frequency = 12.0f, .look.curl_radius = 0.02f};
    uint8_t *dry = gl_test_render(gl, square, &d, &cam, NULL, NULL, NULL);
    uint8_t *wet = gl_test_render(gl, square, &d, &cam, NULL, wet_left_half, NULL);
    uint8_t *dried = gl_test_render(gl, square, &d, &cam, NULL, wet_then_dry, NULL);
    CHECK(dry && wet && dried);
    if (dry && wet && dried) {
        double was = mean_diff_in(dry, wet, 0, W), now = mean_diff_in(dry, dried, 0, W);
        printf("  mean difference from the dry render: wet %.3f, dried %.3f\n", was, now);
        CHECK(was > 2.0);
        CHECK(now < 0.05);
    }
    free(dry);
    free(wet);
    free(dried);
}

static void one_big_clump(pelt_fur *fur, void *user)
{
    (void)user;
    /* One clump over the whole square. */
    pelt_droplet d = {{0.5f, 0.5f}, 0.75f, 1.0f};
    pelt_fur_add_droplet(fur, &d, NULL);
}

/* Distance from the image centre within which 90% of the covered pixels
 * lie. */
static double covered_radius90(const uint8_t *px)
{
    static double r[W * H];
    size_t n = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            if (gl_test_coverage(px + 4 * ((size_t)y * W + (size_t)x), 1))
                r[n++] = hypot(x + 0.5 - W / 2.0, y + 0.5 - H / 2.0);
    if (n == 0) return 0.0;
    qsort(r, n, sizeof r[0], cmp_double);
    return r[(size_t)(0.9 * (double)(n - 1))];
}

/* At full wetness a clump narrows from root to tip (Silva Fig. 9, 13):
 * seen from above one layer at a time, the fur of one clump covering the
 * whole square gathers into an ever smaller disc around its centre, while
 * dry fur covers the square at every height. */
static void clumps_grow_thinner_toward_the_tips(void)
{
    const pelt_camera top = {0.0f, 89.0f, 2.4f, 50.0f, {0, 0, 0}};
    pelt_fur_desc d = {.wet.clump_tightness = 1.0f, .wet.darken = 1e-6f};
    const unsigned layers[] = {1, 4, 7, 10};
    double dry_r[4], wet_r[4];
    for (int k = 0; k < 4; k++) {
        pelt_draw_desc one = {.no_skin = true, .first_layer = layers[k], .layer_count = 1};
        uint8_t *dry = gl_test_render(gl, square, &d, &top, &one, NULL, NULL);
        uint8_t *wet = gl_test_render(gl, square, &d, &top, &one, one_big_clump, NULL);
        CHECK(dry && wet);
        dry_r[k] = dry ? covered_radius90(dry) : 0.0;
        wet_r[k] = wet ? covered_radius90(wet) : 0.0;
        printf("  layer %2u of 16: 90%% of the fur within %5.1f px dry, %5.1f px clumped\n",
               layers[k], dry_r[k], wet_r[k]);
        free(dry);
        free(wet);
    }
    for (int k = 1; k < 4; k++) CHECK(wet_r[k] < wet_r[k - 1]);
    CHECK(wet_r[3] < 0.6 * wet_r[0]);
    CHECK(dry_r[3] > 0.9 * dry_r[0]);
}

int main(void)
{
    gl = gl_test_open(W, H, false);
    if (!gl) return check_skip("no OpenGL context");
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 78, 60, &torus, NULL) == PELT_OK);
    CHECK(pelt_mesh_square(2.0f, 16, &square, NULL) == PELT_OK);
    if (torus && square) {
        RUN(golden_torus_default_fur);
        RUN(golden_square_default_fur);
        RUN(fur_covers_beyond_bare_silhouette);
        RUN(longer_fur_covers_more);
        RUN(shells_are_one_instanced_draw);
        RUN(wet_clumps_show_skin_and_leave_dry_fur_alone);
        RUN(dried_fur_matches_dry_render);
        RUN(clumps_grow_thinner_toward_the_tips);
    }
    pelt_mesh_destroy(torus);
    pelt_mesh_destroy(square);
    pelt_headless_destroy(gl);
    return check_summary();
}
