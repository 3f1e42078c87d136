/* The opaque skin (Lengyel et al. 2001 §2.3, pass 1): the full mesh with
 * depth write, coloured by the innermost fur slice, so shells blend over
 * skin and never over the background behind the body. */
#include "gl/passes.h"

#include "gl/programs.h"

#include <string.h>

static pelt_status build(pelt__skin_pass *p, unsigned features, pelt_error *err)
{
    char defines[PELT__FEATURE_DEFINES_MAX];
    pelt__shell_feature_defines(features & PELT__SKIN_FEATURES, defines);
    const char *vs[] = {pelt__shader_skin_vs, NULL};
    const char *fs[] = {defines, pelt__shader_shading, pelt__shader_shadow_map, pelt__shader_clump,
                        pelt__shader_skin_fs, NULL};
    pelt_status st = pelt__gl_program_create("skin", vs, fs, &p->hooks, &p->variants[features], err);
    if (st != PELT_OK) p->failed[features] = true;
    return st;
}

pelt_status pelt__skin_pass_create(pelt__skin_pass *p, const pelt_hooks *hooks, pelt_error *err)
{
    memset(p, 0, sizeof *p);
    p->hooks = *hooks;
    return build(p, PELT__SKIN_FEATURES, err);
}

void pelt__skin_pass_draw(pelt__skin_pass *p, const pelt__pass_frame *f)
{
    unsigned features = f->shell_features & PELT__SKIN_FEATURES;
    if (!p->variants[features] && !p->failed[features]) build(p, features, NULL);
    if (!p->variants[features]) features = PELT__SKIN_FEATURES;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    if (f->lod.cull_skin) { /* its own front faces would hide the rest */
        glEnable(GL_CULL_FACE);
        glFrontFace(f->lod.front_cw ? GL_CW : GL_CCW);
    } else {
        glDisable(GL_CULL_FACE);
    }
    glUseProgram(p->variants[features]);
    glDrawElements(GL_TRIANGLES, (GLsizei)(f->mesh->triangle_count * 3), GL_UNSIGNED_INT, NULL);
    glFrontFace(GL_CCW);
    f->stats->skin_draw_calls++;
    f->stats->triangles += f->mesh->triangle_count;
}

void pelt__skin_pass_destroy(pelt__skin_pass *p)
{
    for (unsigned k = 0; k <= PELT__SKIN_FEATURES; k++)
        if (p->variants[k]) glDeleteProgram(p->variants[k]);
    memset(p->variants, 0, sizeof p->variants);
}
