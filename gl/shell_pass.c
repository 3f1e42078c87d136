/* The shells (Lengyel et al. 2001 §2.3 pass 3, Silva et al. §4): every
 * layer in ONE instanced draw, gl_InstanceID the layer, never N draws.
 * Instances are drawn in order, so layers blend inner to outer; depth
 * tested against the skin, no depth write. */
#include "gl/passes.h"

#include "gl/programs.h"

pelt_status pelt__shell_pass_create(pelt__shell_pass *p, const pelt_hooks *hooks, pelt_error *err)
{
    const char *vs[] = {pelt__shader_fur_shape, pelt__shader_shell_vs, NULL};
    const char *fs[] = {pelt__shader_shading, pelt__shader_fur_light, pelt__shader_clump,
                        pelt__shader_shell_fs, NULL};
    pelt_status st = pelt__gl_program_create("shell", vs, fs, hooks, &p->program, err);
    if (st == PELT_OK) {
        p->first_layer = glGetUniformLocation(p->program, "u_first_layer");
        p->no_inter_shadow = glGetUniformLocation(p->program, "u_no_inter_shadow");
    }
    return st;
}

void pelt__shell_pass_draw(const pelt__shell_pass *p, const pelt__pass_frame *f)
{
    /* Layers first .. first + count - 1 of N (count 0: to the outermost). */
    unsigned first = f->draw->first_layer;
    unsigned count = first >= f->layers ? 0 : f->layers - first;
    if (f->draw->layer_count && f->draw->layer_count < count) count = f->draw->layer_count;
    if (count == 0) return;
    pelt__gl_blended_hair_state();
    glUseProgram(p->program);
    glUniform1f(p->first_layer, (float)first);
    glUniform1i(p->no_inter_shadow, f->draw->no_inter_shadow ? 1 : 0);
    glDrawElementsInstanced(GL_TRIANGLES, (GLsizei)(f->mesh->triangle_count * 3), GL_UNSIGNED_INT,
                            NULL, (GLsizei)count);
    f->stats->shell_draw_calls++;
    f->stats->shell_instances += count;
    f->stats->triangles += f->mesh->triangle_count * count;
}

void pelt__shell_pass_destroy(pelt__shell_pass *p)
{
    if (p->program) glDeleteProgram(p->program);
    p->program = 0;
}
