#include "gl/programs.h"

#include "core/base/error.h"

#include <stdlib.h>

static const char version_header[] =
    "#version 330 core\n"
    "precision highp float;\n"
    "precision highp int;\n";

static GLuint compile(GLenum stage, const char *const *parts, const char *what, pelt_error *err)
{
    const char *sources[16];
    int n = 0;
    sources[n++] = version_header;
    for (int i = 0; parts[i] && n < 16; i++) sources[n++] = parts[i];
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
