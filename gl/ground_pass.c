/* The ground (pelt/shadow.h): a disc under the mesh that receives the
 * light's shadows, drawn before the skin with depth write so the fur
 * stands on it. One quad from gl_VertexID: no buffers of its own. */
#include "gl/passes.h"

#include "gl/programs.h"

#include "core/fur/fur_gpu.h"

pelt_status pelt__ground_pass_create(pelt__ground_pass *p, const pelt_hooks *hooks, pelt_error *err)
{
    const char *vs[] = {pelt__shader_ground_vs, NULL};
    const char *fs[] = {pelt__shader_shading, pelt__shader_shadow_map, pelt__shader_ground_fs, NULL};
    pelt_status st = pelt__gl_program_create("ground", vs, fs, hooks, &p->program, err);
    if (st != PELT_OK) return st;
    p->ground = glGetUniformLocation(p->program, "u_ground");
    p->color = glGetUniformLocation(p->program, "u_ground_color");
    return PELT_OK;
}

void pelt__ground_pass_draw(const pelt__ground_pass *p, const pelt__pass_frame *f, const float disc[4],
                            const float color[3])
{
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    /* The faded rim blends over the background like the hair does. */
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(p->program);
    glUniform4fv(p->ground, 1, disc);
    /* The ground's colour is sRGB; it is lit in linear light. */
    float linear[3];
    pelt__fur_gpu_linear_rgb(color, linear);
    glUniform3fv(p->color, 1, linear);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    f->stats->ground_draw_calls++;
    f->stats->triangles += 2;
}

void pelt__ground_pass_destroy(pelt__ground_pass *p)
{
    if (p->program) glDeleteProgram(p->program);
    p->program = 0;
}
