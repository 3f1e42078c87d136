/* Shader parity: each GLSL formula evaluated into an RGBA32F target over a
 * grid of inputs, against its C reference in core/. Inputs are a function
 * of the pixel, computed the same way on both sides. */
#include "support/gl_test.h"

#include "core/wet/clump.h"
#include "core/fur/fins.h"
#include "core/fur/fur_shape.h"
#include "core/wet/mask.h"
#include "core/fur/lod.h"
#include "core/fur/shading.h"
#include "pelt/render.h"

enum { W = 64, H = 48 };

static pelt_headless *gl;
static float out[W * H * 4];

/* Shared input generator: cell (x, y) -> a few values in known ranges. */
static const char inputs_glsl[] =
    "vec3 unit_dir(float a, float b) {\n"
    "  return vec3(cos(a) * sin(b), cos(b), sin(a) * sin(b));\n"
    "}\n"
    "void cell_inputs(vec2 c, out vec3 n, out vec3 t, out vec3 tip, out float h, out float s) {\n"
    "  n = unit_dir(c.x * 0.37, 0.2 + c.y * 0.05);\n"
    "  t = normalize(cross(n, vec3(0.3, 0.1, 0.95)));\n"
    "  tip = 0.8 * unit_dir(c.x * 0.11 + 1.0, 0.1 + c.y * 0.03);\n"
    "  h = fract(c.x * 0.131 + c.y * 0.071);\n"
    "  s = fract(c.x * 0.017 + c.y * 0.093);\n"
    "}\n";

static pelt_vec3 unit_dir(float a, float b)
{
    return v3(cosf(a) * sinf(b), cosf(b), sinf(a) * sinf(b));
}

static void cell_inputs(float cx, float cy, pelt_vec3 *n, pelt_vec3 *t, pelt_vec3 *tip, float *h,
                        float *s)
{
    *n = unit_dir(cx * 0.37f, 0.2f + cy * 0.05f);
    *t = v3_norm_or(v3_cross(*n, v3(0.3f, 0.1f, 0.95f)), v3(1, 0, 0));
    *tip = v3_scale(unit_dir(cx * 0.11f + 1.0f, 0.1f + cy * 0.03f), 0.8f);
    float hx = cx * 0.131f + cy * 0.071f, sx = cx * 0.017f + cy * 0.093f;
    *h = hx - floorf(hx);
    *s = sx - floorf(sx);
}

static const char kajiya_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec3 n, t, tip; float h, s;\n"
    "  cell_inputs(floor(gl_FragCoord.xy), n, t, tip, h, s);\n"
    "  vec3 E = normalize(tip - 0.5 * n);\n"
    "  vec2 kk = kajiya_kay(t, n, E, 4.0 + 60.0 * s);\n"
    "  o = vec4(kk, shadow_factor(1.0 + 3.0 * s, h), 0.0);\n"
    "}\n";

static void kajiya_kay_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_shading, inputs_glsl, kajiya_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            pelt_vec3 n, t, tip;
            float h, s, diff, spec;
            cell_inputs((float)x, (float)y, &n, &t, &tip, &h, &s);
            pelt_vec3 e = v3_norm_or(v3_sub(tip, v3_scale(n, 0.5f)), v3(0, 0, 1));
            pelt__kajiya_kay(t, n, e, 4.0f + 60.0f * s, &diff, &spec);
            const float *g = out + 4 * (y * W + x);
            double err = fmax(fabs(g[0] - diff), fmax(fabs(g[1] - spec),
                              fabs(g[2] - pelt__shadow_factor(1.0f + 3.0f * s, h))));
            if (err > worst) worst = err;
        }
    printf("  worst |GLSL - C| = %.3g\n", worst);
    CHECK(worst < 2e-4);
}

static const char wet_shine_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec3 n, t, tip; float h, s;\n"
    "  cell_inputs(floor(gl_FragCoord.xy), n, t, tip, h, s);\n"
    "  float rho = 1.4 * h - 0.2;\n" /* beyond [0, 1] at both ends: clamped */
    "  vec2 ws = wet_shine(rho, 4.0 + 60.0 * s, 1.0 + 7.0 * fract(3.0 * s), 1.0 + 3.0 * h);\n"
    "  vec3 E = normalize(tip - 0.5 * n);\n"
    "  vec2 kk = kajiya_kay(t, n, E, ws.x);\n"
    "  o = vec4(ws, ws.y * kk.y, 0.0);\n"
    "}\n";

/* Wet shine: the exponent and gain of wet fur, and the highlight they make. */
static void wet_shine_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_shading, inputs_glsl, wet_shine_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            pelt_vec3 n, t, tip;
            float h, s, p, gain, diff, spec;
            cell_inputs((float)x, (float)y, &n, &t, &tip, &h, &s);
            float f3 = 3.0f * s - floorf(3.0f * s);
            pelt__wet_shine(1.4f * h - 0.2f, 4.0f + 60.0f * s, 1.0f + 7.0f * f3, 1.0f + 3.0f * h, &p, &gain);
            pelt_vec3 e = v3_norm_or(v3_sub(tip, v3_scale(n, 0.5f)), v3(0, 0, 1));
            pelt__kajiya_kay(t, n, e, p, &diff, &spec);
            const float *g = out + 4 * (y * W + x);
            /* The exponent reaches 512: compare it relative to its size. */
            double err = fmax(fabs(g[0] - p) / fmax(1.0, p), fmax(fabs(g[1] - gain), fabs(g[2] - gain * spec)));
            if (err > worst) worst = err;
        }
    printf("  worst |GLSL - C| = %.3g\n", worst);
    CHECK(worst < 2e-4);
}

static const char wet_color_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec3 n, t, tip; float h, s;\n"
    "  cell_inputs(floor(gl_FragCoord.xy), n, t, tip, h, s);\n"
    "  o = vec4(wet_color(abs(t) * (0.2 + 1.5 * s), 1.4 * h - 0.2, 0.9 * fract(3.0 * s)),\n"
    "           clump_stray(floor(h * 255.0) / 255.0, 0.3 * s) ? 1.0 : 0.0);\n"
    "}\n";

/* Wet hair's colour: darker and more saturated, in GLSL as in C; and the
 * strays, on the ids an 8-bit texture holds. */
static void wet_color_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_shading, pelt__shader_clump, inputs_glsl, wet_color_main, NULL};
    int strays = 0, stray_mismatch = 0;
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            pelt_vec3 n, t, tip;
            float h, s;
            cell_inputs((float)x, (float)y, &n, &t, &tip, &h, &s);
            float f3 = 3.0f * s - floorf(3.0f * s);
            pelt_vec3 c = v3_scale(v3(fabsf(t.x), fabsf(t.y), fabsf(t.z)), 0.2f + 1.5f * s);
            pelt_vec3 w = pelt__wet_color(c, 1.4f * h - 0.2f, 0.9f * f3);
            const float *g = out + 4 * (y * W + x);
            worst = fmax(worst, fmax(fabs(g[0] - w.x), fmax(fabs(g[1] - w.y), fabs(g[2] - w.z))));
            bool stray = pelt__clump_stray(floorf(h * 255.0f) / 255.0f, 0.3f * s);
            strays += stray;
            stray_mismatch += stray != (g[3] > 0.5f);
        }
    printf("  worst |GLSL - C| = %.3g; %d strays, %d differ\n", worst, strays, stray_mismatch);
    CHECK(strays > 0 && stray_mismatch == 0);
    CHECK(worst < 2e-4);
}

/* u_which comes in as a #define placed before this text. */
static const char shape_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec3 n, u, tip; float h, s;\n"
    "  cell_inputs(floor(gl_FragCoord.xy), n, u, tip, h, s);\n"
    "  vec3 v = cross(n, u);\n"
    "  float L0 = 0.8, omega = 30.0 * s, K = 0.1 + 0.2 * s, rho = fract(s * 7.0);\n"
    "  float slant = 1.2 * s;\n"
    "  vec3 r = u_which == 0 ? fur_bend(n, L0, tip, h)\n"
    "         : u_which == 1 ? fur_curl(u, v, omega, K, rho, h)\n"
    "         : u_which == 2 ? fur_tangent(n, L0, tip, u, v, omega, K, rho, h)\n"
    "         : u_which == 3 ? fur_comb(u, L0, slant, h)\n"
    "         : fur_tangent_combed(n, L0, tip, u, v, 0.7 * tip, omega, K, rho, slant, h);\n"
    "  o = vec4(r, 0.0);\n"
    "}\n";

/* beta(h), phi(h) and T(h) of Silva Eq. 1 and 4 in the vertex shader. */
static void fur_shape_glsl_matches_c(void)
{
    const char *which_names[] = {"fur_bend", "fur_curl", "fur_tangent", "fur_comb",
                                 "fur_tangent_combed"};
    for (int which = 0; which < 5; which++) {
        char define[64];
        snprintf(define, sizeof define, "#define u_which %d\n", which);
        const char *fs[] = {pelt__shader_fur_shape, inputs_glsl, define, shape_main, NULL};
        CHECK(gl_test_eval(gl, fs, W, H, out));
        double worst = 0.0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                pelt_vec3 n, u, tip;
                float h, s;
                cell_inputs((float)x, (float)y, &n, &u, &tip, &h, &s);
                pelt_vec3 v = v3_cross(n, u);
                float L0 = 0.8f, omega = 30.0f * s, K = 0.1f + 0.2f * s;
                float rho = s * 7.0f - floorf(s * 7.0f);
                float slant = 1.2f * s;
                pelt_vec3 r = which == 0   ? pelt__fur_bend(n, L0, tip, h)
                              : which == 1 ? pelt__fur_curl(u, v, omega, K, rho, h)
                              : which == 2 ? pelt__fur_tangent(n, L0, tip, u, v, omega, K, rho, h)
                              : which == 3 ? pelt__fur_comb(u, L0, slant, h)
                                           : pelt__fur_tangent_combed(n, L0, tip, u, v,
                                                                      v3_scale(tip, 0.7f), omega,
                                                                      K, rho, slant, h);
                const float *g = out + 4 * (y * W + x);
                double err = fmax(fabs(g[0] - r.x), fmax(fabs(g[1] - r.y), fabs(g[2] - r.z)));
                if (which == 4) err /= fmax(1.0, fabs(r.x)); /* tan grows steep: relative above 1 */
                if (err > worst) worst = err;
            }
        printf("  %s: worst |GLSL - C| = %.3g\n", which_names[which], worst);
        CHECK(worst < 2e-4);
    }
}

static const char fit_normal_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec3 n, u, tip; float h, s;\n"
    "  cell_inputs(floor(gl_FragCoord.xy), n, u, tip, h, s);\n"
    "  vec3 v = cross(n, u), d = 0.4 * (tip - 0.4 * vec3(h, s, h * s));\n"
    "  o = vec4(level_fit_normal(n, u, v, d), 0.0);\n"
    "}\n";

/* A coarse level's fitted hair normal (core/fur/lod_normals.c) in the
 * shell vertex stage as in C. */
static void level_fit_normal_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_fur_shape, inputs_glsl, fit_normal_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0, turned = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            pelt_vec3 n, u, tip;
            float h, s;
            cell_inputs((float)x, (float)y, &n, &u, &tip, &h, &s);
            pelt_vec3 v = v3_cross(n, u);
            pelt_vec3 d = v3_scale(v3_sub(tip, v3_scale(v3(h, s, h * s), 0.4f)), 0.4f);
            float nf[3], uf[3], vf[3], df[3], r[3];
            v3_store(nf, n), v3_store(uf, u), v3_store(vf, v), v3_store(df, d);
            pelt__lod_fit_normal(nf, uf, vf, df, r);
            const float *g = out + 4 * (y * W + x);
            for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(g[k] - r[k]));
            turned = fmax(turned, 1.0 - (r[0] * n.x + r[1] * n.y + r[2] * n.z));
        }
    printf("  worst |GLSL - C| = %.3g, largest turn 1 - cos = %.3g\n", worst, turned);
    CHECK(turned > 0.01);
    CHECK(worst < 2e-5);
}

static const char shell_gap_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec3 n, u, tip; float h, s;\n"
    "  cell_inputs(floor(gl_FragCoord.xy), n, u, tip, h, s);\n"
    "  vec3 v = cross(n, u), t = normalize(tip + 0.3 * n);\n"
    "  vec3 V = normalize(vec3(s - 0.5, h - 0.6, 0.2 - s));\n"
    "  o = vec4(shell_gap(n, t, V, u, v, 0.01 + 0.02 * h, 3.0 + 5.0 * s, 1.2 * fract(7.0 * s) - 0.2), 0.0);\n"
    "}\n";

/* The gap between a shell's section of a hair and the next shell's, seen
 * from the side (pelt__lod_shell_gap), in GLSL as in C. */
static void shell_gap_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_shell_lod, inputs_glsl, shell_gap_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    int read = 0, partly = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            pelt_vec3 n, u, tip;
            float h, s;
            cell_inputs((float)x, (float)y, &n, &u, &tip, &h, &s);
            pelt_vec3 v = v3_cross(n, u), t = v3_norm_or(v3_mad(tip, n, 0.3f), n);
            pelt_vec3 V = v3_norm_or(v3(s - 0.5f, h - 0.6f, 0.2f - s), n);
            float nf[3], tf[3], Vf[3], uf[3], vf[3], g[3];
            v3_store(nf, n), v3_store(tf, t), v3_store(Vf, V), v3_store(uf, u), v3_store(vf, v);
            float sx7 = 7.0f * s;
            pelt__lod_shell_gap(nf, tf, Vf, uf, vf, 0.01f + 0.02f * h, 3.0f + 5.0f * s, 1.2f * (sx7 - floorf(sx7)) - 0.2f, g);
            const float *o = out + 4 * (y * W + x);
            for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(o[k] - g[k]) / fmax(1.0, fabs(g[k])));
            read += g[2] > 0.0f;
            partly += g[2] > 0.0f && g[2] < 1.0f;
        }
    printf("  %d of %d cells read the gap (%d in part); worst relative |GLSL - C| = %.3g\n", read, W * H, partly,
           worst);
    CHECK(read > 0 && read < W * H);
    CHECK(partly > 0);
    CHECK(worst < 1e-4);
}

static const char outline_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec3 n, t, tip; float h, s;\n"
    "  vec2 c = floor(gl_FragCoord.xy);\n"
    "  cell_inputs(c, n, t, tip, h, s);\n"
    "  uint seed = outline_seed(uint(c.x) * 977u, uint(c.y) * 131u + 7u, uint(c.x + c.y) % 32u);\n"
    "  float r0 = outline_random(seed, uint(c.y) % 6u), r1 = outline_random(seed, 1u), r2 = outline_random(seed, 2u);\n"
    "  vec4 q = outline_shape(0.1 * n, 0.1 * n + tip, t, r1, r2, h);\n"
    "  vec3 dir = vec3(outline_lean(r2), outline_reach(30.0 * s), outline_share(30.0 * s, 2.0 * h - 0.5));\n"
    "  float a = outline_alpha(mod(c.x, 9.0), 64.0 * s, h, r0);\n"
    "  o = c.y < 24.0 ? vec4(q.xyz, r0) : vec4(dir, a);\n"
    "}\n";

/* The outline's hairs (outline_hair.glsl against core/fur/fins.c): the
 * hash and its draws exactly, the hair's points, direction and alpha. */
static void outline_hair_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_outline_hair, inputs_glsl, outline_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    int partial = 0, more = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            pelt_vec3 n, t, tip;
            float h, s;
            cell_inputs((float)x, (float)y, &n, &t, &tip, &h, &s);
            uint32_t seed = pelt__outline_seed((uint32_t)x * 977u, (uint32_t)y * 131u + 7u, (uint32_t)(x + y) % 32u);
            float r0 = pelt__outline_random(seed, (uint32_t)y % 6u), r1 = pelt__outline_random(seed, 1u),
                  r2 = pelt__outline_random(seed, 2u);
            float q[4], e[4];
            pelt_vec3 root = v3_scale(n, 0.1f);
            pelt__outline_shape(root, v3_add(root, tip), t, r1, r2, h, q);
            pelt_vec3 dir = v3(pelt__outline_lean(r2), pelt__outline_reach(30.0f * s),
                               pelt__outline_share(30.0f * s, 2.0f * h - 0.5f));
            float a = pelt__outline_alpha((float)(x % 9), 64.0f * s, h, r0);
            if (y < 24)
                e[0] = q[0], e[1] = q[1], e[2] = q[2], e[3] = r0;
            else
                e[0] = dir.x, e[1] = dir.y, e[2] = dir.z, e[3] = a;
            partial += y >= 24 && a > 0.0f && a < 1.0f;
            more += y >= 24 && a > 1.0f;
            const float *o = out + 4 * (y * W + x);
            for (int k = 0; k < 4; k++) worst = fmax(worst, fabs(o[k] - e[k]) / fmax(1.0, fabs(e[k])));
        }
    printf("  %d cells with a partial alpha, %d standing for more hairs; worst relative |GLSL - C| = %.3g\n",
           partial, more, worst);
    CHECK(partial > 0 && more > 0);
    CHECK(worst < 1e-5);
}

static const char clump_main[] =
    "uniform sampler2D u_mask;\n"
    "out vec4 o;\n"
    "void main() {\n"
    "  vec2 c = floor(gl_FragCoord.xy);\n"
    "  vec2 p = (c + vec2(0.37, 0.61)) / vec2(64.0, 48.0);\n"
    "  float h = (1.0 + mod(c.x + c.y, 16.0)) / 16.0;\n"
    "  float w = mod(c.y, 3.0) * 0.5;\n"
    "  vec2 q = p;\n"
    "  float lean = mod(c.x, 2.0) * 0.5;\n"
    "  int r = clump_lookup(u_mask, p, h, w, 16.0, 0.9, lean, q);\n"
    "  o = vec4(float(r), q, clump_tuft_profile(h, w, 16.0));\n"
    "}\n";

/* Silva Eq. 5 and Alg. 2 in the shell fragment shader vs core/wet/clump.c, on
 * a mask with overlapping droplets; every other column's tufts lean by half
 * their radius (clump_lean: the radii's lowest bits pick the way). */
static void clump_glsl_matches_c(void)
{
    pelt__wetness *m = NULL;
    CHECK(pelt__wetness_create(64, 64, NULL, &m, NULL) == PELT_OK);
    if (!m) return;
    const pelt_droplet drops[] = {{{0.3f, 0.4f}, 0.2f, 0.9f}, {{0.45f, 0.5f}, 0.15f, 0.6f},
                                  {{0.8f, 0.2f}, 0.1f, 1.0f}, {{0.7f, 0.75f}, 0.2f, 0.4f}};
    for (size_t i = 0; i < 4; i++) pelt__wetness_add_droplet(m, &drops[i], NULL);
    GLuint tex;
    glGenTextures(1, &tex);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, 64, 64, 0, GL_RGBA, GL_FLOAT, m->texels);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    const char *fs[] = {pelt__shader_clump, clump_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    int mismatched = 0, displaced = 0, discarded = 0, leaning = 0;
    double worst = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float p[2] = {((float)x + 0.37f) / 64.0f, ((float)y + 0.61f) / 48.0f};
            float h = (1.0f + fmodf((float)(x + y), 16.0f)) / 16.0f;
            float w = fmodf((float)y, 3.0f) * 0.5f;
            float q[2] = {p[0], p[1]}, lean[2];
            pelt__clump_lean(pelt__clump_texel(m->texels, 64, 64, p), fmodf((float)x, 2.0f) * 0.5f, lean);
            leaning += fabsf(lean[0]) + fabsf(lean[1]) > 0.0f;
            int r = (int)pelt__clump_lookup_lean(m->texels, 64, 64, p, h, w, 16.0f, 0.9f, lean, q);
            const float *g = out + 4 * (y * W + x);
            if ((int)g[0] != r) mismatched++;
            if (r == PELT__CLUMP_DISPLACED) {
                displaced++;
                worst = fmax(worst, fmax(fabs(g[1] - q[0]), fabs(g[2] - q[1])));
            }
            if (r == PELT__CLUMP_DISCARD) discarded++;
            worst = fmax(worst, fabs(g[3] - pelt__clump_tuft_profile(h, w, 16.0f)));
        }
    printf("  %d displaced, %d discarded, %d leaning, %d results differ, worst |GLSL - C| = %.3g\n", displaced,
           discarded, leaning, mismatched, worst);
    CHECK(displaced > 100 && discarded > 10 && leaning > 100);
    CHECK(mismatched == 0);
    CHECK(worst < 2e-4);
    glDeleteTextures(1, &tex);
    pelt__wetness_destroy(m);
}

static const char tuft_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec3 n, t, tip; float h, s;\n"
    "  cell_inputs(floor(gl_FragCoord.xy), n, t, tip, h, s);\n"
    "  float slope = clump_tuft_slope(h, s, 16.0);\n"
    "  vec3 du = 3.0 * n, dv = 2.0 * tip;\n"
    "  vec3 L = normalize(vec3(0.3, 0.8, 0.5)), E = normalize(vec3(-0.2, -0.4, -0.9));\n"
    "  vec2 d = tuft_dots(vec3(dot(t, L), dot(du, L), dot(dv, L)), vec3(dot(t, E), dot(du, E), dot(dv, E)),\n"
    "                     vec4(dot(t, du), dot(t, dv), dot(du, du), dot(dv, dv)), dot(du, dv),\n"
    "                     vec2(s - 0.5, 0.3 - h), 0.9 * slope);\n"
    "  o = vec4(d, slope, 0.0);\n"
    "}\n";

static float dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* A tuft's hair's dots with the light and the eye and the slope of its
 * profile, in GLSL as in C; and the dots are those of the tuft's tangent
 * (t plus the pull's way to the centre, normalised) worked out as vectors. */
static void tuft_dots_glsl_match_c(void)
{
    const char *fs[] = {pelt__shader_clump, inputs_glsl, tuft_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0, worst_vectors = 0.0;
    int bent = 0;
    const float L0[3] = {0.3f, 0.8f, 0.5f}, E0[3] = {-0.2f, -0.4f, -0.9f};
    float L[3], E[3], nl = sqrtf(dot3(L0, L0)), ne = sqrtf(dot3(E0, E0));
    for (int k = 0; k < 3; k++) L[k] = L0[k] / nl, E[k] = E0[k] / ne;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            pelt_vec3 n, t, tip;
            float h, s;
            cell_inputs((float)x, (float)y, &n, &t, &tip, &h, &s);
            float slope = pelt__clump_tuft_slope(h, s, 16.0f);
            float tv[3] = {t.x, t.y, t.z}, du[3] = {3.0f * n.x, 3.0f * n.y, 3.0f * n.z};
            float dv[3] = {2.0f * tip.x, 2.0f * tip.y, 2.0f * tip.z}, to[2] = {s - 0.5f, 0.3f - h};
            float l[3] = {dot3(tv, L), dot3(du, L), dot3(dv, L)}, e[3] = {dot3(tv, E), dot3(du, E), dot3(dv, E)};
            float g4[4] = {dot3(tv, du), dot3(tv, dv), dot3(du, du), dot3(dv, dv)}, d[2];
            pelt__tuft_dots(l, e, g4, dot3(du, dv), to, 0.9f * slope, d);
            const float *g = out + 4 * (y * W + x);
            worst = fmax(worst, fmax(fabs(g[0] - d[0]), fabs(g[1] - d[1])));
            worst = fmax(worst, fabs(g[2] - slope) / fmax(1.0, slope));
            /* The tangent as vectors. */
            float T[3], len2 = 0.0f;
            for (int k = 0; k < 3; k++) {
                T[k] = tv[k] + (du[k] * to[0] + dv[k] * to[1]) * 0.9f * slope;
                len2 += T[k] * T[k];
            }
            for (int k = 0; k < 3; k++) T[k] /= sqrtf(len2);
            worst_vectors = fmax(worst_vectors, fmax(fabs(dot3(T, L) - d[0]), fabs(dot3(T, E) - d[1])));
            bent += dot3(T, tv) < 0.99f;
        }
    printf("  %d of %d tangents bent towards their tuft; worst |GLSL - C| = %.3g, |dots - vectors| = %.3g\n", bent,
           W * H, worst, worst_vectors);
    CHECK(bent > W * H / 4);
    CHECK(worst < 2e-4);
    CHECK(worst_vectors < 1e-4);
}

static const char ringlet_tangent_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec3 n, t, tip; float h, s;\n"
    "  cell_inputs(floor(gl_FragCoord.xy), n, t, tip, h, s);\n"
    "  vec3 u = normalize(cross(n, t)), v = cross(t, u);\n"
    "  float psi = ringlet_phase(s);\n"
    "  o = vec4(ringlet_tangent(t, u, v, 0.5 * s, 37.7 * h, h, psi), psi);\n"
    "}\n";

/* A ringlet's tangent and its phase from the strand's id, in GLSL as in C. */
static void ringlet_tangent_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_fur_shape, inputs_glsl, ringlet_tangent_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    int curled = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            pelt_vec3 n, t, tip;
            float h, s;
            cell_inputs((float)x, (float)y, &n, &t, &tip, &h, &s);
            pelt_vec3 u = v3_norm_or(v3_cross(n, t), v3(1, 0, 0)), v = v3_cross(t, u);
            float psi = pelt__ringlet_phase(s);
            pelt_vec3 T = pelt__ringlet_tangent(t, u, v, 0.5f * s, 37.7f * h, h, psi);
            const float *g = out + 4 * (y * W + x);
            worst = fmax(worst, fmax(fabs(g[0] - T.x), fmax(fabs(g[1] - T.y), fabs(g[2] - T.z))));
            worst = fmax(worst, fabs(g[3] - psi) / 6.2831853);
            curled += v3_dot(T, t) < 0.9f;
        }
    printf("  %d of %d tangents turned by their curl; worst |GLSL - C| = %.3g\n", curled, W * H, worst);
    CHECK(curled > W * H / 4);
    CHECK(worst < 5e-4);
}

static const char ringlet_dots_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec3 n, t, tip; float h, s;\n"
    "  cell_inputs(floor(gl_FragCoord.xy), n, t, tip, h, s);\n"
    "  vec3 u = normalize(n + 0.3 * t), v = normalize(cross(t, n) + 0.2 * n);\n"
    "  vec3 a = normalize(vec3(0.5, 1.0, 0.8)), b = normalize(tip - vec3(0.0, 2.0, 0.0));\n"
    "  vec2 d = ringlet_dots(vec3(dot(t, a), dot(u, a), dot(v, a)), vec3(dot(t, b), dot(u, b), dot(v, b)),\n"
    "                        vec3(dot(t, u), dot(t, v), dot(u, v)), 0.5 * s, 37.7 * h, h, ringlet_phase(s),\n"
    "                        strand_curl_slope(0.08 * s, 18.8, s > 0.5, h, ringlet_phase(h)));\n"
    "  o = vec4(d, 0.0, 0.0);\n"
    "}\n";

/* The curl's dots (the shells' and fins' dry curl light: a ringlet and the
 * texture's own curl, helix and wave), in GLSL as in C. */
static void ringlet_dots_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_fur_shape, inputs_glsl, ringlet_dots_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            pelt_vec3 n, t, tip;
            float h, s;
            cell_inputs((float)x, (float)y, &n, &t, &tip, &h, &s);
            pelt_vec3 u = v3_norm_or(v3_add(n, v3_scale(t, 0.3f)), v3(1, 0, 0));
            pelt_vec3 v = v3_norm_or(v3_add(v3_cross(t, n), v3_scale(n, 0.2f)), v3(0, 0, 1));
            pelt_vec3 a = v3_norm_or(v3(0.5f, 1.0f, 0.8f), v3(0, 1, 0)), b = v3_norm_or(v3_sub(tip, v3(0, 2, 0)), a);
            const float ta[3] = {v3_dot(t, a), v3_dot(u, a), v3_dot(v, a)};
            const float tb[3] = {v3_dot(t, b), v3_dot(u, b), v3_dot(v, b)};
            const float gram[3] = {v3_dot(t, u), v3_dot(t, v), v3_dot(u, v)};
            float d[2];
            float extra[2];
            pelt__strand_curl_slope(0.08f * s, 18.8f, s > 0.5f, h, pelt__ringlet_phase(h), extra);
            pelt__ringlet_dots(ta, tb, gram, 0.5f * s, 37.7f * h, h, pelt__ringlet_phase(s), extra, d);
            const float *g = out + 4 * (y * W + x);
            worst = fmax(worst, fmax(fabs(g[0] - d[0]), fabs(g[1] - d[1])));
        }
    printf("  worst |GLSL - C| = %.3g\n", worst);
    CHECK(worst < 5e-4);
}

static const char ringlet_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec2 c = floor(gl_FragCoord.xy);\n"
    "  float rho = c.x / 50.0 - 0.1;\n"
    "  float levels = 1.0 + mod(c.y, 4.0);\n"
    "  o = vec4(ringlet_levels(rho, levels, 17.0 + c.y), 0.0);\n"
    "}\n";

/* Ringlets: the two curl levels a wet fragment blends, and the weight. */
static void ringlet_levels_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_clump, ringlet_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float r[3];
            pelt__ringlet_levels((float)x / 50.0f - 0.1f, 1.0f + fmodf((float)y, 4.0f), 17.0f + (float)y, r);
            const float *g = out + 4 * (y * W + x);
            for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(g[k] - r[k]));
        }
    printf("  worst |GLSL - C| = %.3g\n", worst);
    CHECK(worst < 2e-4);
}

static const char coverage_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec2 c = floor(gl_FragCoord.xy);\n"
    "  float a = c.x / 63.0, k = 0.05 + 0.95 * c.y / 47.0;\n"
    "  o = vec4(clump_coverage(a, k), 0.0, 0.0, 0.0);\n"
    "}\n";

/* The tuft's coverage of squeezed strands, GLSL vs C. */
static void clump_coverage_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_clump, coverage_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float a = (float)x / 63.0f, k = 0.05f + 0.95f * (float)y / 47.0f;
            worst = fmax(worst, fabs(out[4 * (y * W + x)] - pelt__clump_coverage(a, k)));
        }
    printf("  worst |GLSL - C| = %.3g\n", worst);
    CHECK(worst < 2e-4);
}

static const char bundle_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec2 c = floor(gl_FragCoord.xy);\n"
    "  float k = 0.05 + 0.95 * c.x / 63.0, lod = c.y / 47.0 * 5.0 - 1.0;\n"
    "  o = vec4(clump_bundle_squeeze(k, lod), 0.0, 0.0, 0.0);\n"
    "}\n";

/* The squeeze a tuft's coverage is raised by at a mip level, GLSL vs C. */
static void clump_bundle_squeeze_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_clump, bundle_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float k = 0.05f + 0.95f * (float)x / 63.0f, lod = (float)y / 47.0f * 5.0f - 1.0f;
            worst = fmax(worst, fabs(out[4 * (y * W + x)] - pelt__clump_bundle_squeeze(k, lod)));
        }
    printf("  worst |GLSL - C| = %.3g\n", worst);
    CHECK(worst < 2e-6);
}

static const char sub_shell_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec2 c = floor(gl_FragCoord.xy);\n"
    "  float k = 1.0 + floor(c.y / 8.0), part = mod(c.x, k), a = c.x / 63.0;\n"
    "  o = vec4(sub_shell_layer(20.0, part, k, 1.0 + mod(c.y, 4.0)), sub_shell_alpha(a, k), 0.0, 0.0);\n"
    "}\n";

/* Sub shells' layers and coverage, GLSL vs C. */
static void sub_shell_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_clump, sub_shell_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float k = 1.0f + floorf((float)y / 8.0f), part = fmodf((float)x, k), a = (float)x / 63.0f;
            const float *g = out + 4 * (y * W + x);
            worst = fmax(worst, fabs(g[0] - pelt__sub_shell_layer(20.0f, part, k, 1.0f + fmodf((float)y, 4.0f))));
            worst = fmax(worst, fabs(g[1] - pelt__sub_shell_alpha(a, k)));
        }
    printf("  worst |GLSL - C| = %.3g\n", worst);
    CHECK(worst < 2e-5);
}

/* Close-up sub shells per vertex: sub_shell_need over spacings from a
 * tenth of a pixel to 4 px, view angles and curls, and sub_shell_exponent
 * for every part of 1 to 6 at that need, GLSL vs C. */
static const char sub_shell_need_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec2 c = floor(gl_FragCoord.xy);\n"
    "  float side = 0.1 + 3.9 * c.x / 63.0, ndv = -1.0 + 2.0 * c.y / 47.0, drift = 0.1 * mod(c.x, 3.0);\n"
    "  float need = sub_shell_need(side, ndv, drift);\n"
    "  float k = 1.0 + mod(c.y, 6.0), part = mod(c.x, k);\n"
    "  o = vec4(need, sub_shell_exponent(part, k, need), 0.0, 1.0);\n"
    "}\n";

static void sub_shell_need_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_shell_lod, sub_shell_need_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    int none = 0, all = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float side = 0.1f + 3.9f * (float)x / 63.0f, ndv = -1.0f + 2.0f * (float)y / 47.0f;
            float drift = 0.1f * fmodf((float)x, 3.0f);
            float need = pelt__lod_sub_shell_need(side, ndv, drift);
            float k = 1.0f + fmodf((float)y, 6.0f), part = fmodf((float)x, k);
            const float *g = out + 4 * (y * W + x);
            worst = fmax(worst, fabs(g[0] - need));
            worst = fmax(worst, fabs(g[1] - pelt__lod_sub_shell_exponent(part, k, need)));
            none += need == 0.0f, all += need == 1.0f;
        }
    printf("  sub_shell_need, sub_shell_exponent: worst |GLSL - C| = %.3g (%d none, %d all)\n", worst, none, all);
    CHECK(none > 100 && all > 100);
    CHECK(worst < 2e-5);
}

static const char skin_sheen_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec2 c = floor(gl_FragCoord.xy);\n"
    "  float ndh = c.x / 63.0 * 1.2 - 0.1, rho = c.y / 47.0 * 1.2 - 0.1;\n"
    "  o = vec4(wet_skin_sheen(ndh, rho, 20.0, 4.0, 2.0), wet_skin_sheen(ndh, rho, 7.0, 1.0, 1.0), 0.0, 0.0);\n"
    "}\n";

/* Wet skin's sheen, GLSL vs C, outside [0, 1] too. */
static void wet_skin_sheen_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_shading, skin_sheen_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0, largest = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float ndh = (float)x / 63.0f * 1.2f - 0.1f, rho = (float)y / 47.0f * 1.2f - 0.1f;
            float a = pelt__wet_skin_sheen(ndh, rho, 20.0f, 4.0f, 2.0f), b = pelt__wet_skin_sheen(ndh, rho, 7.0f, 1.0f, 1.0f);
            const float *g = out + 4 * (y * W + x);
            largest = fmax(largest, a);
            worst = fmax(worst, fmax(fabs(g[0] - a), fabs(g[1] - b)));
        }
    printf("  worst |GLSL - C| = %.3g, sheen up to %.2f\n", worst, largest);
    CHECK(largest > 1.5);
    CHECK(worst < 2e-4);
}

static const char fin_shift_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec2 c = floor(gl_FragCoord.xy);\n"
    "  vec2 d = vec2(c.x / 31.5 - 1.0, c.y / 23.5 - 1.0) * 0.02;\n"
    "  vec2 dir = vec2(cos(c.x * 0.37 + c.y), sin(c.x * 0.37 + c.y)) * (c.y < 4.0 ? 0.0 : 1e-3 * (0.5 + c.y / 47.0));\n"
    "  o = vec4(clump_fin_shift(d, dir), 0.0, 0.0, 0.0);\n"
    "}\n";

/* A tuft's pull along a fin (the fins' tufts), GLSL vs C, the rows without
 * an edge direction included. */
static void clump_fin_shift_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_clump, fin_shift_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0, largest = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float d[2] = {((float)x / 31.5f - 1.0f) * 0.02f, ((float)y / 23.5f - 1.0f) * 0.02f};
            float angle = (float)x * 0.37f + (float)y, len = y < 4 ? 0.0f : 1e-3f * (0.5f + (float)y / 47.0f);
            float dir[2] = {cosf(angle) * len, sinf(angle) * len};
            float c = pelt__clump_fin_shift(d, dir);
            largest = fmax(largest, fabs(c));
            worst = fmax(worst, fabs(out[4 * (y * W + x)] - c) / fmax(1.0, fabs(c)));
        }
    printf("  worst |GLSL - C| = %.3g (relative above 1), shifts up to %.1f\n", worst, largest);
    CHECK(largest > 1.0);
    CHECK(worst < 2e-4);
}

static const char groom_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec3 n, u, tip; float h, s;\n"
    "  cell_inputs(floor(gl_FragCoord.xy), n, u, tip, h, s);\n"
    "  vec3 v = cross(n, u);\n"
    "  vec3 color = vec3(0.55, 0.34, 0.18) * (0.2 + s), tipc = vec3(1.0, 0.82, 0.58);\n"
    "  vec4 c = vec4(fract(tip * 3.7 + 0.5), h);\n"
    "  vec3 r = u_which == 0 ? fur_groom_shear(tip, 1.3 * s, u, v, vec2(h - 0.5, s * 1.2 - 0.4))\n"
    "         : u_which == 1 ? groom_root_color(color, c)\n"
    "         : u_which == 2 ? groom_tip_color(color, tipc, c)\n"
    "         : u_which == 4 ? vec3(wet_slant(tip.x * 1.5, 1.2 * s, h), 0.0, 0.0)\n"
    "         : vec3(groom_keeps(fract(s * 5.3), h) ? 1.0 : 0.0, 0.0, 0.0);\n"
    "  o = vec4(r, 0.0);\n"
    "}\n";

/* Grooming (Lengyel et al. §3): the shear of a groomed strand in the
 * vertex shader, the hair colour and the density test in the fragment
 * shaders, against pelt__fur_groom_shear and core/fur/shading.c; and wet
 * fur's slant (wet_slant, pelt__fur_wet_slant). */
static void groom_glsl_matches_c(void)
{
    const char *names[] = {"fur_groom_shear", "groom_root_color", "groom_tip_color", "groom_keeps", "wet_slant"};
    for (int which = 0; which < 5; which++) {
        char define[64];
        snprintf(define, sizeof define, "#define u_which %d\n", which);
        const char *fs[] = {pelt__shader_fur_shape, pelt__shader_shading, inputs_glsl, define,
                            groom_main, NULL};
        CHECK(gl_test_eval(gl, fs, W, H, out));
        double worst = 0.0;
        int kept = 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                pelt_vec3 n, u, tip;
                float h, s;
                cell_inputs((float)x, (float)y, &n, &u, &tip, &h, &s);
                pelt_vec3 v = v3_cross(n, u);
                pelt_vec3 color = v3_scale(v3(0.55f, 0.34f, 0.18f), 0.2f + s);
                pelt_vec3 tipc = v3(1.0f, 0.82f, 0.58f);
                const float tv[3] = {tip.x, tip.y, tip.z};
                float c[4];
                for (int k = 0; k < 3; k++) {
                    float f = tv[k] * 3.7f + 0.5f;
                    c[k] = f - floorf(f);
                }
                c[3] = h;
                float lean[2] = {h - 0.5f, s * 1.2f - 0.4f};
                float id = s * 5.3f - floorf(s * 5.3f);
                pelt_vec3 r = which == 0   ? pelt__fur_groom_shear(tip, 1.3f * s, u, v, lean)
                              : which == 1 ? pelt__groom_root_color(color, c)
                              : which == 2 ? pelt__groom_tip_color(color, tipc, c)
                              : which == 4 ? v3(pelt__fur_wet_slant(tip.x * 1.5f, 1.2f * s, h), 0, 0)
                                           : v3(pelt__groom_keeps(id, h) ? 1.0f : 0.0f, 0, 0);
                /* A threshold test: cells within rounding of it can go either way. */
                if (which == 3 && fabsf(id - h) < 1e-4f) continue;
                kept += which == 3 && r.x > 0.5f;
                const float *g = out + 4 * (y * W + x);
                double err = fmax(fabs(g[0] - r.x), fmax(fabs(g[1] - r.y), fabs(g[2] - r.z)));
                if (which == 4) err /= fmax(1.0, fabs(r.x)); /* tan grows steep: relative above 1 */
                if (err > worst) worst = err;
            }
        printf("  %s: worst |GLSL - C| = %.3g\n", names[which], worst);
        if (which == 3) CHECK(kept > W * H / 5 && kept < W * H * 4 / 5); /* both branches seen */
        CHECK(worst < 2e-4);
    }
}

static const char shadow_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec3 n, u, tip; float h, s;\n"
    "  cell_inputs(floor(gl_FragCoord.xy), n, u, tip, h, s);\n"
    "  o = vec4(inter_shadow_offset(normalize(tip), u, cross(n, u), 0.01 + s * 0.02), 0.0, 0.0);\n"
    "}\n";

/* Kenwright's step towards the light, against core/fur/shading.c. (The
 * fins' normal and fade have no GLSL twin: core/fur/fin_frame.c works them
 * out for the fin pass with pelt__fin_normal and pelt__fin_fade.) */
static void inter_shadow_glsl_matches_c(void)
{
    const char *fs[] = {pelt__shader_shading, inputs_glsl, shadow_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            pelt_vec3 n, u, tip;
            float h, s, r[4] = {0};
            cell_inputs((float)x, (float)y, &n, &u, &tip, &h, &s);
            pelt__inter_shadow_offset(v3_norm_or(tip, n), u, v3_cross(n, u), 0.01f + s * 0.02f, r);
            const float *g = out + 4 * (y * W + x);
            for (int k = 0; k < 4; k++) worst = fmax(worst, fabs(g[k] - r[k]));
        }
    printf("  inter_shadow_offset: worst |GLSL - C| = %.3g\n", worst);
    CHECK(worst < 2e-4);
}

/* How much of Kenwright's shadow a shell draws (inter_shadow_view_fade in
 * shading.glsl) against pelt__inter_shadow_view_fade, |N.V| from -1 to 1. */
static void inter_shadow_view_fade_glsl_matches_c(void)
{
    static const char main_glsl[] =
        "out vec4 o;\n"
        "void main() {\n"
        "  vec2 c = floor(gl_FragCoord.xy);\n"
        "  o = vec4(inter_shadow_view_fade(-1.0 + 2.0 * (c.x + 64.0 * c.y) / 3071.0), 0.0, 0.0, 0.0);\n"
        "}\n";
    const char *fs[] = {pelt__shader_shading, main_glsl, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    int between = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float r = pelt__inter_shadow_view_fade(-1.0f + 2.0f * ((float)x + 64.0f * (float)y) / 3071.0f);
            worst = fmax(worst, fabs(out[4 * (y * W + x)] - r));
            between += r > 0.0f && r < 1.0f;
        }
    printf("  inter_shadow_view_fade: worst |GLSL - C| = %.3g, %d of 3072 between none and all\n", worst, between);
    CHECK(between > 500);
    CHECK(worst < 1e-5);
}

/* Lengyel §2.4 in the shell draw: instance -> layer, slices, blend and
 * opacity (shell_lod.glsl) against pelt__lod_shell_instance, over draws of
 * several layer counts, levels, blends and a first layer. The uniforms of
 * each draw come from pelt__lod_shell_uniforms, as in gl/shell_pass.c. */
enum { SHELL_CASES = 8 };
static const struct { unsigned layers, level, first; float blend; } shell_cases[SHELL_CASES] = {
    {16, 0, 0, 0.0f}, {16, 0, 4, 0.0f}, {16, 0, 0, 0.6f}, {16, 1, 0, 0.3f},
    {16, 2, 0, 0.0f}, {10, 1, 0, 0.5f}, {10, 2, 0, 0.25f}, {3, 1, 0, 0.8f}};

static void shell_lod_glsl_matches_c(void)
{
    float shells[SHELL_CASES][4], next[SHELL_CASES][2];
    unsigned count[SHELL_CASES];
    char consts[2048];
    int at = snprintf(consts, sizeof consts, "const vec4 SH[%d] = vec4[%d](", SHELL_CASES, SHELL_CASES);
    for (int c = 0; c < SHELL_CASES; c++) {
        pelt__lod_shell_uniforms(shell_cases[c].layers, shell_cases[c].level, shell_cases[c].blend,
                                 shell_cases[c].first, shells[c], next[c], &count[c]);
        at += snprintf(consts + at, sizeof consts - (size_t)at, "%svec4(%.9g, %.9g, %.9g, %.9g)", c ? ", " : "",
                       (double)shells[c][0], (double)shells[c][1], (double)shells[c][2], (double)shells[c][3]);
    }
    at += snprintf(consts + at, sizeof consts - (size_t)at, ");\nconst vec3 NX[%d] = vec3[%d](", SHELL_CASES,
                   SHELL_CASES);
    for (int c = 0; c < SHELL_CASES; c++)
        at += snprintf(consts + at, sizeof consts - (size_t)at, "%svec3(%.9g, %.9g, %u.0)", c ? ", " : "",
                       (double)next[c][0], (double)next[c][1], shell_cases[c].layers);
    snprintf(consts + at, sizeof consts - (size_t)at, ");\n");
    static const char main_glsl[] =
        "out vec4 o;\n"
        "void main() {\n"
        "  int c = int(gl_FragCoord.y) % 8;\n"
        "  vec3 slices; float alpha;\n"
        "  float layer = shell_instance(floor(gl_FragCoord.x), SH[c], NX[c].xy, NX[c].z, slices, alpha);\n"
        "  o = u_which == 0 ? vec4(layer, slices) : vec4(alpha, 0.0, 0.0, 0.0);\n"
        "}\n";
    double worst = 0.0;
    for (int which = 0; which < 2; which++) {
        char define[64];
        snprintf(define, sizeof define, "#define u_which %d\n", which);
        const char *fs[] = {pelt__shader_shell_lod, consts, define, main_glsl, NULL};
        CHECK(gl_test_eval(gl, fs, W, H, out));
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                int c = y % SHELL_CASES;
                if ((unsigned)x >= count[c]) continue;
                float slices[3], alpha;
                float layer = pelt__lod_shell_instance(shells[c], next[c], (float)shell_cases[c].layers, (float)x,
                                                       slices, &alpha);
                float r[4] = {layer, slices[0], slices[1], slices[2]};
                if (which == 1) r[0] = alpha, r[1] = r[2] = r[3] = 0.0f;
                const float *g = out + 4 * (y * W + x);
                for (int k = 0; k < 4; k++) worst = fmax(worst, fabs(g[k] - r[k]));
            }
    }
    printf("  shell_instance: worst |GLSL - C| = %.3g\n", worst);
    CHECK(worst < 1e-5);
}

/* The view's shell budget (shell_view_blend and shell_view_texel in
 * shell_lod.glsl) against pelt__lod_view_blend and pelt__lod_view_texel
 * over side-on spacings, view angles and targets: face-on, grazing and
 * edge-on, in and out of the clamp; the texel at that weight. */
static void shell_view_blend_glsl_matches_c(void)
{
    static const char main_glsl[] =
        "out vec4 o;\n"
        "void main() {\n"
        "  float side = 0.05 + 0.05 * floor(gl_FragCoord.x);\n"     /* 0.05 .. 3.2 px */
        "  float ndv = -1.0 + 2.0 * fract(gl_FragCoord.y / 16.0);\n"
        "  float target = 0.25 + 0.25 * mod(floor(gl_FragCoord.y / 16.0), 4.0);\n"
        "  float drift = mod(floor(gl_FragCoord.x / 3.0), 3.0) * 0.4;\n" /* 0, 0.4, 0.8 */
        "  float w = shell_view_blend(side, ndv, target, drift);\n"
        "  vec4 t = shell_view_texel(w, vec4(0.3, 0.2, 0.1, 0.1) * fract(gl_FragCoord.x / 7.0) * 9.0);\n"
        "  o = vec4(w, t.rgb);\n"
        "}\n";
    const char *fs[] = {pelt__shader_shell_lod, main_glsl, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    int inside = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float fx = x + 0.5f, fy = y + 0.5f;
            float side = 0.05f + 0.05f * floorf(fx);
            float ndv = -1.0f + 2.0f * (fy / 16.0f - floorf(fy / 16.0f));
            float target = 0.25f + 0.25f * fmodf(floorf(fy / 16.0f), 4.0f);
            float drift = fmodf(floorf(fx / 3.0f), 3.0f) * 0.4f;
            float r = pelt__lod_view_blend(side, ndv, target, drift);
            float f = fx / 7.0f - floorf(fx / 7.0f);
            float t[4] = {0.3f * f * 9.0f, 0.2f * f * 9.0f, 0.1f * f * 9.0f, 0.1f * f * 9.0f};
            pelt__lod_view_texel(r, t);
            inside += r > 0.01f && r < 0.99f;
            const float *g = out + 4 * (y * W + x);
            worst = fmax(worst, fabs(g[0] - r));
            for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(g[1 + k] - t[k]));
        }
    printf("  shell_view_blend: worst |GLSL - C| = %.3g, %d samples inside the clamp\n", worst, inside);
    CHECK(inside > 100);
    CHECK(worst < 1e-4);
}

/* A leaning hair's drift per layer (shell_lean_drift in shell_lod.glsl)
 * against pelt__lod_shell_lean_drift: tangents from upright through flat
 * to pointing into the skin, of several lengths, over tilted normals. */
static void shell_lean_drift_glsl_matches_c(void)
{
    static const char main_glsl[] =
        "out vec4 o;\n"
        "void main() {\n"
        "  vec2 c = floor(gl_FragCoord.xy);\n"
        "  float a = 3.14159265 * c.x / 63.0, b = 6.2831853 * c.y / 47.0;\n"
        "  vec3 n = vec3(0.3 * sin(b), 0.2, 1.0 + 0.5 * mod(c.y, 3.0));\n"
        "  vec3 t = (0.5 + mod(c.x, 4.0)) * vec3(sin(a) * cos(b), sin(a) * sin(b), cos(a));\n"
        "  o = vec4(shell_lean_drift(t, n), 0.0, 0.0, 0.0);\n"
        "}\n";
    const char *fs[] = {pelt__shader_shell_lod, main_glsl, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    int steep = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float a = 3.14159265f * (float)x / 63.0f, b = 6.2831853f * (float)y / 47.0f;
            float n[3] = {0.3f * sinf(b), 0.2f, 1.0f + 0.5f * fmodf((float)y, 3.0f)};
            float l = 0.5f + fmodf((float)x, 4.0f);
            float t[3] = {l * sinf(a) * cosf(b), l * sinf(a) * sinf(b), l * cosf(a)};
            float r = pelt__lod_shell_lean_drift(t, n);
            worst = fmax(worst, fabs(out[4 * (y * W + x)] - r) / fmax(1.0, fabs(r)));
            steep += r > 2.0f;
        }
    printf("  shell_lean_drift: worst |GLSL - C| = %.3g (relative above 1), %d samples leaning past 63 degrees\n",
           worst, steep);
    CHECK(steep > 100);
    CHECK(worst < 1e-4);
}

/* The ray's drift against a hair through the shells' stack (shell_stack_cos
 * in shell_lod.glsl) against pelt__lod_shell_stack_cos: unit hairs over
 * the sphere of directions, rays from above down to the shells' plane and
 * below it, normals tilted off z. */
static void shell_stack_cos_glsl_matches_c(void)
{
    static const char main_glsl[] =
        "out vec4 o;\n"
        "void main() {\n"
        "  vec2 c = floor(gl_FragCoord.xy);\n"
        "  float a = 3.14159265 * c.x / 63.0, b = 6.2831853 * c.y / 47.0;\n"
        "  float e = 3.14159265 * mod(c.x * 5.0 + c.y, 16.0) / 15.0;\n"
        "  vec3 n = normalize(vec3(0.3 * sin(b), 0.2, 1.0));\n"
        "  vec3 t = vec3(sin(a) * cos(b), sin(a) * sin(b), cos(a));\n"
        "  vec3 v = vec3(sin(e) * cos(2.0 * b), sin(e) * sin(2.0 * b), -cos(e));\n"
        "  o = vec4(shell_stack_cos(t, v, n), abs(dot(t, v)), 0.0, 0.0);\n"
        "}\n";
    const char *fs[] = {pelt__shader_shell_lod, main_glsl, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    int differ = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float a = 3.14159265f * (float)x / 63.0f, b = 6.2831853f * (float)y / 47.0f;
            float e = 3.14159265f * fmodf((float)x * 5.0f + (float)y, 16.0f) / 15.0f;
            float n[3] = {0.3f * sinf(b), 0.2f, 1.0f};
            float nl = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int k = 0; k < 3; k++) n[k] /= nl;
            float t[3] = {sinf(a) * cosf(b), sinf(a) * sinf(b), cosf(a)};
            float v[3] = {sinf(e) * cosf(2.0f * b), sinf(e) * sinf(2.0f * b), -cosf(e)};
            float r = pelt__lod_shell_stack_cos(t, v, n);
            const float *g = out + 4 * (y * W + x);
            worst = fmax(worst, fabs(g[0] - r));
            differ += fabsf(r - g[1]) > 0.05f; /* the stack's count is not the angle's */
        }
    printf("  shell_stack_cos: worst |GLSL - C| = %.3g, %d samples more than 0.05 off |T.V|\n", worst, differ);
    CHECK(differ > 100);
    CHECK(worst < 1e-4);
}

/* A shell fragment's coverage in one power (coverage_log, coverage_share),
 * GLSL vs C, over coverages 0..1 (both ends) and exponents 0.05..3. */
static void coverage_share_glsl_matches_c(void)
{
    static const char main_glsl[] =
        "out vec4 o;\n"
        "void main() {\n"
        "  vec2 c = floor(gl_FragCoord.xy);\n"
        "  float a = c.x / 63.0, e = 0.05 + 2.95 * c.y / 47.0;\n"
        "  float l = coverage_log(a);\n"
        "  o = vec4(coverage_share(l, e), l < -1e29 ? 1.0 : 0.0, l > COVERAGE_CLEAR_LOG ? 1.0 : 0.0, 0.0);\n"
        "}\n";
    const char *fs[] = {pelt__shader_shell_lod, main_glsl, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    int flags_off = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float a = (float)x / 63.0f, e = 0.05f + 2.95f * (float)y / 47.0f;
            float l = pelt__lod_coverage_log(a);
            const float *g = out + 4 * (y * W + x);
            worst = fmax(worst, fabs(g[0] - pelt__lod_coverage_share(l, e)));
            flags_off += (g[1] > 0.5f) != (l < -1e29f) || (g[2] > 0.5f) != (l > PELT__COVERAGE_CLEAR_LOG);
        }
    printf("  worst |GLSL - C| = %.3g, %d opaque or clear flags differ\n", worst, flags_off);
    CHECK(worst < 2e-4 && flags_off == 0);
}

/* The shells' over-count of a hair seen along its length (shell_lod.glsl)
 * against pelt__lod_shell_overcount and its companions: widths, angles and
 * drifts over the grid, and the share of coverage each shell takes. */
static void shell_overcount_glsl_matches_c(void)
{
    static const char main_glsl[] =
        "out vec4 o;\n"
        "void main() {\n"
        "  vec2 c = floor(gl_FragCoord.xy);\n"
        "  float h = c.x / 63.0, cosv = -1.0 + 2.0 * c.y / 47.0;\n"
        "  float span = shell_hair_span(0.01 + 0.001 * mod(c.y, 7.0), 0.8, h, 32.0, 0.05 + 0.01 * mod(c.x, 5.0));\n"
        "  float drift = shell_hair_drift(0.02 * mod(c.x, 3.0), 30.0, h, 0.1, 0.01 * mod(c.y, 4.0), 12.0);\n"
        "  float k = shell_overcount(span, cosv, drift, 1.0, shell_overcount_cap(c.y < 24.0 ? 32.0 : 96.0));\n"
        "  o = vec4(span, drift, k, shell_overcount_alpha(fract(0.37 * c.x + 0.11 * c.y), k));\n"
        "}\n";
    const char *fs[] = {pelt__shader_shell_lod, main_glsl, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    int counted = 0, capped = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float h = (float)x / 63.0f, cosv = -1.0f + 2.0f * (float)y / 47.0f;
            float span = pelt__lod_shell_hair_span(0.01f + 0.001f * fmodf((float)y, 7.0f), 0.8f, h, 32.0f,
                                                   0.05f + 0.01f * fmodf((float)x, 5.0f));
            float drift = pelt__lod_shell_hair_drift(0.02f * fmodf((float)x, 3.0f), 30.0f, h, 0.1f,
                                                     0.01f * fmodf((float)y, 4.0f), 12.0f);
            float cap = pelt__lod_shell_overcount_cap(y < 24 ? 32.0f : 96.0f);
            float k = pelt__lod_shell_overcount(span, cosv, drift, 1.0f, cap);
            float a = 0.37f * (float)x + 0.11f * (float)y;
            a -= floorf(a);
            float r[4] = {span, drift, k, pelt__lod_shell_overcount_alpha(a, k)};
            const float *g = out + 4 * (y * W + x);
            for (int j = 0; j < 4; j++) worst = fmax(worst, fabs(g[j] - r[j]) / fmax(1.0, fabs(r[j])));
            counted += k > 1.01f && k < cap - 0.01f;
            capped += k >= cap;
        }
    printf("  worst |GLSL - C| = %.3g (relative above 1), %d between the bounds, %d at the cap (3 or 9)\n", worst,
           counted, capped);
    CHECK(counted > 100 && capped > 100);
    CHECK(worst < 2e-4);
}

/* The least count a shell seen edge-on may take (shell_edge_least in
 * shell_lod.glsl) against pelt__lod_shell_edge_least over view angles and
 * depths 1 to 16, and shell_overcount under it against
 * pelt__lod_shell_overcount: widths and angles that put the count
 * below 1, at it and above. */
static void shell_edge_least_glsl_matches_c(void)
{
    static const char main_glsl[] =
        "out vec4 o;\n"
        "void main() {\n"
        "  vec2 c = floor(gl_FragCoord.xy);\n"
        "  float ndv = -1.0 + 2.0 * c.x / 63.0, depth = 1.0 + 15.0 * c.y / 47.0;\n"
        "  float least = shell_edge_least(ndv, depth);\n"
        "  float span = 0.2 + 0.1 * mod(c.y, 9.0), cosv = -1.0 + 2.0 * mod(c.x * 7.0, 64.0) / 63.0;\n"
        "  o = vec4(least, shell_overcount(span, cosv, 0.0, least, 3.0), 0.0, 1.0);\n"
        "}\n";
    const char *fs[] = {pelt__shader_shell_lod, main_glsl, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    int under = 0, exact = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float ndv = -1.0f + 2.0f * (float)x / 63.0f, depth = 1.0f + 15.0f * (float)y / 47.0f;
            float least = pelt__lod_shell_edge_least(ndv, depth);
            float span = 0.2f + 0.1f * fmodf((float)y, 9.0f), cosv = -1.0f + 2.0f * fmodf((float)x * 7.0f, 64.0f) / 63.0f;
            float k = pelt__lod_shell_overcount(span, cosv, 0.0f, least, 3.0f);
            const float *g = out + 4 * (y * W + x);
            worst = fmax(worst, fabs(g[0] - least));
            worst = fmax(worst, fabs(g[1] - k) / fmax(1.0, fabs(k)));
            under += k < 0.99f;
            exact += y == 0 && g[0] == 1.0f; /* depth 1: every count at least 1, exactly */
        }
    printf("  shell_edge_least, shell_overcount: worst |GLSL - C| = %.3g, %d counts below 1, %d of 64 exact at "
           "depth 1\n", worst, under, exact);
    CHECK(under > 100);
    CHECK(exact == W);
    CHECK(worst < 2e-4);
}

/* Footprints of a fur-uv read (tiles per pixel along x and along y) for
 * the pixel (x, y) of a parity picture: 2^(lo + span x / 63) texels of a
 * 256-texel tile along a direction turning with y, and 1 to 1/16 of that
 * across it. The GLSL and C halves make the same ones. */
static const char footprint_glsl[] =
    "void footprint(vec2 c, float lo, float span, out vec2 dx, out vec2 dy) {\n"
    "  float len = exp2(lo + span * c.x / 63.0) / 256.0, a = 0.3 * c.y;\n"
    "  dx = len * vec2(cos(a), sin(a));\n"
    "  dy = len * exp2(-mod(c.y, 5.0)) * vec2(-sin(a), cos(a));\n"
    "}\n";

static void footprint(int x, int y, float lo, float span, float dx[2], float dy[2])
{
    float len = exp2f(lo + span * (float)x / 63.0f) / 256.0f, a = 0.3f * (float)y;
    float s = len * exp2f(-fmodf((float)y, 5.0f));
    dx[0] = len * cosf(a), dx[1] = len * sinf(a);
    dy[0] = -s * sinf(a), dy[1] = s * cosf(a);
}

/* The shells' fur texture level (shell_fur_texture_lod, which is
 * fur_texture_lod half a level finer where the footprint is round, in
 * shell_lod.glsl) against
 * pelt__lod_shell_fur_texture over footprints from magnified to 64 texels, round
 * to 16 to 1 in every direction, at the shells' default max_aniso
 * (lod.texture_aniso); and fur_texture_aniso against
 * pelt__lod_fur_texture_aniso over spacings and view angles, at most 3; the fins' FIN_TEXTURE_ANISO and fin_texture_aniso against
 * PELT__FIN_TEXTURE_ANISO and pelt__lod_fin_texture_aniso. */
static void fur_texture_lod_glsl_matches_c(void)
{
    static const char main_glsl[] =
        "out vec4 o;\n"
        "void main() {\n"
        "  vec2 c = floor(gl_FragCoord.xy), dx, dy;\n"
        "  footprint(c, -2.0, 8.0, dx, dy);\n"
        "  float side = 0.05 * c.x, ndv = -1.0 + 2.0 * c.y / 47.0;\n"
        "  o = vec4(shell_fur_texture_lod(dx, dy, 256.0, 4.0), fur_texture_aniso(side, ndv, 3.0),\n"
        "           FIN_TEXTURE_ANISO, fin_texture_aniso(dx * 256.0, dy * 256.0));\n"
        "}\n";
    const char *fs[] = {pelt__shader_shell_lod, footprint_glsl, main_glsl, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    int between = 0, fin_between = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float dx[2], dy[2];
            footprint(x, y, -2.0f, 8.0f, dx, dy);
            float r = pelt__lod_shell_fur_texture(dx, dy, 256.0f, PELT__FUR_TEXTURE_ANISO); /* 4, as above */
            worst = fmax(worst, fabs(out[4 * (y * W + x)] - r));
            float q = pelt__lod_fur_texture_aniso(0.05f * (float)x, -1.0f + 2.0f * (float)y / 47.0f, 3.0f);
            worst = fmax(worst, fabs(out[4 * (y * W + x) + 1] - q));
            between += q > 1.01f && q < 3.0f - 0.01f;
            worst = fmax(worst, fabs(out[4 * (y * W + x) + 2] - PELT__FIN_TEXTURE_ANISO)); /* the fins' */
            float tx[2] = {dx[0] * 256.0f, dx[1] * 256.0f}, ty[2] = {dy[0] * 256.0f, dy[1] * 256.0f};
            float fa = pelt__lod_fin_texture_aniso(tx, ty);
            worst = fmax(worst, fabs(out[4 * (y * W + x) + 3] - fa));
            fin_between += fa > 1.01f && fa < PELT__FIN_TEXTURE_ANISO - 0.01f;
        }
    printf("  shell_fur_texture_lod, fur_texture_aniso, fin_texture_aniso: worst |GLSL - C| = %.3g, %d and %d between 1 "
           "and the most\n", worst, between, fin_between);
    CHECK(between > 50);
    CHECK(fin_between > 50);
    CHECK(worst < 1e-4);
}

/* The fetches along the footprint (fur_texture_taps in shell_lod.glsl)
 * against pelt__lod_fur_texture_taps: footprints from magnified to 64
 * texels, 1.3 to 21 to 1, at max_aniso 1 and 2 and at most 1 to 8
 * fetches. A footprint whose ratio lies within 1e-4 of a fetch count's
 * edge may round either way in float: counted, not compared. */
static void fur_texture_taps_glsl_matches_c(void)
{
    static const char main_glsl[] =
        "out vec4 o;\n"
        "void main() {\n"
        "  vec2 c = floor(gl_FragCoord.xy), dx, dy;\n"
        "  footprint(c, -2.0, 8.0, dx, dy);\n"
        "  dy *= 0.77;\n"
        "  float aniso = 1.0 + mod(c.x, 2.0), most = 1.0 + mod(c.y, 8.0), lod;\n"
        "  float n = fur_texture_taps(dx, dy, 256.0, aniso, most, lod);\n"
        "  o = vec4(n, lod, 0.0, 1.0);\n"
        "}\n";
    const char *fs[] = {pelt__shader_shell_lod, footprint_glsl, main_glsl, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    int split = 0, edge = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float dx[2], dy[2], lod;
            footprint(x, y, -2.0f, 8.0f, dx, dy);
            dy[0] *= 0.77f, dy[1] *= 0.77f; /* ratios off the counts' edges */
            float aniso = 1.0f + (float)(x % 2);
            unsigned most = 1u + (unsigned)(y % 8);
            unsigned n = pelt__lod_fur_texture_taps(dx, dy, 256.0f, aniso, most, &lod);
            float a = (dx[0] * dx[0] + dx[1] * dx[1]), b = (dy[0] * dy[0] + dy[1] * dy[1]);
            float ratio = sqrtf(fmaxf(a, b) / fmaxf(fminf(a, b), 1e-30f)) / aniso;
            if (fabsf(ratio - roundf(ratio)) < 1e-4f) {
                edge++;
                continue;
            }
            worst = fmax(worst, fabs(out[4 * (y * W + x)] - (float)n));
            worst = fmax(worst, fabs(out[4 * (y * W + x) + 1] - lod));
            split += n > 1 && n < most;
        }
    printf("  fur_texture_taps: worst |GLSL - C| = %.3g, %d split short of the most, %d on an edge\n", worst, split,
           edge);
    CHECK(split > 50);
    CHECK(edge < W * H / 20);
    CHECK(worst < 1e-4);
}

/* The hair's edge seen close (fur_edge_gain and fur_edge in shell_lod.glsl)
 * against pelt__lod_fur_edge_gain and pelt__lod_fur_edge: footprints from
 * 16 pixels a texel to 4 texels a pixel, round to 16 to 1, and coverages
 * 0 to 1 under gains 1 to 8. */
static void fur_edge_glsl_matches_c(void)
{
    static const char main_glsl[] =
        "out vec4 o;\n"
        "void main() {\n"
        "  vec2 c = floor(gl_FragCoord.xy), dx, dy;\n"
        "  footprint(c, -4.0, 6.0, dx, dy);\n"
        "  float cover = c.x / 63.0, gain = 1.0 + 7.0 * c.y / 47.0;\n"
        "  vec4 e = fur_edge(vec4(0.3, 0.6, 0.9, 1.0) * cover, gain);\n"
        "  o = vec4(fur_edge_gain(dx, dy, 256.0), e.a, e.r, e.b);\n"
        "}\n";
    const char *fs[] = {pelt__shader_shell_lod, footprint_glsl, main_glsl, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst = 0.0;
    int steepened = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float dx[2], dy[2];
            footprint(x, y, -4.0f, 6.0f, dx, dy);
            const float *o = out + 4 * (y * W + x);
            float g = pelt__lod_fur_edge_gain(dx, dy, 256.0f);
            worst = fmax(worst, fabs(o[0] - g) / g);
            float cover = (float)x / 63.0f, rgba[4] = {0.3f * cover, 0.6f * cover, 0.9f * cover, cover};
            pelt__lod_fur_edge(rgba, 1.0f + 7.0f * (float)y / 47.0f);
            worst = fmax(worst, fmax(fabs(o[1] - rgba[3]), fmax(fabs(o[2] - rgba[0]), fabs(o[3] - rgba[2]))));
            steepened += g > 1.01f;
        }
    printf("  fur_edge_gain, fur_edge: worst |GLSL - C| = %.3g, %d footprints magnified\n", worst, steepened);
    CHECK(steepened > 500);
    CHECK(worst < 1e-4);
}

static const char table_main[] =
    "uniform sampler2D u_table;\n"
    "out vec4 o;\n"
    "void main() {\n"
    "  vec2 c = floor(gl_FragCoord.xy);\n"
    "  vec3 T = vec3(1.0, 0.0, 0.0);\n"
    "  float a = -0.98 + 1.96 * c.x / 63.0, b = -0.98 + 1.96 * c.y / 47.0;\n"
    "  vec3 L = vec3(a, sqrt(1.0 - a * a), 0.0), H = vec3(b, 0.0, sqrt(1.0 - b * b));\n"
    "  o = vec4(lengyel_lookup(u_table, T, L, H), 0.0, 0.0);\n"
    "}\n";

/* Lengyel §2.4: the 32x32 table as the shaders read it (bilinear) against
 * the formula, u = T.L and v = T.H over (-0.98, 0.98), P_d 1 and P_s 20:
 * the table's own interpolation error, at most 0.02 for the specular and
 * 0.06 for the diffuse (sqrt(1 - u^2) turns steep as |u| nears 1). */
static void lengyel_table_lookup_matches_the_formula(void)
{
    enum { T = PELT__LIGHT_TABLE };
    float table[T * T * 2];
    pelt__lengyel_table(1.0f, 20.0f, table);
    GLuint tex;
    glGenTextures(1, &tex);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RG32F, T, T, 0, GL_RG, GL_FLOAT, table);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    const char *fs[] = {pelt__shader_shading, table_main, NULL};
    CHECK(gl_test_eval(gl, fs, W, H, out));
    double worst_d = 0.0, worst_s = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float u = -0.98f + 1.96f * (float)x / 63.0f, v = -0.98f + 1.96f * (float)y / 47.0f;
            float d, s;
            pelt__lengyel_lighting(u, v, 1.0f, 20.0f, &d, &s);
            const float *g = out + 4 * (y * W + x);
            worst_d = fmax(worst_d, fabs(g[0] - d));
            worst_s = fmax(worst_s, fabs(g[1] - s));
        }
    printf("  table lookup vs formula: worst diffuse error %.4f, specular %.4f\n", worst_d, worst_s);
    CHECK(worst_d < 0.06 && worst_s < 0.02);
    glDeleteTextures(1, &tex);
}

static const char hair_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec3 n, t, tip; float h, s;\n"
    "  cell_inputs(floor(gl_FragCoord.xy), n, t, tip, h, s);\n"
    "  vec3 E = normalize(tip - 0.5 * n);\n"
    "  vec3 L = normalize(vec3(0.5, 1.0, 0.8) * (s - 0.4) + n * (h - 0.5));\n"
    "  float p = 4.0 + 60.0 * s;\n"
    "  vec3 ts = shift_tangent(t, n, h - 0.5);\n"
    "  o = u_which == 0 ? hair_lobes(t, n, L, E, p)\n"
    "    : u_which == 1 ? vec4(ts, strand_specular(ts, normalize(L - E), p))\n"
    "    : vec4(hair_transmission(t, L, E, p), fur_occlusion(3.0 * s, h), 0.0, 0.0);\n"
    "}\n";

/* Scheuermann-Marschner: the four lobes, the shifted tangent and its
 * highlight, transmission and occlusion, against core/fur/shading.c. */
static void hair_model_glsl_matches_c(void)
{
    const char *names[] = {"hair_lobes", "shift_tangent, strand_specular", "hair_transmission, fur_occlusion"};
    for (int which = 0; which < 3; which++) {
        char define[64];
        snprintf(define, sizeof define, "#define u_which %d\n", which);
        const char *fs[] = {pelt__shader_shading, inputs_glsl, define, hair_main, NULL};
        CHECK(gl_test_eval(gl, fs, W, H, out));
        double worst = 0.0, largest = 0.0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                pelt_vec3 n, t, tip;
                float h, s, r[4] = {0};
                cell_inputs((float)x, (float)y, &n, &t, &tip, &h, &s);
                pelt_vec3 e = v3_norm_or(v3_sub(tip, v3_scale(n, 0.5f)), v3(0, 0, 1));
                pelt_vec3 l = v3_norm_or(v3_add(v3_scale(v3(0.5f, 1.0f, 0.8f), s - 0.4f), v3_scale(n, h - 0.5f)),
                                         v3(0, 1, 0));
                float p = 4.0f + 60.0f * s;
                pelt_vec3 ts = pelt__shift_tangent(t, n, h - 0.5f);
                if (which == 0) {
                    pelt__hair_lobes(t, n, l, e, p, r);
                } else if (which == 1) {
                    pelt_vec3 hv = v3_norm_or(v3_sub(l, e), n);
                    r[0] = ts.x, r[1] = ts.y, r[2] = ts.z, r[3] = pelt__strand_specular(ts, hv, p);
                } else {
                    r[0] = pelt__hair_transmission(t, l, e, p);
                    r[1] = pelt__fur_occlusion(3.0f * s, h);
                }
                const float *g = out + 4 * (y * W + x);
                for (int k = 0; k < 4; k++) {
                    worst = fmax(worst, fabs(g[k] - r[k]));
                    largest = fmax(largest, fabs(r[k]));
                }
            }
        printf("  %s: worst |GLSL - C| = %.3g (values up to %.3g)\n", names[which], worst, largest);
        CHECK(largest > 0.5); /* the grid reaches the lobes' peaks */
        CHECK(worst < 5e-4);
    }
}

static const char display_main[] =
    "out vec4 o;\n"
    "void main() {\n"
    "  vec2 c = floor(gl_FragCoord.xy);\n"
    "  float x = (c.x + float(W) * c.y) / float(W * H);\n"
    "  vec3 v = vec3(x, x * 6.0, x * 0.02);\n"
    "  vec3 d = srgb_decode(v.xxz);\n"
    "  o = u_which == 0 ? vec4(d, shade_decode(v.x))\n"
    "    : u_which == 1 ? vec4(srgb_encode(v), 0.0)\n"
    "    : u_which == 2 ? vec4(tone_map(v, 1.7, 0.0), 0.0)\n"
    "    : u_which == 3 ? vec4(tone_map(v, 1.7, 1.0), 0.0)\n"
    "    : u_which == 4 ? vec4(display_color(v, 0.8, 0.0), 0.0)\n"
    "    : vec4(display_color(v, 0.8, 1.0), 0.0);\n"
    "}\n";

/* Linear light: sRGB decode and encode, the tone curves and the whole
 * display mapping, against core/fur/shading.c. */
static void display_glsl_matches_c(void)
{
    const char *names[] = {"srgb_decode, shade_decode", "srgb_encode", "tone_map filmic", "tone_map none",
                           "display_color filmic", "display_color none"};
    for (int which = 0; which < 6; which++) {
        char define[96];
        snprintf(define, sizeof define, "#define u_which %d\n#define W %d\n#define H %d\n", which, W, H);
        const char *fs[] = {pelt__shader_shading, define, display_main, NULL};
        CHECK(gl_test_eval(gl, fs, W, H, out));
        double worst = 0.0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                float v0 = ((float)x + (float)W * (float)y) / (float)(W * H);
                const float v[3] = {v0, v0 * 6.0f, v0 * 0.02f};
                float r[4] = {0};
                for (int k = 0; k < 3; k++) {
                    if (which == 0) r[k] = pelt__srgb_decode(k == 2 ? v[2] : v[0]);
                    if (which == 1) r[k] = pelt__srgb_encode(v[k]);
                    if (which == 2) r[k] = pelt__tone(v[k], 1.7f, PELT_TONE_FILMIC);
                    if (which == 3) r[k] = pelt__tone(v[k], 1.7f, PELT_TONE_NONE);
                    if (which == 4) r[k] = pelt__display(v[k], 0.8f, PELT_TONE_FILMIC);
                    if (which == 5) r[k] = pelt__display(v[k], 0.8f, PELT_TONE_NONE);
                }
                if (which == 0) r[3] = pelt__shade_decode(v[0]);
                const float *g = out + 4 * (y * W + x);
                for (int k = 0; k < 4; k++) worst = fmax(worst, fabs(g[k] - r[k]));
            }
        printf("  %s: worst |GLSL - C| = %.3g\n", names[which], worst);
        CHECK(worst < 2e-4);
    }
}

int main(void)
{
    gl = gl_test_open(W, H, true);
    if (!gl) return check_skip("no OpenGL context");
    RUN(kajiya_kay_glsl_matches_c);
    RUN(wet_shine_glsl_matches_c);
    RUN(wet_color_glsl_matches_c);
    RUN(tuft_dots_glsl_match_c);
    RUN(fur_shape_glsl_matches_c);
    RUN(level_fit_normal_glsl_matches_c);
    RUN(shell_gap_glsl_matches_c);
    RUN(outline_hair_glsl_matches_c);
    RUN(clump_glsl_matches_c);
    RUN(clump_coverage_glsl_matches_c);
    RUN(clump_bundle_squeeze_glsl_matches_c);
    RUN(sub_shell_glsl_matches_c);
    RUN(sub_shell_need_glsl_matches_c);
    RUN(clump_fin_shift_glsl_matches_c);
    RUN(wet_skin_sheen_glsl_matches_c);
    RUN(ringlet_levels_glsl_matches_c);
    RUN(ringlet_tangent_glsl_matches_c);
    RUN(ringlet_dots_glsl_matches_c);
    RUN(groom_glsl_matches_c);
    RUN(inter_shadow_glsl_matches_c);
    RUN(inter_shadow_view_fade_glsl_matches_c);
    RUN(shell_lod_glsl_matches_c);
    RUN(shell_view_blend_glsl_matches_c);
    RUN(shell_lean_drift_glsl_matches_c);
    RUN(shell_stack_cos_glsl_matches_c);
    RUN(fur_texture_lod_glsl_matches_c);
    RUN(fur_texture_taps_glsl_matches_c);
    RUN(shell_edge_least_glsl_matches_c);
    RUN(fur_edge_glsl_matches_c);
    RUN(shell_overcount_glsl_matches_c);
    RUN(coverage_share_glsl_matches_c);
    RUN(lengyel_table_lookup_matches_the_formula);
    RUN(hair_model_glsl_matches_c);
    RUN(display_glsl_matches_c);
    pelt_headless_destroy(gl);
    return check_summary();
}
