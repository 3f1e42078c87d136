/* pelt view: the HUD. stb_easy_font (Debian libstb-dev) turns text into
 * quads; a tiny OpenGL 3.3 core program draws them over a dark panel. */
#include "apps/view.h"

#include "gl/gl_api.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wshadow"
#endif
#include <stb_easy_font.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#define HUD_MAX_QUADS 20000
#define HUD_RUN_MAX 512

struct view_hud {
    GLuint program, vao, vbo, ibo;
    GLint u_size, u_scale, u_origin;
    float *verts; /* 4 floats per vertex (x, y, z, packed colour), 4 vertices per quad */
};

static const char *vs_src =
    PELT_GLSL_VERSION
    "precision highp float;\n"
    "layout(location = 0) in vec2 pos;\n"
    "layout(location = 1) in vec4 color;\n"
    "uniform vec2 size;\n"
    "uniform vec2 origin;\n"
    "uniform float scale;\n"
    "out vec4 v_color;\n"
    "void main() {\n"
    "    vec2 p = origin + pos * scale;\n"
    "    gl_Position = vec4(p.x * 2.0 / size.x - 1.0, 1.0 - p.y * 2.0 / size.y, 0.0, 1.0);\n"
    "    v_color = color;\n"
    "}\n";

static const char *fs_src =
    PELT_GLSL_VERSION
    "precision mediump float;\n"
    "in vec4 v_color;\n"
    "out vec4 frag;\n"
    "void main() { frag = v_color; }\n";

static GLuint compile(GLenum type, const char *src, char *err, size_t err_size)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        snprintf(err, err_size, "HUD shader: %s", log);
        glDeleteShader(s);
        return 0;
    }
    return s;
}

bool view_hud_create(view_hud **out, char *err, size_t err_size)
{
    *out = NULL;
    view_hud *h = calloc(1, sizeof *h);
    if (h) h->verts = malloc((size_t)HUD_MAX_QUADS * 4 * 4 * sizeof(float));
    if (!h || !h->verts) {
        if (h) free(h);
        snprintf(err, err_size, "out of memory for the HUD");
        return false;
    }
    GLuint vs = compile(GL_VERTEX_SHADER, vs_src, err, err_size);
    GLuint fs = vs ? compile(GL_FRAGMENT_SHADER, fs_src, err, err_size) : 0;
    if (!vs || !fs) {
        if (vs) glDeleteShader(vs);
        view_hud_destroy(h);
        return false;
    }
    h->program = glCreateProgram();
    glAttachShader(h->program, vs);
    glAttachShader(h->program, fs);
    glLinkProgram(h->program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(h->program, GL_LINK_STATUS, &ok);
    if (!ok) {
        snprintf(err, err_size, "HUD program does not link");
        view_hud_destroy(h);
        return false;
    }
    h->u_size = glGetUniformLocation(h->program, "size");
    h->u_scale = glGetUniformLocation(h->program, "scale");
    h->u_origin = glGetUniformLocation(h->program, "origin");

    /* Quads as indexed triangles: 0 1 2, 0 2 3 for each. */
    GLuint *idx = malloc((size_t)HUD_MAX_QUADS * 6 * sizeof *idx);
    if (!idx) {
        snprintf(err, err_size, "out of memory for the HUD");
        view_hud_destroy(h);
        return false;
    }
    for (GLuint q = 0; q < HUD_MAX_QUADS; q++) {
        GLuint b = 4 * q, *o = idx + 6 * q;
        o[0] = b, o[1] = b + 1, o[2] = b + 2, o[3] = b, o[4] = b + 2, o[5] = b + 3;
    }
    glGenVertexArrays(1, &h->vao);
    glBindVertexArray(h->vao);
    glGenBuffers(1, &h->ibo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, h->ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)HUD_MAX_QUADS * 6 * sizeof *idx, idx,
                 GL_STATIC_DRAW);
    free(idx);
    glGenBuffers(1, &h->vbo);
    glBindBuffer(GL_ARRAY_BUFFER, h->vbo);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 16, (const void *)0);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(1, 4, GL_UNSIGNED_BYTE, GL_TRUE, 16, (const void *)12);
    glEnableVertexAttribArray(1);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    *out = h;
    return true;
}

void view_hud_destroy(view_hud *h)
{
    if (!h) return;
    if (h->program) glDeleteProgram(h->program);
    if (h->vao) glDeleteVertexArrays(1, &h->vao);
    if (h->vbo) glDeleteBuffers(1, &h->vbo);
    if (h->ibo) glDeleteBuffers(1, &h->ibo);
    free(h->verts);
    free(h);
}

static void quad(float *v, float x0, float y0, float x1, float y1, const uint8_t c[4])
{
    float xs[4] = {x0, x1, x1, x0}, ys[4] = {y0, y0, y1, y1};
    for (int j = 0; j < 4; j++) {
        v[4 * j] = xs[j];
        v[4 * j + 1] = ys[j];
        v[4 * j + 2] = 0.0f;
        memcpy(&v[4 * j + 3], c, 4);
    }
}

/* Draws the first `quads` quads of h->verts, placed at origin + scale * p. */
static void draw_quads(view_hud *h, size_t quads, float ox, float oy, float scale, unsigned width,
                       unsigned height)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glViewport(0, 0, (GLsizei)width, (GLsizei)height);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(h->program);
    glUniform2f(h->u_size, (float)width, (float)height);
    glUniform2f(h->u_origin, ox, oy);
    glUniform1f(h->u_scale, scale);
    glBindVertexArray(h->vao);
    glBindBuffer(GL_ARRAY_BUFFER, h->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(quads * 64), h->verts, GL_STREAM_DRAW);
    glDrawElements(GL_TRIANGLES, (GLsizei)(quads * 6), GL_UNSIGNED_INT, NULL);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glUseProgram(0);
    glBlendFunc(GL_ONE, GL_ZERO);
    glDisable(GL_BLEND);
}

void view_hud_text(view_hud *h, const char *text, float x, float y, float scale, unsigned width,
                   unsigned height)
{
    static const uint8_t colors[5][4] = {
        {235, 235, 235, 255}, {235, 235, 235, 255}, {255, 80, 70, 255}, {160, 160, 170, 255},
        {255, 220, 90, 255}};
    static const uint8_t panel[4] = {0, 0, 0, 170};
    size_t quads = 1; /* the panel first */
    float lx = 0.0f, ly = 0.0f, max_x = 0.0f;
    const uint8_t *color = colors[0];
    char run[HUD_RUN_MAX + 1];
    size_t n = 0;
    for (const char *p = text;; p++) {
        unsigned char ch = (unsigned char)*p;
        if (ch == '\0' || ch == '\n' || (ch >= 1 && ch <= 4) || n == HUD_RUN_MAX) {
            run[n] = '\0';
            if (n) {
                size_t room = (HUD_MAX_QUADS - quads) * 64;
                int q = stb_easy_font_print(lx, ly, run, (unsigned char *)color,
                                            h->verts + quads * 16, (int)room);
                quads += (size_t)q;
                lx += (float)stb_easy_font_width(run);
                if (lx > max_x) max_x = lx;
            }
            n = 0;
            if (ch == '\0') break;
            if (ch == '\n') lx = 0.0f, ly += 12.0f;
            else if (ch <= 4) color = colors[ch];
            else run[n++] = ch < 32 || ch > 126 ? '?' : (char)ch; /* a full run, flushed */
            continue;
        }
        run[n++] = ch < 32 || ch > 126 ? '?' : (char)ch; /* stb_easy_font knows 32..126 */
    }
    float pad = 4.0f;
    quad(h->verts, -pad, -pad, max_x + pad, ly + 12.0f + pad - 2.0f, panel);

    draw_quads(h, quads, x + pad * scale, y + pad * scale, scale, width, height);
}

void view_hud_ring(view_hud *h, float cx, float cy, float r, unsigned width, unsigned height)
{
    static const uint8_t dark[4] = {0, 0, 0, 140}, light[4] = {255, 255, 255, 200};
    enum { SEGMENTS = 72 };
    size_t quads = 0;
    for (int pass = 0; pass < 2; pass++) /* a dark ring under a light one: seen on any fur */
        for (int i = 0; i < SEGMENTS; i++) {
            float a0 = 6.2831853f * (float)i / SEGMENTS, a1 = 6.2831853f * (float)(i + 1) / SEGMENTS;
            float w = pass == 0 ? 2.0f : 0.75f, rr[2] = {r - w, r + w};
            float *v = h->verts + quads * 16;
            float xs[4] = {cx + rr[0] * cosf(a0), cx + rr[1] * cosf(a0), cx + rr[1] * cosf(a1),
                           cx + rr[0] * cosf(a1)};
            float ys[4] = {cy + rr[0] * sinf(a0), cy + rr[1] * sinf(a0), cy + rr[1] * sinf(a1),
                           cy + rr[0] * sinf(a1)};
            for (int j = 0; j < 4; j++) {
                v[4 * j] = xs[j];
                v[4 * j + 1] = ys[j];
                v[4 * j + 2] = 0.0f;
                memcpy(&v[4 * j + 3], pass == 0 ? dark : light, 4);
            }
            quads++;
        }
    draw_quads(h, quads, 0.0f, 0.0f, 1.0f, width, height);
}
