/* Shadows from the light (docs/shadows.md) by what they are for: what an
 * occluder hides from the light goes darker while what the light sees
 * does not change; deeper fur is darker; a lower light casts a longer
 * shadow on the ground. And the receivers' GLSL against the C references. */
#include "support/gl_test.h"

#include "core/fur/shading.h"
#include "core/fur/shadow_map.h"

#include <math.h>

enum { W = 320, H = 240, PW = 64, PH = 48 };
#define NPX ((size_t)W * H)

static pelt_headless *gl;

/* ---- parity: shadow_map.glsl against core/fur/shadow_map.c ------------- */

/* Cell (x, y): slices S = 1 + y % 8, slice sums rising with j, a slice
 * position k across [-1, S + 1], a coverage a. */
static const char parity_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec2 c = floor(gl_FragCoord.xy);\n"
    "  float S = 1.0 + mod(c.y, 8.0);\n"
    "  float k = c.x / 63.0 * (S + 2.0) - 1.0;\n"
    "  float a = fract(c.x * 0.137 + c.y * 0.071);\n"
    "  vec4 s0 = vec4(0.3, 0.7, 0.8, 1.6) * (1.0 + 0.1 * c.y);\n"
    "  vec4 s1 = vec4(1.9, 2.0, 2.6, 3.1) * (1.0 + 0.1 * c.y);\n"
    "  vec4 w0, w1;\n"
    "  shadow_slice_weights(k, S, w0, w1);\n"
    "  int j = int(mod(c.x + c.y, 8.0));\n"
    "  float w = j < 4 ? w0[j] : w1[j - 4];\n"
    "  o = vec4(shadow_opacity(s0, s1, S, k), w, shadow_sigma(a), 0.0);\n"
    "}\n";

static void shadow_glsl_matches_c(void)
{
    static float out[PW * PH * 4];
    pelt_headless *fgl = gl_test_open(PW, PH, true);
    CHECK(fgl != NULL);
    if (!fgl) return;
    const char *fs[] = {pelt__shader_blocks, pelt__shader_shadow_map, parity_main, NULL};
    CHECK(gl_test_eval(fgl, fs, PW, PH, out));
    double worst = 0.0;
    for (int y = 0; y < PH; y++)
        for (int x = 0; x < PW; x++) {
            unsigned S = 1 + (unsigned)(y % 8);
            float k = (float)x / 63.0f * ((float)S + 2.0f) - 1.0f;
            float a = (float)x * 0.137f + (float)y * 0.071f;
            a -= floorf(a);
            const float base[8] = {0.3f, 0.7f, 0.8f, 1.6f, 1.9f, 2.0f, 2.6f, 3.1f};
            float sums[PELT_SHADOW_MAX_SLICES];
            for (int i = 0; i < 8; i++) sums[i] = base[i] * (1.0f + 0.1f * (float)y);
            unsigned j = (unsigned)((x + y) % 8);
            const float *g = out + 4 * (y * PW + x);
            worst = fmax(worst, fabs(g[0] - pelt__shadow_opacity(sums, S, k)));
            worst = fmax(worst, fabs(g[1] - pelt__shadow_slice_weight(k, j, S)));
            worst = fmax(worst, fabs(g[2] - pelt__shadow_sigma(a)));
        }
    printf("  worst |GLSL - C| = %.3g\n", worst);
    CHECK(worst < 2e-4);
    pelt_headless_destroy(fgl);
}

/* ---- rendering --------------------------------------------------------- */

/* Squares in y = height, x0..x1 by z0..z1, facing +y, n x n quads each. */
typedef struct squares {
    float positions[2 * 17 * 17 * 3];
    float uvs[2 * 17 * 17 * 2]; /* (x, z) / 2: the same fur wherever a square lies */
    uint32_t indices[2 * 16 * 16 * 6];
    size_t vertices, triangles;
} squares;

static void add_square(squares *s, float x0, float x1, float z0, float z1, float height)
{
    const unsigned n = 16;
    uint32_t base = (uint32_t)s->vertices;
    for (unsigned j = 0; j <= n; j++)
        for (unsigned i = 0; i <= n; i++) {
            float *p = s->positions + 3 * s->vertices++;
            p[0] = x0 + (x1 - x0) * (float)i / (float)n;
            p[1] = height;
            p[2] = z0 + (z1 - z0) * (float)j / (float)n;
            s->uvs[2 * (s->vertices - 1)] = p[0] * 0.5f;
            s->uvs[2 * (s->vertices - 1) + 1] = p[2] * 0.5f;
        }
    for (unsigned j = 0; j < n; j++)
        for (unsigned i = 0; i < n; i++) {
            uint32_t a = base + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            uint32_t *t = s->indices + 3 * s->triangles;
            /* Counter-clockwise seen from +y. */
            t[0] = a, t[1] = c, t[2] = b, t[3] = b, t[4] = c, t[5] = d;
            s->triangles += 2;
        }
}

typedef struct scene {
    pelt_fur *fur;
    pelt_renderer *renderer;
} scene;

static bool scene_make(const pelt_mesh *mesh, const pelt_shadow_desc *sd, const pelt_ground_desc *gd, bool lod,
                       scene *s)
{
    memset(s, 0, sizeof *s);
    const pelt_fur_desc d = {.look.texture_size = 128, .look.tiling = 3.0f, .length = 0.12f, .lod.mode = lod ? PELT_LOD_AUTO : PELT_LOD_OFF};
    pelt_error err = {0};
    if (pelt_fur_create(mesh, &d, &s->fur, &err) != PELT_OK ||
        pelt_renderer_create(mesh, s->fur, NULL, &s->renderer, &err) != PELT_OK ||
        pelt_renderer_set_shadows(s->renderer, sd, &err) != PELT_OK) {
        fprintf(stderr, "  %s\n", err.message);
        return false;
    }
    pelt_renderer_set_ground(s->renderer, gd);
    return true;
}

static void scene_free(scene *s)
{
    pelt_renderer_destroy(s->renderer);
    pelt_fur_destroy(s->fur);
}

static pelt_view view_of(const pelt_camera *cam, const float light[3])
{
    pelt_view v;
    memset(&v, 0, sizeof v);
    pelt_camera_to_view(cam, (float)W / H, &v);
    v.light = (pelt_light){{light[0], light[1], light[2]}, {1.2f, 1.2f, 1.2f}, 0.2f};
    v.width = W, v.height = H;
    return v;
}

static void draw(scene *s, const pelt_view *v, const pelt_draw_desc *dd, uint8_t *px)
{
    pelt_headless_bind(gl);
    glClearColor(gl_test_background[0], gl_test_background[1], gl_test_background[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    pelt_renderer_draw(s->renderer, v, dd);
    pelt_headless_read_rgba8(gl, px);
}

/* The pixel (column, row from the top) where world point p lands. */
static void project(const pelt_view *v, const float p[3], int *col, int *row)
{
    float q[4] = {0}, e[4] = {0};
    for (int i = 0; i < 4; i++)
        e[i] = v->view[i] * p[0] + v->view[4 + i] * p[1] + v->view[8 + i] * p[2] + v->view[12 + i];
    for (int i = 0; i < 4; i++)
        q[i] = v->proj[i] * e[0] + v->proj[4 + i] * e[1] + v->proj[8 + i] * e[2] + v->proj[12 + i] * e[3];
    *col = (int)((q[0] / q[3] * 0.5f + 0.5f) * W);
    *row = (int)((0.5f - q[1] / q[3] * 0.5f) * H);
}

static double luminance(const uint8_t *px, size_t i) { return gl_test_luma(px + 4 * i); }

/* The luminance in linear light of a pixel drawn without a tone curve. */
static double linear_luminance(const uint8_t *px, size_t i)
{
    return 0.2126 * pelt__srgb_decode(px[4 * i] / 255.0f) + 0.7152 * pelt__srgb_decode(px[4 * i + 1] / 255.0f) +
           0.0722 * pelt__srgb_decode(px[4 * i + 2] / 255.0f);
}

/* Mean luminance of the (2 r + 1)^2 pixels around the point p. */
static double window_mean(const pelt_view *v, const uint8_t *px, const float p[3], int r)
{
    int c, w;
    project(v, p, &c, &w);
    double sum = 0.0;
    int n = 0;
    for (int y = w - r; y <= w + r; y++)
        for (int x = c - r; x <= c + r; x++)
            if (x >= 0 && x < W && y >= 0 && y < H) sum += luminance(px, (size_t)(H - 1 - y) * W + (size_t)x), n++;
    return n ? sum / n : 0.0;
}

/* A furry square under a light at 45 degrees, seen from straight above.
 * A second square floats above and to the side of it, out of the
 * camera's view but between part of it and the light. With the occluder,
 * the part it hides from the light is darker than the same fur without
 * the occluder, by at least a factor 0.6; the part the light still sees
 * is unchanged within 3%. Level of detail off: the two meshes would get
 * different simplified levels, and so a different picture. */
static void an_occluder_darkens_what_it_hides_and_nothing_else(void)
{
    static squares with, without;
    memset(&with, 0, sizeof with);
    memset(&without, 0, sizeof without);
    add_square(&with, -1.0f, 1.0f, -1.0f, 1.0f, 0.0f);
    add_square(&with, 1.0f, 3.0f, -2.0f, 2.0f, 1.2f); /* its shadow: x from -0.2 on */
    add_square(&without, -1.0f, 1.0f, -1.0f, 1.0f, 0.0f);
    pelt_mesh *ma = NULL, *mb = NULL;
    pelt_mesh_data da = {.positions = with.positions, .uvs = with.uvs, .vertex_count = with.vertices, .indices = with.indices,
                         .triangle_count = with.triangles};
    pelt_mesh_data db = da;
    db.positions = without.positions, db.uvs = without.uvs, db.vertex_count = without.vertices, db.indices = without.indices;
    db.triangle_count = without.triangles;
    CHECK(pelt_mesh_create(&da, &ma, NULL) == PELT_OK);
    CHECK(pelt_mesh_create(&db, &mb, NULL) == PELT_OK);
    const pelt_shadow_desc sd = {.enabled = true};
    scene a, b;
    uint8_t *pa = malloc(NPX * 4), *pb = malloc(NPX * 4);
    if (ma && mb && pa && pb && scene_make(ma, &sd, NULL, false, &a) && scene_make(mb, &sd, NULL, false, &b)) {
        const pelt_camera cam = {0.0f, 89.0f, 3.5f, 30.0f, {0, 0, 0}};
        const float light[3] = {1.0f, 1.0f, 0.0f};
        pelt_view v = view_of(&cam, light);
        draw(&a, &v, NULL, pa);
        draw(&b, &v, NULL, pb);
        stbi_write_png(PELT_TEST_OUT "/shadow_occluder.png", W, H, 4, pa, W * 4);
        const float hidden[3] = {0.4f, 0.0f, 0.0f}, seen[3] = {-0.65f, 0.0f, 0.0f};
        double ha = window_mean(&v, pa, hidden, 12), hb = window_mean(&v, pb, hidden, 12);
        double sa = window_mean(&v, pa, seen, 8), sb = window_mean(&v, pb, seen, 8);
        printf("  hidden from the light: %.1f with the occluder, %.1f without (ratio %.2f)\n", ha, hb, ha / hb);
        printf("  in view of the light:  %.1f with the occluder, %.1f without (ratio %.3f)\n", sa, sb, sa / sb);
        CHECK(hb > 20.0 && ha < 0.6 * hb);
        CHECK(fabs(sa / sb - 1.0) < 0.03);
        pelt_render_stats st = pelt_renderer_get_stats(a.renderer);
        CHECK(st.shadow_draw_calls == 2);
    }
    scene_free(&a);
    scene_free(&b);
    free(pa);
    free(pb);
    pelt_mesh_destroy(ma);
    pelt_mesh_destroy(mb);
}

/* Each layer of a furry square drawn alone, with the light's shadows and
 * without them (gamma kept both ways): the fraction of light that reaches
 * a layer rises from the roots to the tips, by at least 10%. Measured in
 * linear light: drawn without the tone curve, the pixels decoded; a layer
 * with fewer than 1% of the pixels (the longest hairs' tips) is skipped. */
static void deeper_fur_is_darker(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_square(2.0f, 16, &m, NULL) == PELT_OK);
    const pelt_shadow_desc sd = {.enabled = true, .keep_gamma = true};
    scene s;
    uint8_t *on = malloc(NPX * 4), *off = malloc(NPX * 4);
    if (m && on && off && scene_make(m, &sd, NULL, true, &s)) {
        const pelt_camera cam = {20.0f, 60.0f, 3.0f, 40.0f, {0, 0, 0}};
        const float light[3] = {0.3f, 1.0f, 0.2f};
        pelt_view v = view_of(&cam, light);
        unsigned layers = pelt_fur_get_desc(s.fur).layers;
        double prev = 0.0, first = 0.0, last = 0.0;
        int falls = 0;
        unsigned measured = 0;
        for (unsigned i = 0; i < layers; i++) {
            pelt_draw_desc dd = {.no_skin = true, .no_fins = true, .first_layer = i, .layer_count = 1, .debug.flat_shells = true,
                                 .tone = PELT_TONE_NONE};
            draw(&s, &v, &dd, on);
            dd.debug.no_shadows = true;
            draw(&s, &v, &dd, off);
            /* Over the pixels of this layer's hair. */
            double lit = 0.0, all = 0.0;
            size_t covered = 0;
            for (size_t p = 0; p < NPX; p++)
                if (gl_test_coverage(off + 4 * p, 1)) {
                    lit += linear_luminance(on, p);
                    all += linear_luminance(off, p);
                    covered++;
                }
            /* The outermost layers hold only the longest hairs' tips: a
             * few faint pixels measure nothing. */
            if (covered < NPX / 100) {
                printf("  layer %2u: %zu pixels, too few to measure\n", i, covered);
                continue;
            }
            double ratio = lit / fmax(all, 1.0);
            printf("  layer %2u: %.3f of the light\n", i, ratio);
            measured++;
            if (prev > 0.0 && ratio < prev - 0.01) falls++;
            if (first == 0.0) first = ratio;
            last = ratio;
            prev = ratio;
        }
        CHECK(4 * measured >= 3 * layers); /* all but the longest tips measured */
        CHECK(falls == 0);
        CHECK(first < 0.9 * last);
        CHECK(last > 0.95);
        scene_free(&s);
    }
    free(on);
    free(off);
    pelt_mesh_destroy(m);
}

/* A furry sphere on the ground seen from above, the light at 70, 50 and
 * 35 degrees: the ground's shadowed area (pixels at least 20% darker
 * than without shadows) grows by at least 10% each time. */
static void a_lower_light_casts_a_longer_shadow(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_sphere(0.5f, 32, 16, &m, NULL) == PELT_OK);
    const pelt_shadow_desc sd = {.enabled = true};
    const pelt_ground_desc gd = {.enabled = true, .size = 10.0f}; /* its rim out of view */
    scene s;
    uint8_t *on = malloc(NPX * 4), *off = malloc(NPX * 4);
    if (m && on && off && scene_make(m, &sd, &gd, true, &s)) {
        const pelt_camera cam = {0.0f, 89.0f, 7.0f, 40.0f, {0, 0, 0}};
        const float elevations[3] = {70.0f, 50.0f, 35.0f};
        size_t prev = 0;
        for (int e = 0; e < 3; e++) {
            float a = elevations[e] * 3.14159265f / 180.0f;
            const float light[3] = {cosf(a), sinf(a), 0.0f};
            pelt_view v = view_of(&cam, light);
            draw(&s, &v, NULL, on);
            pelt_draw_desc dd = {.debug.no_shadows = true};
            draw(&s, &v, &dd, off);
            CHECK(pelt_renderer_get_stats(s.renderer).ground_draw_calls == 1);
            /* The ground's colour, where no shadow can fall (across the light). */
            int c, r;
            const float ref[3] = {0.0f, -0.5f, 1.4f};
            project(&v, ref, &c, &r);
            size_t at = (size_t)(H - 1 - r) * W + (size_t)c;
            size_t shadowed = 0, ground = 0;
            for (size_t p = 0; p < NPX; p++) {
                bool is_ground = true;
                for (int k = 0; k < 3; k++)
                    if (abs((int)off[4 * p + k] - (int)off[4 * at + k]) > 3) is_ground = false;
                if (!is_ground) continue;
                ground++;
                if (luminance(on, p) < 0.8 * luminance(off, p)) shadowed++;
            }
            printf("  light at %2.0f degrees: %zu of %zu ground pixels in shadow\n", (double)elevations[e], shadowed,
                   ground);
            if (e == 2) stbi_write_png(PELT_TEST_OUT "/shadow_ground.png", W, H, 4, on, W * 4);
            CHECK(ground > NPX / 4);
            CHECK(shadowed > 20 && shadowed > prev + prev / 10);
            prev = shadowed;
        }
        scene_free(&s);
    }
    free(on);
    free(off);
    pelt_mesh_destroy(m);
}

/* The light pass draws into its own framebuffers and puts back what the
 * caller had: framebuffer, viewport, scissor test, colour mask. Bad
 * settings are refused and leave the shadows as they were. */
static void the_light_pass_leaves_the_callers_state(void)
{
    pelt_mesh *m = NULL;
    CHECK(pelt_mesh_sphere(0.5f, 16, 8, &m, NULL) == PELT_OK);
    const pelt_shadow_desc sd = {.enabled = true, .map_size = 256, .slices = 8};
    scene s;
    if (m && scene_make(m, &sd, NULL, true, &s)) {
        pelt_headless_bind(gl);
        GLint fbo = 0, vp[4], after_fbo = -1, after_vp[4];
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
        glViewport(7, 5, W - 20, H - 30);
        glEnable(GL_SCISSOR_TEST);
        glScissor(0, 0, W, H);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
        glGetIntegerv(GL_VIEWPORT, vp);
        const pelt_camera cam = {30.0f, 20.0f, 3.0f, 40.0f, {0, 0, 0}};
        const float light[3] = {0.5f, 1.0f, 0.8f};
        pelt_view v = view_of(&cam, light);
        pelt_renderer_draw(s.renderer, &v, NULL);
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &after_fbo);
        glGetIntegerv(GL_VIEWPORT, after_vp);
        GLboolean mask[4];
        glGetBooleanv(GL_COLOR_WRITEMASK, mask);
        CHECK(after_fbo == fbo);
        CHECK(memcmp(vp, after_vp, sizeof vp) == 0);
        CHECK(glIsEnabled(GL_SCISSOR_TEST));
        CHECK(mask[0] && !mask[3]);
        CHECK(pelt_renderer_get_stats(s.renderer).shadow_draw_calls == 2);
        glDisable(GL_SCISSOR_TEST);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glViewport(0, 0, W, H);

        pelt_error err = {0};
        CHECK(pelt_renderer_set_shadows(s.renderer, &(pelt_shadow_desc){.enabled = true, .map_size = 8}, &err) ==
              PELT_ERR_INVALID_ARGUMENT);
        CHECK(strstr(err.message, "map size") != NULL);
        CHECK(pelt_renderer_set_shadows(s.renderer, &(pelt_shadow_desc){.enabled = true, .slices = 9}, &err) ==
              PELT_ERR_INVALID_ARGUMENT);
        pelt_renderer_draw(s.renderer, &v, NULL);
        CHECK(pelt_renderer_get_stats(s.renderer).shadow_draw_calls == 2); /* still on */
        CHECK(pelt_renderer_set_shadows(s.renderer, NULL, &err) == PELT_OK);
        pelt_renderer_draw(s.renderer, &v, NULL);
        CHECK(pelt_renderer_get_stats(s.renderer).shadow_draw_calls == 0);
        scene_free(&s);
    }
    pelt_mesh_destroy(m);
}

int main(void)
{
    RUN(shadow_glsl_matches_c);
    gl = gl_test_open(W, H, false);
    if (!gl) return CHECK_SKIP_CODE;
    RUN(an_occluder_darkens_what_it_hides_and_nothing_else);
    RUN(deeper_fur_is_darker);
    RUN(a_lower_light_casts_a_longer_shadow);
    RUN(the_light_pass_leaves_the_callers_state);
    pelt_headless_destroy(gl);
    return check_summary();
}
