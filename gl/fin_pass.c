/* Fins (Lengyel et al. 2001 §2.3 pass 2): after the skin, before the
 * shells, every fin in ONE instanced draw, blended, depth tested without
 * depth write. An instance is a mesh edge; its strip rises along the
 * displaced strands of the edge's two vertices, read from the vertex
 * tables (gl/gpu_mesh.c). The fade (shaders/fins.glsl) collapses fins away
 * from the silhouette in the vertex stage, so they cost no fragments. */
#include "gl/passes.h"

#include "core/base/error.h"
#include "core/fur/fur_gpu.h"
#include "gl/programs.h"

#include <string.h>

typedef struct fin_instance {
    uint32_t a, b;
    float start;
} fin_instance;

pelt_status pelt__fin_pass_create(pelt__fin_pass *p, pelt_fur *fur, const pelt_hooks *hooks,
                                  pelt_error *err)
{
    memset(p, 0, sizeof *p);
    const char *vs[] = {pelt__shader_fur_shape, pelt__shader_fins, pelt__shader_fin_vs, NULL};
    const char *fs[] = {pelt__shader_shading, pelt__shader_fur_light, pelt__shader_fin_fs, NULL};
    pelt_status st = pelt__gl_program_create("fin", vs, fs, hooks, &p->program, err);
    if (st != PELT_OK) return st;
    p->unfaded = glGetUniformLocation(p->program, "u_unfaded");

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

    /* One instance per edge. The edge records are already laid out as the
     * attributes want them (two uints, a float). */
    const pelt__fin_edge *edges = pelt__fur_gpu_fins(fur, &p->count);
    _Static_assert(sizeof(pelt__fin_edge) == sizeof(fin_instance), "fin edge layout");
    glGenVertexArrays(1, &p->vao);
    glBindVertexArray(p->vao);
    glGenBuffers(1, &p->vbo);
    glBindBuffer(GL_ARRAY_BUFFER, p->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(p->count * sizeof(fin_instance)), edges, GL_STATIC_DRAW);
    glEnableVertexAttribArray(PELT_ATTR_FIN_EDGE);
    glVertexAttribIPointer(PELT_ATTR_FIN_EDGE, 2, GL_UNSIGNED_INT, sizeof(fin_instance),
                           (const void *)offsetof(fin_instance, a));
    glVertexAttribDivisor(PELT_ATTR_FIN_EDGE, 1);
    glEnableVertexAttribArray(PELT_ATTR_FIN_START);
    glVertexAttribPointer(PELT_ATTR_FIN_START, 1, GL_FLOAT, GL_FALSE, sizeof(fin_instance),
                          (const void *)offsetof(fin_instance, start));
    glVertexAttribDivisor(PELT_ATTR_FIN_START, 1);
    glBindVertexArray(0);
    return PELT_OK;
}

void pelt__fin_pass_draw(const pelt__fin_pass *p, const pelt__pass_frame *f)
{
    if (p->count == 0) return;
    pelt__gl_blended_hair_state();
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_FIN);
    glBindTexture(GL_TEXTURE_2D, p->texture);
    glUseProgram(p->program);
    glUniform1i(p->unfaded, f->draw->fins_unfaded ? 1 : 0);
    glBindVertexArray(p->vao);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 2 * (PELT_FIN_ROWS + 1), (GLsizei)p->count);
    glBindVertexArray(f->mesh->vao);
    f->stats->fin_draw_calls++;
    f->stats->fins += p->count;
    f->stats->triangles += p->count * 2 * PELT_FIN_ROWS;
}

void pelt__fin_pass_destroy(pelt__fin_pass *p)
{
    if (p->program) glDeleteProgram(p->program);
    if (p->vbo) glDeleteBuffers(1, &p->vbo);
    if (p->vao) glDeleteVertexArrays(1, &p->vao);
    if (p->texture) glDeleteTextures(1, &p->texture);
    memset(p, 0, sizeof *p);
}
