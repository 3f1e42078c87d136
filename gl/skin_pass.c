/* The opaque skin (Lengyel et al. 2001 §2.3, pass 1): the full mesh with
 * depth write, coloured by the innermost fur slice, so shells blend over
 * skin and never over the background behind the body. */
#include "gl/passes.h"

#include "gl/programs.h"

pelt_status pelt__skin_pass_create(pelt__skin_pass *p, const pelt_hooks *hooks, pelt_error *err)
{
    const char *vs[] = {pelt__shader_skin_vs, NULL};
    const char *fs[] = {pelt__shader_shading, pelt__shader_shadow_map, pelt__shader_skin_fs, NULL};
    return pelt__gl_program_create("skin", vs, fs, hooks, &p->program, err);
}

void pelt__skin_pass_draw(const pelt__skin_pass *p, const pelt__pass_frame *f)
{
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glUseProgram(p->program);
    glDrawElements(GL_TRIANGLES, (GLsizei)(f->mesh->triangle_count * 3), GL_UNSIGNED_INT, NULL);
    f->stats->skin_draw_calls++;
    f->stats->triangles += f->mesh->triangle_count;
}

void pelt__skin_pass_destroy(pelt__skin_pass *p)
{
    if (p->program) glDeleteProgram(p->program);
    p->program = 0;
}
