/* Helpers for tests that need OpenGL: a headless context, rendering a
 * furry mesh into pixels, image comparison and GLSL evaluation into a
 * float target. Header-only (static) so each test stays one file. */
#ifndef PELT_GL_TEST_H
#define PELT_GL_TEST_H

#include "pelt/pelt.h"
#include "gl/programs.h"
#include "support/check.h"

#include <epoxy/gl.h>
#include <stb_image.h>
#include <stb_image_write.h>
#include <stdlib.h>
#include <string.h>

static const float gl_test_background[3] = {0.10f, 0.11f, 0.13f};

/* A headless context of w x h (a float target for parity tests), or NULL
 * with the reason printed; prints the renderer's name. */
static inline pelt_headless *gl_test_open(unsigned w, unsigned h, bool float_target)
{
    pelt_error err = {0};
    pelt_headless *gl = NULL;
    pelt_headless_desc hd = {w, h, 0, float_target};
    if (pelt_headless_create(&hd, &gl, &err) != PELT_OK) {
        fprintf(stderr, "no OpenGL: %s\n", err.message);
        return NULL;
    }
    printf("%s\n", pelt_headless_renderer_name(gl));
    return gl;
}

/* Renders `mesh` with fur `d` at w x h; returns malloc'd RGBA8 (top row
 * first) or NULL (and a printed reason). `tweak` may change the fur; dd
 * picks passes and layers (NULL: everything). The view has no size, so
 * the finest levels of detail draw (gl_test_render_sized gives it the
 * viewport's: the levels the view picks). */
static inline uint8_t *gl_test_render_sized(pelt_headless *gl, const pelt_mesh *mesh, const pelt_fur_desc *d,
                                            const pelt_camera *cam, const pelt_draw_desc *dd,
                                            void (*tweak)(pelt_fur *, void *), void *user, bool sized)
{
    pelt_error err = {0};
    pelt_fur *fur = NULL;
    pelt_renderer *r = NULL;
    if (pelt_fur_create(mesh, d, &fur, &err) != PELT_OK) {
        fprintf(stderr, "  fur: %s\n", err.message);
        return NULL;
    }
    if (tweak) tweak(fur, user);
    if (pelt_renderer_create(mesh, fur, NULL, &r, &err) != PELT_OK) {
        fprintf(stderr, "  renderer: %s\n", err.message);
        pelt_fur_destroy(fur);
        return NULL;
    }
    GLint vp[4];
    pelt_headless_bind(gl);
    glGetIntegerv(GL_VIEWPORT, vp);
    pelt_view v;
    memset(&v, 0, sizeof v);
    pelt_camera_to_view(cam, (float)vp[2] / (float)vp[3], &v);
    if (sized) v.width = (unsigned)vp[2], v.height = (unsigned)vp[3];
    v.light = (pelt_light){{0.5f, 1.0f, 0.8f}, {1.5f, 1.45f, 1.4f}, 0.25f};
    glClearColor(gl_test_background[0], gl_test_background[1], gl_test_background[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    pelt_renderer_draw(r, &v, dd);
    uint8_t *px = malloc((size_t)vp[2] * (size_t)vp[3] * 4);
    if (px) pelt_headless_read_rgba8(gl, px);
    pelt_renderer_destroy(r);
    pelt_fur_destroy(fur);
    return px;
}

static inline uint8_t *gl_test_render(pelt_headless *gl, const pelt_mesh *mesh, const pelt_fur_desc *d,
                                      const pelt_camera *cam, const pelt_draw_desc *dd,
                                      void (*tweak)(pelt_fur *, void *), void *user)
{
    return gl_test_render_sized(gl, mesh, d, cam, dd, tweak, user, false);
}

/* An RGBA8 pixel's largest channel difference from the background, 0..255. */
/* The meshes most GL tests draw: the Table 1 torus (9,360 triangles) and
 * a 2 x 2 square of 16 x 16 quads. */
static inline bool gl_test_meshes(pelt_mesh **torus, pelt_mesh **square)
{
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 78, 60, torus, NULL) == PELT_OK);
    CHECK(pelt_mesh_square(2.0f, 16, square, NULL) == PELT_OK);
    return *torus && *square;
}

/* Draws one frame and counts the primitives it generated (a
 * GL_PRIMITIVES_GENERATED query around pelt_renderer_draw). */
static inline unsigned gl_test_draw_primitives(pelt_renderer *r, const pelt_view *v, const pelt_draw_desc *d)
{
    GLuint q, prims = 0;
    glGenQueries(1, &q);
    glBeginQuery(GL_PRIMITIVES_GENERATED, q);
    pelt_renderer_draw(r, v, d);
    glEndQuery(GL_PRIMITIVES_GENERATED);
    glGetQueryObjectuiv(q, GL_QUERY_RESULT, &prims);
    glDeleteQueries(1, &q);
    return prims;
}

static inline int gl_test_off_background(const uint8_t *px)
{
    int d = 0;
    for (int k = 0; k < 3; k++) {
        int e = abs((int)px[k] - (int)(gl_test_background[k] * 255.0f + 0.5f));
        if (e > d) d = e;
    }
    return d;
}

/* A pixel's luminance (BT.709 weights on its encoded RGBA8 values). */
static inline double gl_test_luma(const uint8_t *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

/* Pixels that differ from the background by more than a small margin. */
static inline size_t gl_test_coverage(const uint8_t *px, size_t n)
{
    size_t c = 0;
    for (size_t i = 0; i < n; i++) c += gl_test_off_background(px + 4 * i) > 6;
    return c;
}

/* Mean absolute channel error (0..255, RGB) of two RGBA8 images of n
 * pixels, and the fraction of pixels with a channel off by more than 32:
 * the measures of the golden tolerance. */
static inline void gl_test_compare(const uint8_t *a, const uint8_t *b, size_t n, double *mean, double *frac)
{
    double sum = 0.0;
    size_t off = 0;
    for (size_t i = 0; i < n; i++) {
        int worst = 0;
        for (int k = 0; k < 3; k++) {
            int e = abs((int)a[4 * i + k] - (int)b[4 * i + k]);
            sum += e;
            if (e > worst) worst = e;
        }
        if (worst > 32) off++;
    }
    *mean = sum / (3.0 * (double)n);
    *frac = (double)off / (double)n;
}

/* Compares with a reference PNG (made on Mesa llvmpipe) under a tolerance:
 * mean absolute channel error <= max_mean (0..255) and the fraction of
 * pixels with a channel off by more than 32 <= max_frac. With
 * PELT_UPDATE_GOLDEN=1 in the environment the reference is rewritten. */
static inline void gl_test_golden(const char *name, const uint8_t *px, int w, int h, double max_mean,
                           double max_frac)
{
    char path[1024], seen[1024];
    snprintf(path, sizeof path, "%s/golden/%s.png", PELT_TEST_DATA, name);
    snprintf(seen, sizeof seen, "%s/%s.seen.png", PELT_TEST_OUT, name);
    stbi_write_png(seen, w, h, 4, px, w * 4);
    if (getenv("PELT_UPDATE_GOLDEN")) {
        stbi_write_png(path, w, h, 4, px, w * 4);
        printf("  updated %s\n", path);
        return;
    }
    int rw, rh, rc;
    uint8_t *ref = stbi_load(path, &rw, &rh, &rc, 4);
    CHECK(ref != NULL);
    if (!ref) {
        fprintf(stderr, "  missing reference %s (seen image: %s)\n", path, seen);
        return;
    }
    CHECK(rw == w && rh == h);
    if (rw == w && rh == h) {
        double mean, frac;
        gl_test_compare(px, ref, (size_t)w * (size_t)h, &mean, &frac);
        printf("  %s: mean error %.3f (max %.3f), pixels off %.4f (max %.4f)\n", name, mean,
               max_mean, frac, max_frac);
        CHECK(mean <= max_mean);
        CHECK(frac <= max_frac);
        if (mean > max_mean || frac > max_frac)
            fprintf(stderr, "  compare %s with %s\n", seen, path);
    }
    stbi_image_free(ref);
}

static const char parity_vs[] =
    "void main() {\n"
    "  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));\n"
    "  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);\n"
    "}\n";

/* Draws one full-screen triangle with the fragment parts into the current
 * float framebuffer and reads it back (bottom row first). */
static inline bool gl_test_eval(pelt_headless *gl, const char *const *fs_parts, unsigned w, unsigned h,
                         float *out)
{
    const char *vs[] = {parity_vs, NULL};
    GLuint prog;
    pelt_error err = {0};
    if (pelt__program_build("parity", vs, fs_parts, &prog, &err) != PELT_OK) {
        fprintf(stderr, "  %s\n", err.message);
        return false;
    }
    GLuint vao;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    pelt_headless_bind(gl);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(prog);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    pelt_headless_read_rgba32f(gl, out);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(prog);
    (void)w;
    (void)h;
    return true;
}

#endif
