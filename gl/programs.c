/* GL programs from the embedded .glsl pieces: every stage starts with the
 * version header and the binding table, so C and GLSL read one list of
 * locations, units and binding points (shaders/bindings.glsl). */
#include "gl/programs.h"

#include "core/base/error.h"
#include "gl/gpu.h"

/* GLSL 3.30 core on the desktop, GLSL ES 3.00 in the browser (gl/gl_api.h):
 * the shaders are written to compile as both. */
static const char version_header[] =
    PELT_GLSL_VERSION
#if PELT_GL_ES
    "precision highp sampler2DArray;\n"
    "precision highp usampler2D;\n"
    "precision highp sampler2D;\n"
#endif
    "precision highp float;\n"
    "precision highp int;\n";

enum { MAX_PARTS = 12 };

static GLuint compile(GLenum stage, const char *const *parts, const char *what, pelt_error *err)
{
    const char *sources[2 + MAX_PARTS];
    int n = 0;
    sources[n++] = version_header;
    sources[n++] = pelt__shader_bindings;
    for (int i = 0; i < MAX_PARTS && parts[i]; i++) sources[n++] = parts[i];
    GLuint s = glCreateShader(stage);
    glShaderSource(s, n, sources, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[400];
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        pelt__fail(err, PELT_ERR_GL, "%s %s shader does not compile: %s", what,
                   stage == GL_VERTEX_SHADER ? "vertex" : "fragment", log);
        glDeleteShader(s);
        return 0;
    }
    return s;
}

pelt_status pelt__program_build(const char *what, const char *const *vertex_parts,
                                const char *const *fragment_parts, GLuint *out,
                                pelt_error *err)
{
    *out = 0;
    GLuint vs = compile(GL_VERTEX_SHADER, vertex_parts, what, err);
    if (!vs) return PELT_ERR_GL;
    GLuint fs = compile(GL_FRAGMENT_SHADER, fragment_parts, what, err);
    if (!fs) {
        glDeleteShader(vs);
        return PELT_ERR_GL;
    }
    GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glLinkProgram(p);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[400];
        glGetProgramInfoLog(p, sizeof log, NULL, log);
        glDeleteProgram(p);
        return pelt__fail(err, PELT_ERR_GL, "%s program does not link: %s", what, log);
    }
    *out = p;
    return PELT_OK;
}

/* parts with the uniform blocks in front, into room for MAX_PARTS + 1. */
static void with_blocks(const char *const *parts, const char **out)
{
    int n = 0;
    out[n++] = pelt__shader_blocks;
    for (int i = 0; parts[i] && n < MAX_PARTS; i++) out[n++] = parts[i];
    out[n] = NULL;
}

pelt_status pelt__gl_program_create(const char *what, const char *const *vertex_parts,
                                    const char *const *fragment_parts, const pelt_hooks *hooks,
                                    GLuint *out, pelt_error *err)
{
    const char *vs[MAX_PARTS + 1], *fs[MAX_PARTS + 1];
    with_blocks(vertex_parts, vs);
    with_blocks(fragment_parts, fs);
    pelt_error e = {0};
    pelt_status st = pelt__program_build(what, vs, fs, out, &e);
    if (st != PELT_OK) {
        pelt__log(&hooks->logger, PELT_LOG_ERROR, "%s", e.message);
        if (err) *err = e;
        return st;
    }
    static const struct { const char *name; GLuint binding; } blocks[] = {
        {"pelt_frame_block", PELT_BLOCK_FRAME}, {"pelt_fur_block", PELT_BLOCK_FUR}};
    static const struct { const char *name; GLint unit; } samplers[] = {
        {"u_fur", PELT_UNIT_FUR},           {"u_color_tex", PELT_UNIT_COLOR},
        {"u_mask", PELT_UNIT_MASK},         {"u_fin_tex", PELT_UNIT_FIN},
        {"u_light_table", PELT_UNIT_LIGHT_TABLE}, {"u_fin_edges", PELT_UNIT_FIN_EDGES},
        {"u_fin_vertices", PELT_UNIT_FIN_VERTICES}, {"u_shadow_depth", PELT_UNIT_SHADOW_DEPTH},
        {"u_shadow_opacity", PELT_UNIT_SHADOW_OPACITY}, {"u_bones", PELT_UNIT_BONES}};
    for (size_t i = 0; i < sizeof blocks / sizeof blocks[0]; i++) {
        GLuint index = glGetUniformBlockIndex(*out, blocks[i].name);
        if (index != GL_INVALID_INDEX) glUniformBlockBinding(*out, index, blocks[i].binding);
    }
    glUseProgram(*out);
    for (size_t i = 0; i < sizeof samplers / sizeof samplers[0]; i++) {
        GLint loc = glGetUniformLocation(*out, samplers[i].name);
        if (loc >= 0) glUniform1i(loc, samplers[i].unit);
    }
    return PELT_OK;
}
