/* Fins (Lengyel et al. 2001 §2.3 pass 2): after the skin, before the
 * shells, every fin in ONE instanced draw, blended, depth tested without
 * depth write. An instance is a mesh edge; its strip rises along the
 * displaced strands of the edge's two vertices, read from the vertex
 * tables (gl/gpu_mesh.c). The fade (shaders/fins.glsl) collapses fins away
 * from the silhouette in the vertex stage, so they cost no fragments. */
#include "gl/passes.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/vec.h"
#include "core/fur/fur_gpu.h"
#include "gl/programs.h"

#include <string.h>

typedef struct fin_instance {
    uint32_t a, b;
    float start;
} fin_instance;

/* A fin program with `features` (PELT__FIN_FEATURES bits) compiled in, as
 * the shells' variants (gl/shell_pass.c); PELT__FIN_FEATURES is generic. */
static pelt_status build(pelt__fin_pass *p, unsigned features, pelt_error *err)
{
    static const struct { unsigned bit; const char *define; } defines[] = {
        {PELT__SHELL_WET, "#define PELT_WET 1\n"},
        {PELT__SHELL_COLOR_TEXTURE, "#define PELT_COLOR_TEXTURE 1\n"},
        {PELT__SHELL_KAJIYA_KAY, "#define PELT_SHADING_KK 1\n"},
        {PELT__SHELL_LIGHT_TABLE, "#define PELT_SHADING_TABLE 1\n"},
    };
    const char *fs[8];
    int n = 0;
    for (size_t k = 0; k < sizeof defines / sizeof defines[0]; k++)
        if (features & defines[k].bit) fs[n++] = defines[k].define;
    fs[n++] = pelt__shader_shading;
    fs[n++] = pelt__shader_fur_light;
    fs[n++] = pelt__shader_fin_fs;
    fs[n] = NULL;
    const char *vs[] = {pelt__shader_fur_shape, pelt__shader_fins, pelt__shader_fin_vs, NULL};
    pelt_status st = pelt__gl_program_create("fin", vs, fs, &p->hooks, &p->variants[features], err);
    if (st != PELT_OK) {
        p->failed[features] = true;
        return st;
    }
    p->unfaded[features] = glGetUniformLocation(p->variants[features], "u_unfaded");
    return PELT_OK;
}

pelt_status pelt__fin_pass_create(pelt__fin_pass *p, pelt_fur *fur, const pelt_hooks *hooks,
                                  pelt_error *err)
{
    memset(p, 0, sizeof *p);
    p->hooks = *hooks;
    pelt_status st = build(p, PELT__FIN_FEATURES, err);
    if (st != PELT_OK) return st;

    /* The fin texture: repeats along the fin, clamped at root and tip. */
    pelt__gl_unpack_defaults();
    unsigned w, h;
    const uint8_t *texels = pelt__fur_gpu_fin_texture(fur, &w, &h);
    glGenTextures(1, &p->texture);
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_FIN);
    glBindTexture(GL_TEXTURE_2D, p->texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, (GLsizei)w, (GLsizei)h, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glGenerateMipmap(GL_TEXTURE_2D);

    /* One instance per edge, every level of detail's fins one after the
     * other (core/fur/lod.h). The edge records are already laid out as the
     * attributes want them (two uints, a float). */
    _Static_assert(sizeof(pelt__fin_edge) == sizeof(fin_instance), "fin edge layout");
    const pelt__lod_chain *lod = pelt__fur_gpu_lod(fur);
    for (unsigned k = 0; k < lod->count; k++) {
        p->level_first[k] = p->count;
        p->level_count[k] = lod->levels[k].fin_count;
        p->count += lod->levels[k].fin_count;
    }
    glGenVertexArrays(1, &p->vao);
    glBindVertexArray(p->vao);
    glGenBuffers(1, &p->vbo);
    glBindBuffer(GL_ARRAY_BUFFER, p->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(p->count * sizeof(fin_instance)), NULL, GL_STATIC_DRAW);
    for (unsigned k = 0; k < lod->count; k++)
        glBufferSubData(GL_ARRAY_BUFFER, (GLintptr)(p->level_first[k] * sizeof(fin_instance)),
                        (GLsizeiptr)(p->level_count[k] * sizeof(fin_instance)), lod->levels[k].fins);
    size_t most = 0;
    for (unsigned k = 0; k < lod->count; k++)
        if (lod->levels[k].fin_count > most) most = lod->levels[k].fin_count;
    p->lod = lod;
    p->alloc = hooks->allocator;
    p->staging = pelt__alloc(&p->alloc, (most ? most : 1) * sizeof *p->staging);
    if (!p->staging) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for %zu fins", most);
    glGenBuffers(1, &p->vbo_facing);
    glBindBuffer(GL_ARRAY_BUFFER, p->vbo_facing);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)((most ? most : 1) * sizeof(fin_instance)), NULL, GL_STREAM_DRAW);
    glEnableVertexAttribArray(PELT_ATTR_FIN_EDGE);
    glVertexAttribDivisor(PELT_ATTR_FIN_EDGE, 1);
    glEnableVertexAttribArray(PELT_ATTR_FIN_START);
    glVertexAttribDivisor(PELT_ATTR_FIN_START, 1);
    glBindVertexArray(0);
    return PELT_OK;
}

/* Points the instance attributes at one level's fins: GL 3.3 has no base
 * instance, so the level's offset goes into the pointers. */
static void point_at(GLuint vbo, size_t first)
{
    size_t at = first * sizeof(fin_instance);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glVertexAttribIPointer(PELT_ATTR_FIN_EDGE, 2, GL_UNSIGNED_INT, sizeof(fin_instance),
                           (const void *)(at + offsetof(fin_instance, a)));
    glVertexAttribPointer(PELT_ATTR_FIN_START, 1, GL_FLOAT, GL_FALSE, sizeof(fin_instance),
                          (const void *)(at + offsetof(fin_instance, start)));
}

void pelt__fin_pass_draw(pelt__fin_pass *p, const pelt__pass_frame *f)
{
    unsigned level = f->lod.full_mesh ? 0 : f->lod.mesh_level;
    size_t count = p->level_count[level];
    if (count == 0) return;
    GLuint source = p->vbo;
    size_t first = p->level_first[level];
    if (!f->draw->fins_unfaded) {
        /* The view direction in mesh space: the transpose of the model's
         * rotation (exact for rotations and uniform scale; the margin
         * covers mild non-uniform scale). */
        const float *m = f->view->model, *v = f->view->view;
        pelt_vec3 fwd = v3(-v[2], -v[6], -v[10]);
        pelt_vec3 local = v3(m[0] * fwd.x + m[1] * fwd.y + m[2] * fwd.z, m[4] * fwd.x + m[5] * fwd.y + m[6] * fwd.z,
                             m[8] * fwd.x + m[9] * fwd.y + m[10] * fwd.z);
        local = v3_norm_or(local, v3(0.0f, 0.0f, -1.0f));
        const pelt__lod_level *l = &p->lod->levels[level];
        count = pelt__fins_facing(l->fins, l->fin_normals, l->fin_count, local, 0.05f, p->staging);
        if (count == 0) return;
        glBindBuffer(GL_ARRAY_BUFFER, p->vbo_facing);
        glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(count * sizeof(fin_instance)), p->staging);
        source = p->vbo_facing;
        first = 0;
    }
    pelt__gl_blended_hair_state();
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_FIN);
    glBindTexture(GL_TEXTURE_2D, p->texture);
    unsigned features = f->shell_features & PELT__FIN_FEATURES;
    if (!p->variants[features] && !p->failed[features]) build(p, features, NULL);
    if (!p->variants[features]) features = PELT__FIN_FEATURES;
    glUseProgram(p->variants[features]);
    glUniform1i(p->unfaded[features], f->draw->fins_unfaded ? 1 : 0);
    glBindVertexArray(p->vao);
    point_at(source, first);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 2 * (PELT_FIN_ROWS + 1), (GLsizei)count);
    glBindVertexArray(f->mesh->vao);
    f->stats->fin_draw_calls++;
    f->stats->fins += count;
    f->stats->triangles += count * 2 * PELT_FIN_ROWS;
}

void pelt__fin_pass_destroy(pelt__fin_pass *p)
{
    for (int k = 0; k < PELT__SHELL_VARIANTS; k++)
        if (p->variants[k]) glDeleteProgram(p->variants[k]);
    if (p->vbo) glDeleteBuffers(1, &p->vbo);
    if (p->vbo_facing) glDeleteBuffers(1, &p->vbo_facing);
    pelt__free(&p->alloc, p->staging);
    if (p->vao) glDeleteVertexArrays(1, &p->vao);
    if (p->texture) glDeleteTextures(1, &p->texture);
    memset(p, 0, sizeof *p);
}
