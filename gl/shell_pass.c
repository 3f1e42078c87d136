/* The shells (Lengyel et al. 2001 §2.3 pass 3, Silva et al. §4): every
 * layer in ONE instanced draw, gl_InstanceID the layer, never N draws.
 * Instances are drawn in order, so layers blend inner to outer; depth
 * tested against the skin, no depth write. */
#include "gl/passes.h"

#include "gl/programs.h"

#include <stdio.h>
#include <string.h>

static const char *const feature_defines[] = {"PELT_WET", "PELT_INTER_SHADOW", "PELT_LOD_BLEND",
                                              "PELT_COLOR_TEXTURE", "PELT_SHADING_KK", "PELT_SHADING_TABLE",
                                              "PELT_SHADOW_MAP", "PELT_RINGLETS", "PELT_FUR_TAPS", "PELT_LIGHT_PASS",
                                              "PELT_GPU_SKIN", "PELT_NO_GAP", "PELT_TUFT_BASE"};

void pelt__shell_feature_defines(unsigned features, char out[PELT__FEATURE_DEFINES_MAX])
{
    size_t at = 0;
    out[0] = '\0';
    for (unsigned k = 0; k < sizeof feature_defines / sizeof feature_defines[0]; k++)
        if (features & (1u << k))
            at += (size_t)snprintf(out + at, PELT__FEATURE_DEFINES_MAX - at, "#define %s 1\n", feature_defines[k]);
}

static pelt_status build(pelt__shell_program *sp, unsigned features, bool floor, const pelt_hooks *hooks,
                         pelt_error *err)
{
    char defines[PELT__FEATURE_DEFINES_MAX];
    pelt__shell_feature_defines(features, defines);
    const char *vs[] = {defines,          pelt__shader_shading,   pelt__shader_shadow_map,
                        pelt__shader_fur_light, pelt__shader_fur_shape, pelt__shader_own_light,
                        pelt__shader_clump, pelt__shader_shell_lod, pelt__shader_skin_blend,
                        pelt__shader_shell_vs, NULL};
    const char *fs[] = {defines,           pelt__shader_shading, pelt__shader_shadow_map, pelt__shader_fur_shape,
                        pelt__shader_own_light, pelt__shader_clump, pelt__shader_shell_lod, pelt__shader_shell_fs,
                        NULL};
    const char *floor_fs[] = {pelt__shader_shell_floor_fs, NULL};
    pelt_status st = pelt__gl_program_create(floor ? "shell floor" : "shell", vs, floor ? floor_fs : fs, hooks,
                                             &sp->program, err);
    if (st != PELT_OK) {
        sp->failed = true;
        return st;
    }
    sp->shells = glGetUniformLocation(sp->program, "u_shells");
    sp->shells_next = glGetUniformLocation(sp->program, "u_shells_next");
    sp->shell_view = glGetUniformLocation(sp->program, "u_shell_view");
    sp->back_reach = glGetUniformLocation(sp->program, "u_back_reach");
    sp->instance_base = glGetUniformLocation(sp->program, "u_instance_base");
    sp->no_inter_shadow = glGetUniformLocation(sp->program, "u_no_inter_shadow");
    sp->sub_shells = glGetUniformLocation(sp->program, "u_sub_shells");
    sp->sub_view = glGetUniformLocation(sp->program, "u_sub_view");
    sp->no_overcount = glGetUniformLocation(sp->program, "u_no_overcount");
    sp->fur_taps = glGetUniformLocation(sp->program, "u_fur_taps");
    sp->fur_aniso = glGetUniformLocation(sp->program, "u_fur_aniso");
    sp->edge_depth = glGetUniformLocation(sp->program, "u_edge_depth");
    return PELT_OK;
}

pelt_status pelt__shell_pass_create(pelt__shell_pass *p, const pelt_hooks *hooks, pelt_error *err)
{
    memset(p, 0, sizeof *p);
    p->hooks = *hooks;
    pelt_status st = build(&p->variants[PELT__SHELL_GENERIC], PELT__SHELL_GENERIC, false, hooks, err);
    if (st == PELT_OK) st = build(&p->floor, 0, true, hooks, err);
    return st;
}

/* One instanced draw of `triangles` from byte `offset` of the element
 * buffer, `count` shells, with the program in use; counted in the stats. */
static void draw_instanced(const pelt__pass_frame *f, size_t offset, size_t triangles, unsigned count)
{
    glDrawElementsInstanced(GL_TRIANGLES, (GLsizei)(triangles * 3), GL_UNSIGNED_INT, (const void *)offset,
                            (GLsizei)count);
    f->stats->shell_draw_calls++;
    f->stats->triangles += triangles * count;
}

/* The plain shell renderer of pelt bench --plain (shell_plain_vs.glsl):
 * every shell along the normal, all N on every triangle, no back faces
 * culled, one fetch blended. Built the first time it draws. */
static void draw_plain(pelt__shell_pass *p, const pelt__pass_frame *f)
{
    if (!p->plain.program && !p->plain.failed) {
        const char *vs[] = {pelt__shader_shell_plain_vs, NULL};
        const char *fs[] = {pelt__shader_shell_plain_fs, NULL};
        if (pelt__gl_program_create("shell plain", vs, fs, &p->hooks, &p->plain.program, NULL) != PELT_OK)
            p->plain.failed = true;
    }
    if (!p->plain.program || f->layers == 0) return;
    pelt__gl_blended_hair_state();
    glUseProgram(p->plain.program);
    draw_instanced(f, 0, f->mesh->triangle_count, f->layers);
    f->stats->shell_instances += f->layers;
}

/* Built on first use; a variant that does not build is logged through the
 * hooks, and the generic program stands in. */
const pelt__shell_program *pelt__shell_pass_program(pelt__shell_pass *p, unsigned features)
{
    features &= PELT__SHELL_VARIANTS - 1;
    pelt__shell_program *sp = &p->variants[features];
    if (!sp->program && !sp->failed) build(sp, features, false, &p->hooks, NULL);
    if (sp->program) return sp;
    return features & PELT__SHELL_LIGHT_PASS ? NULL : &p->variants[PELT__SHELL_GENERIC];
}

/* sp in use with the shell pass's uniforms, its shells from instance 0. */
static void use_program(const pelt__shell_program *sp, const pelt__pass_frame *f, const float shells[4],
                        const float next[2])
{
    glUseProgram(sp->program);
    glUniform4fv(sp->shells, 1, shells);
    glUniform2fv(sp->shells_next, 1, next);
    glUniform2fv(sp->shell_view, 1, f->lod.shell_view);
    glUniform1f(sp->back_reach, f->lod.back_reach);
    glUniform1f(sp->instance_base, 0.0f);
    glUniform1i(sp->no_inter_shadow, f->draw->debug.no_inter_shadow ? 1 : 0);
    glUniform1f(sp->sub_shells, 1.0f);
    glUniform2f(sp->sub_view, f->lod.sub_side, 1.0f);
    glUniform1i(sp->no_overcount, f->draw->debug.no_overcount ? 1 : 0);
    glUniform1f(sp->fur_taps, (float)f->lod.texture_taps);
    glUniform1f(sp->fur_aniso, f->lod.texture_aniso);
    glUniform1f(sp->edge_depth, f->lod.edge_depth);
}

/* Close up, the shells every layer is drawn as (the frame plan's, 1: one). */
static unsigned close_up_shells(const pelt__pass_frame *f)
{
    return f->lod.sub_shells > 1 ? f->lod.sub_shells : 1;
}

/* draw_instanced with sp and the shell pass's uniforms: `count` shells
 * from shell `first` (u_instance_base). */
static void draw_part(const pelt__shell_program *sp, const pelt__pass_frame *f, const float shells[4],
                      const float next[2], size_t offset, size_t triangles, unsigned first, unsigned count)
{
    if (triangles == 0 || count == 0) return;
    use_program(sp, f, shells, next);
    /* Close up, each layer's k shells are instances k i .. k i + k - 1. */
    const unsigned k = close_up_shells(f);
    glUniform1f(sp->sub_shells, (float)k);
    glUniform1f(sp->instance_base, (float)first);
    draw_instanced(f, offset, triangles, count * k);
    glUniform1f(sp->sub_shells, 1.0f);
    glUniform1f(sp->instance_base, 0.0f);
}

/* The sub shells the wet shells of draw instance i are drawn in
 * (pelt__clump_sub_shells): where a tuft gathers its hairs, between this
 * layer and the one below. */
static unsigned layer_sub_shells(const pelt__pass_frame *f, const float shells[4], const float next[2], unsigned i,
                                 bool *tufts)
{
    const unsigned close = close_up_shells(f); /* every layer's */
    *tufts = false;
    if (!(f->lod.tuft_pull[1] > 0.0f)) return close;
    float slices[3], alpha, n = (float)f->layers;
    float layer = pelt__lod_shell_instance(shells, next, n, (float)i, slices, &alpha);
    unsigned tuft = pelt__clump_sub_shells((1.0f + layer - shells[1]) / n, (1.0f + layer) / n, f->lod.tuft_pull[0],
                                           n, f->lod.tuft_pull[1]);
    *tufts = tuft > 1; /* the tufts need them wherever the layer is drawn */
    return tuft > close ? tuft : close;
}

/* Whether a wet layer takes sub shells for its tufts (drawn a layer at a
 * time, draw_split: their count and that they are needed everywhere). */
static bool any_sub_shells(const pelt__pass_frame *f, const float shells[4], const float next[2], unsigned count)
{
    const unsigned close = close_up_shells(f);
    bool tufts;
    for (unsigned i = 0; i < count; i++)
        if (layer_sub_shells(f, shells, next, i, &tufts) > close || tufts) return true;
    return false;
}

/* One part of the triangles draw_split draws: a program, the first
 * triangle (bytes into the element buffer) and how many. */
typedef struct shell_part {
    const pelt__shell_program *sp;
    size_t offset, triangles;
    /* A wet part's layers below the tufts' base (tuft_base_shells): the
     * program without the clump lookup, or NULL where sp draws them. */
    const pelt__shell_program *base_sp;
} shell_part;

/* How many of the `count` shells from the inside stand below the tufts'
 * base (pelt__clump_below_tufts): a wet layer there keeps its hair where
 * it grew, so the lean wet program draws it (PELT__SHELL_TUFT_BASE). */
static unsigned tuft_base_shells(const pelt__pass_frame *f, const float shells[4], const float next[2],
                                 unsigned count)
{
    float slices[3], alpha, n = (float)f->layers;
    unsigned below = 0;
    while (below < count &&
           pelt__clump_below_tufts((1.0f + pelt__lod_shell_instance(shells, next, n, (float)below, slices, &alpha)) / n, n))
        below++;
    return below;
}

/* Wet and dry drawn apart, a shell at a time: the dry triangles' shell i
 * with the dry shader, then the wet ones' with the wet shader, from the
 * inside out. The shells blend in the order one draw of every triangle
 * gives them; two instanced draws, all dry shells and then all wet ones,
 * laid a wet patch's inner shells over the dry fur in front of it (dark
 * patches where fur is seen at a grazing angle). The wet shells of a
 * layer where tufts gather their hairs are its sub shells, one instanced
 * draw. Each of dry and wet comes in up to two parts (the view split's
 * face-on part without the read across the gap, then the rest; a part
 * of no triangles is not drawn): dry[0], dry[1], wet[0], wet[1]. A dry
 * frame's view split is dry's two parts alone. */
static void draw_split(const shell_part dry[2], const shell_part wet[2], const pelt__pass_frame *f,
                       const float shells[4], const float next[2], unsigned count)
{
    const unsigned close = close_up_shells(f);
    const unsigned below = tuft_base_shells(f, shells, next, count);
    for (int k = 0; k < 2; k++) {
        if (wet[k].triangles) use_program(wet[k].sp, f, shells, next);
        if (wet[k].triangles && wet[k].base_sp) use_program(wet[k].base_sp, f, shells, next);
        if (dry[k].triangles) {
            use_program(dry[k].sp, f, shells, next);
            glUniform1f(dry[k].sp->sub_shells, (float)close);
        }
    }
    for (unsigned i = 0; i < count; i++) {
        for (int k = 0; k < 2; k++) {
            if (!dry[k].triangles) continue;
            glUseProgram(dry[k].sp->program);
            glUniform1f(dry[k].sp->instance_base, (float)i);
            draw_instanced(f, dry[k].offset, dry[k].triangles, close);
        }
        bool tufts;
        unsigned sub = layer_sub_shells(f, shells, next, i, &tufts);
        for (int k = 0; k < 2; k++) {
            if (!wet[k].triangles) continue;
            const pelt__shell_program *sp = i < below && wet[k].base_sp ? wet[k].base_sp : wet[k].sp;
            glUseProgram(sp->program);
            glUniform1f(sp->instance_base, (float)i);
            glUniform1f(sp->sub_shells, (float)sub);
            glUniform2f(sp->sub_view, f->lod.sub_side, tufts ? 0.0f : 1.0f); /* the tufts': everywhere */
            draw_instanced(f, wet[k].offset, wet[k].triangles, sub);
        }
        if (wet[0].triangles || wet[1].triangles) f->stats->sub_shells += sub - close;
    }
    for (int k = 0; k < 6; k++) {
        const shell_part *part = k < 2 ? &dry[k] : &wet[(k - 2) % 2];
        const pelt__shell_program *sp = k < 4 ? part->sp : part->base_sp;
        if (!part->triangles || !sp) continue;
        glUseProgram(sp->program);
        glUniform1f(sp->instance_base, 0.0f);
        glUniform1f(sp->sub_shells, 1.0f);
        glUniform2f(sp->sub_view, f->lod.sub_side, 1.0f);
    }
}

/* One wet part's shells in two instanced draws: those below the tufts'
 * base with its base program, then the rest (inside out, as one draw
 * would). */
static void draw_wet_part(const shell_part *part, const pelt__pass_frame *f, const float shells[4],
                          const float next[2], unsigned count)
{
    const unsigned below = part->base_sp ? tuft_base_shells(f, shells, next, count) : 0;
    if (below) draw_part(part->base_sp, f, shells, next, part->offset, part->triangles, 0, below);
    draw_part(part->sp, f, shells, next, part->offset, part->triangles, below, count - below);
}

/* draw_split, or one instanced draw where only one part has triangles
 * and no wet layer takes its own sub shells (any_sub_shells). */
static void draw_parts(const shell_part dry[2], const shell_part wet[2], const pelt__pass_frame *f,
                       const float shells[4], const float next[2], unsigned count)
{
    const shell_part *only = NULL;
    int parts = 0;
    for (int k = 0; k < 4; k++) {
        const shell_part *part = k < 2 ? &dry[k] : &wet[k - 2];
        if (part->triangles) only = part, parts++;
    }
    bool wet_only = parts == 1 && (wet[0].triangles || wet[1].triangles);
    if (wet_only && !any_sub_shells(f, shells, next, count))
        draw_wet_part(only, f, shells, next, count);
    else if (parts == 1 && !wet_only)
        draw_part(only->sp, f, shells, next, only->offset, only->triangles, 0, count);
    else if (parts > 0)
        draw_split(dry, wet, f, shells, next, count);
}

bool pelt__shell_pass_wet_apart(const pelt__pass_frame *f)
{
    const pelt__gpu_mesh *m = f->mesh;
    const pelt__frame_lod *lod = &f->lod;
    size_t triangles = lod->full_mesh ? m->triangle_count : m->level_triangles[lod->mesh_level];
    return (f->shell_features & PELT__SHELL_WET) && m->split_ok && !f->draw->debug.no_wet_split &&
           !f->draw->debug.floor_shader && !f->draw->debug.plain_shells && triangles == m->triangle_count &&
           3 * m->split.dry_count >= triangles;
}

void pelt__shell_pass_draw(pelt__shell_pass *p, const pelt__pass_frame *f)
{
    if (f->draw->debug.plain_shells) {
        draw_plain(p, f);
        return;
    }
    const pelt__frame_lod *lod = &f->lod;
    unsigned n = f->layers, level = lod->shell_level;
    float shells[4], next[2];
    unsigned count;
    pelt__lod_shell_uniforms(n, level, lod->shell_blend, f->draw->first_layer, shells, next, &count);
    if (level == 0 && lod->shell_blend == 0.0f && f->draw->layer_count && f->draw->layer_count < count)
        count = f->draw->layer_count;
    if (count == 0) return;
    pelt__gl_blended_hair_state();
    /* The shells are drawn a layer at a time, inside out: along a ray into
     * one surface that is back to front, but where one furry surface lies
     * behind another on screen (the far wall of a torus's hole seen over
     * its near lip) the far fur's outer layers came after the near fur's
     * inner ones and were laid over them. Each hair fragment drawn writes
     * its depth, so fur behind it that comes later is hidden; fur of the
     * same surface that comes later is an outer layer, in front, and
     * still blends over (docs/reference.md, The near lip). */
    if (!f->draw->debug.no_shell_depth) glDepthMask(GL_TRUE);
#if !PELT_GL_ES
    glEnable(GL_CLIP_DISTANCE0); /* faded shells clipped (shell_vs.glsl) */
#endif
    if (lod->cull) {
        /* The skin hides what faces away; the fins carry the silhouette. */
        glEnable(GL_CULL_FACE);
        glFrontFace(lod->front_cw ? GL_CW : GL_CCW);
    }
    const pelt__gpu_mesh *m = f->mesh;
    size_t triangles = lod->full_mesh ? m->triangle_count : m->level_triangles[lod->mesh_level];
    size_t offset = lod->full_mesh ? 0 : m->level_offset[lod->mesh_level];
    pelt__gpu_mesh_point_fit(m, lod->full_mesh, lod->mesh_level);
    const pelt__shell_program *sp = f->draw->debug.floor_shader ? &p->floor : pelt__shell_pass_program(p, f->shell_features);
    /* Wet and dry drawn apart: the mesh's dry triangles (no water anywhere
     * they reach in the mask) with the dry shader, the others wet. Only
     * on the full mesh, whose triangles the split holds, and when at least
     * a third of them is dry: pelt bench measured the default torus 58%
     * dry at 0.83x the frame drawn all wet, a bunny 17% dry at 1.05x. */
    const unsigned wet_bits = PELT__SHELL_WET;
    /* A wet frame's layers below the tufts' base with the lean wet program
     * (tuft_base_shells), face-on without the read across the gap too. */
    const bool wet = sp != &p->floor && (f->shell_features & wet_bits);
    const bool base = wet && !f->draw->debug.no_tuft_base;
    const unsigned base_bits = f->shell_features | PELT__SHELL_TUFT_BASE;
    const pelt__shell_program *base_sp = base ? pelt__shell_pass_program(p, base_bits) : NULL;
    const shell_part none[2] = {{NULL, 0, 0, NULL}, {NULL, 0, 0, NULL}};
    if (wet && pelt__shell_pass_wet_apart(f)) {
        const size_t dry = m->split.dry_count, wet_count = triangles - dry, tri = 3 * sizeof(uint32_t);
        const unsigned dry_bits = f->shell_features & ~wet_bits;
        const pelt__shell_program *dry_sp = pelt__shell_pass_program(p, dry_bits);
        shell_part dry_parts[2] = {{dry_sp, m->split_offset, 0, NULL}, {dry_sp, m->split_offset, dry, NULL}};
        shell_part wet_parts[2] = {{sp, m->split_offset + dry * tri, 0, NULL},
                                   {sp, m->split_offset + dry * tri, wet_count, base_sp}};
        /* Each part's face-on triangles without the read across the gap
         * (the view split of both parts, as a dry frame's). */
        if (f->view_split && m->view_wet && m->view_total == dry && m->view_wet_total == wet_count) {
            const size_t face = m->view_face, wet_face = m->view_wet_face, wet_view = m->view_offset + dry * tri;
            dry_parts[0] = (shell_part){pelt__shell_pass_program(p, dry_bits | PELT__SHELL_NO_GAP), m->view_offset,
                                        face, NULL};
            dry_parts[1] = (shell_part){dry_sp, m->view_offset + face * tri, dry - face, NULL};
            wet_parts[0] = (shell_part){pelt__shell_pass_program(p, f->shell_features | PELT__SHELL_NO_GAP), wet_view,
                                        wet_face,
                                        base ? pelt__shell_pass_program(p, base_bits | PELT__SHELL_NO_GAP) : NULL};
            wet_parts[1] = (shell_part){sp, wet_view + wet_face * tri, wet_count - wet_face, base_sp};
            f->stats->face_on_triangles = face + wet_face;
        }
        draw_parts(dry_parts, wet_parts, f, shells, next, count);
    } else if (wet) {
        /* Wet all over, or not on the full mesh: one wet part. */
        const shell_part wet_parts[2] = {{sp, offset, 0, NULL}, {sp, offset, triangles, base_sp}};
        draw_parts(none, wet_parts, f, shells, next, count);
    } else if (sp != &p->floor && f->view_split && m->view_total == triangles && m->view_face > 0) {
        /* The view split: the face-on triangles without the read across
         * the gap, which llvmpipe would run on every fragment (docs/lod.md). */
        const shell_part parts[2] = {
            {pelt__shell_pass_program(p, f->shell_features | PELT__SHELL_NO_GAP), m->view_offset, m->view_face, NULL},
            {sp, m->view_offset + m->view_face * 3 * sizeof(uint32_t), triangles - m->view_face, NULL}};
        f->stats->face_on_triangles = m->view_face;
        draw_parts(parts, none, f, shells, next, count);
    } else {
        draw_part(sp, f, shells, next, offset, triangles, 0, count);
    }
    f->stats->shell_instances += count; /* the shells each triangle drew */
    f->stats->layer_shells = close_up_shells(f);
    glFrontFace(GL_CCW);
#if !PELT_GL_ES
    glDisable(GL_CLIP_DISTANCE0);
#endif
}

void pelt__shell_pass_destroy(pelt__shell_pass *p)
{
    for (int k = 0; k < PELT__SHELL_VARIANTS; k++)
        if (p->variants[k].program) glDeleteProgram(p->variants[k].program);
    if (p->floor.program) glDeleteProgram(p->floor.program);
    if (p->plain.program) glDeleteProgram(p->plain.program);
    memset(p, 0, sizeof *p);
}
