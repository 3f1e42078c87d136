/* Images rendered on Mesa llvmpipe headless: golden references under a
 * tolerance, and properties that need no reference. */
#include "gl_test.h"

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
    pelt_renderer_desc bare = {.no_shells = true};
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
        pelt_renderer_desc rd = {.no_skin = true};
        CHECK(pelt_fur_create(torus, &d, &fur, NULL) == PELT_OK);
        CHECK(pelt_renderer_create(torus, fur, &rd, &r, NULL) == PELT_OK);
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
        pelt_renderer_draw(r, &v);
        glEndQuery(GL_PRIMITIVES_GENERATED);
        GLuint prims = 0;
        glGetQueryObjectuiv(q, GL_QUERY_RESULT, &prims);
        glDeleteQueries(1, &q);
        CHECK(pelt_renderer_shell_draw_calls(r) == 1);
        CHECK_NEAR(prims, 9360.0 * layer_counts[k], 0.0);
        pelt_renderer_destroy(r);
        pelt_fur_destroy(fur);
    }
}

int main(void)
{
    pelt_error err = {0};
    pelt_headless_desc hd = {W, H, 0, false};
    if (pelt_headless_create(&hd, &gl, &err) != PELT_OK) {
        fprintf(stderr, "no OpenGL: %s\n", err.message);
        return 1;
    }
    printf("%s\n", pelt_headless_renderer_name(gl));
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 78, 60, &torus, NULL) == PELT_OK);
    CHECK(pelt_mesh_square(2.0f, 16, &square, NULL) == PELT_OK);
    if (torus && square) {
        RUN(golden_torus_default_fur);
        RUN(golden_square_default_fur);
        RUN(fur_covers_beyond_bare_silhouette);
        RUN(longer_fur_covers_more);
        RUN(shells_are_one_instanced_draw);
    }
    pelt_mesh_destroy(torus);
    pelt_mesh_destroy(square);
    pelt_headless_destroy(gl);
    return check_summary();
}
