/* The light's maps (docs/shadows.md; Yuksel and Keyser 2008 deep opacity
 * maps): first the skin's depth from the light, then every shell of a
 * coarse level in one instanced draw, each fragment adding its hair's
 * -ln(1 - alpha) to the slices at and behind its depth in the slab in
 * front of the skin (additive blending, so order does not matter). */
#include "gl/passes.h"

#include "core/base/error.h"
#include "gl/programs.h"

#include <string.h>

pelt_status pelt__shadow_pass_create(pelt__shadow_pass *p, const pelt_hooks *hooks, pelt_error *err)
{
    memset(p, 0, sizeof *p);
    const char *vs[] = {pelt__shader_shadow_map, pelt__shader_shadow_depth_vs, NULL};
    const char *fs[] = {pelt__shader_shadow_depth_fs, NULL};
    return pelt__gl_program_create("shadow depth", vs, fs, hooks, &p->depth_program, err);
}

static void release_maps(pelt__shadow_pass *p)
{
    GLuint fbos[2] = {p->depth_fbo, p->opacity_fbo}, textures[2] = {p->depth, p->opacity};
    glDeleteFramebuffers(2, fbos);
    glDeleteTextures(2, textures);
    p->depth_fbo = p->opacity_fbo = p->depth = p->opacity = 0;
    p->size = 0;
}

pelt_status pelt__shadow_pass_resize(pelt__shadow_pass *p, unsigned size, pelt_error *err)
{
    if (p->size == size) return PELT_OK;
    release_maps(p);
    GLint draw_fbo = 0, read_fbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fbo);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fbo);
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_SHADOW_DEPTH);
    glGenTextures(1, &p->depth);
    glBindTexture(GL_TEXTURE_2D, p->depth);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, (GLsizei)size, (GLsizei)size, 0, GL_DEPTH_COMPONENT,
                 GL_UNSIGNED_INT, NULL);
    /* Nearest: the receivers compare depths themselves, tap by tap. */
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_SHADOW_OPACITY);
    glGenTextures(1, &p->opacity);
    glBindTexture(GL_TEXTURE_2D_ARRAY, p->opacity);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA16F, (GLsizei)size, (GLsizei)size, 2, 0, GL_RGBA, GL_HALF_FLOAT,
                 NULL);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, 0);

    glGenFramebuffers(1, &p->depth_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, p->depth_fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, p->depth, 0);
    static const GLenum none = GL_NONE;
    glDrawBuffers(1, &none);
    glReadBuffer(GL_NONE);
    bool ok = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glGenFramebuffers(1, &p->opacity_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, p->opacity_fbo);
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, p->opacity, 0, 0);
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, p->opacity, 0, 1);
    static const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, both);
    ok = ok && glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)draw_fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)read_fbo);
    if (!ok) {
        release_maps(p);
        return pelt__fail(err, PELT_ERR_GL, "the shadow maps' framebuffers are incomplete (%ux%u)", size, size);
    }
    p->size = size;
    return PELT_OK;
}

/* What pelt/render.h promises to leave as found. */
typedef struct saved_state {
    GLint draw_fbo, read_fbo, viewport[4];
    GLboolean mask[4], scissor;
} saved_state;

/* Saves the caller's state, draws the skin's depth from the light, and
 * leaves the opacity slices bound, cleared, with additive blending: what
 * the fur adds comes next. */
static void begin_maps(const pelt__shadow_pass *p, const pelt__pass_frame *f, const pelt__shadow_frame *sf,
                       saved_state *s)
{
    s->scissor = glIsEnabled(GL_SCISSOR_TEST);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_fbo);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s->read_fbo);
    glGetIntegerv(GL_VIEWPORT, s->viewport);
    glGetBooleanv(GL_COLOR_WRITEMASK, s->mask);
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glViewport(0, 0, (GLsizei)p->size, (GLsizei)p->size);

    const pelt__gpu_mesh *m = f->mesh;
    size_t triangles = sf->full_mesh ? m->triangle_count : m->level_triangles[sf->mesh_level];
    const void *offset = (const void *)(sf->full_mesh ? 0 : m->level_offset[sf->mesh_level]);
    /* 1. The skin's depth. The maps are unbound while they are drawn. */
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_SHADOW_OPACITY);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_SHADOW_DEPTH);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, p->depth_fbo);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    static const float far_depth = 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &far_depth);
    glUseProgram(p->depth_program);
    glDrawElements(GL_TRIANGLES, (GLsizei)(triangles * 3), GL_UNSIGNED_INT, offset);
    f->stats->shadow_draw_calls++;
    f->stats->triangles += triangles;

    /* 2. The fur's opacity, added up: order does not matter. */
    glBindTexture(GL_TEXTURE_2D, p->depth);
    glBindFramebuffer(GL_FRAMEBUFFER, p->opacity_fbo);
    static const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearBufferfv(GL_COLOR, 0, zero);
    glClearBufferfv(GL_COLOR, 1, zero);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
}

static void end_maps(const saved_state *s)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->draw_fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)s->read_fbo);
    glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    glColorMask(s->mask[0], s->mask[1], s->mask[2], s->mask[3]);
    if (s->scissor) glEnable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    glDepthMask(GL_TRUE);
}

void pelt__shadow_pass_draw(const pelt__shadow_pass *p, pelt__shell_pass *shells, const pelt__pass_frame *f,
                            const pelt__shadow_frame *sf)
{
    if (!p->size) return;
    saved_state s;
    begin_maps(p, f, sf, &s);
    /* Every shell of the level in one draw. */
    const pelt__shell_program *sp = pelt__shell_pass_program(shells, sf->features | PELT__SHELL_LIGHT_PASS);
    if (sp) {
        const pelt__gpu_mesh *m = f->mesh;
        size_t triangles = sf->full_mesh ? m->triangle_count : m->level_triangles[sf->mesh_level];
        const void *offset = (const void *)(sf->full_mesh ? 0 : m->level_offset[sf->mesh_level]);
        pelt__gpu_mesh_point_fit(m, sf->full_mesh, sf->mesh_level);
        float span[4], next[2];
        unsigned count;
        pelt__lod_shell_uniforms(f->layers, sf->shell_level, 0.0f, 0, span, next, &count);
        if (sf->cull) {
            glEnable(GL_CULL_FACE);
            glFrontFace(sf->front_cw ? GL_CW : GL_CCW);
        }
        glUseProgram(sp->program);
        glUniform4fv(sp->shells, 1, span);
        glUniform2fv(sp->shells_next, 1, next);
        glUniform1i(sp->no_inter_shadow, 1);
        glDrawElementsInstanced(GL_TRIANGLES, (GLsizei)(triangles * 3), GL_UNSIGNED_INT, offset, (GLsizei)count);
        glDisable(GL_CULL_FACE);
        glFrontFace(GL_CCW);
        f->stats->shadow_draw_calls++;
        f->stats->triangles += triangles * count;
    }
    end_maps(&s);
}

void pelt__shadow_pass_draw_strands(const pelt__shadow_pass *p, pelt__strands_pass *strands,
                                    const pelt__pass_frame *f, const pelt__shadow_frame *sf)
{
    if (!p->size) return;
    saved_state s;
    begin_maps(p, f, sf, &s);
    pelt__strands_pass_draw_light(strands, f);
    end_maps(&s);
}

void pelt__shadow_pass_bind(const pelt__shadow_pass *p)
{
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_SHADOW_DEPTH);
    glBindTexture(GL_TEXTURE_2D, p->depth);
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_SHADOW_OPACITY);
    glBindTexture(GL_TEXTURE_2D_ARRAY, p->opacity);
    glActiveTexture(GL_TEXTURE0);
}

void pelt__shadow_pass_destroy(pelt__shadow_pass *p)
{
    release_maps(p);
    if (p->depth_program) glDeleteProgram(p->depth_program);
    memset(p, 0, sizeof *p);
}
