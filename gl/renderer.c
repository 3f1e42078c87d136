/* The fur renderer (Lengyel et al. 2001 §2.3, Silva et al. §4): owns the
 * shared GPU objects (gl/gpu.h) and the passes (gl/passes.h) and runs one
 * frame: upload what changed, bind the shared objects, skin, shells, then
 * leave GL state as pelt/render.h states. */
#include "pelt/render.h"

#include "core/base/error.h"
#include "core/base/vec.h"
#include "core/fur/fur_gpu.h"
#include "gl/passes.h"

#include <math.h>
#include <string.h>

/* The maps the strand reference shades its hairs with when they stand in
 * for Kenwright's shadows (reference_self_shadow): finer than the default
 * light's, as a reference may be slow. */
#define PELT__REFERENCE_SHADOW_MAP 1024u
#define PELT__REFERENCE_SHADOW_SLICES 8u

struct pelt_renderer {
    pelt_hooks hooks;
    pelt_fur *fur;
    unsigned layers;
    pelt__gpu_mesh mesh;
    pelt__gpu_fur textures;
    pelt__gpu_blocks blocks;
    pelt__skin_pass skin;
    pelt__fin_pass fins;
    pelt__shell_pass shells;
    pelt__shadow_pass shadow;
    pelt__ground_pass ground;
    pelt__strands_pass strands;
    pelt_shadow_desc shadow_desc; /* resolved (core/fur/shadow_map.h) */
    pelt_ground_desc ground_desc;
    pelt__ground_cache ground_cache; /* the mesh's lowest point for the model's y row */
    size_t pending_upload; /* bytes uploaded since the last draw */
    pelt_render_stats stats;
};

pelt_status pelt_renderer_create(const pelt_mesh *mesh, pelt_fur *fur,
                                 const pelt_renderer_desc *desc, pelt_renderer **out,
                                 pelt_error *err)
{
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_renderer_create: out is NULL");
    *out = NULL;
    pelt__fur_snapshot fs = {0};
    if (fur) pelt__fur_gpu_snapshot(fur, &fs);
    if (!mesh || !fur || fs.mesh != mesh)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "pelt_renderer_create: needs a mesh and a fur made for that mesh");
    if (pelt_mesh_get_data(mesh).triangle_count * 3 > 0x7fffffff)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "mesh too large for one draw call");
    const pelt_hooks hooks = desc ? desc->hooks : (pelt_hooks){0};
    pelt_status hst = pelt__hooks_check(&hooks, "pelt_renderer_desc", err);
    if (hst != PELT_OK) return hst;
    pelt_renderer *r = pelt__alloc_zero(&hooks.allocator, 1, sizeof *r);
    if (!r) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory");
    memset(r, 0, sizeof *r);
    r->hooks = hooks;
    r->fur = fur;
    r->layers = pelt_fur_get_desc(fur).layers;

    pelt_status st = pelt__skin_pass_create(&r->skin, &hooks, err);
    if (st == PELT_OK) st = pelt__shell_pass_create(&r->shells, &hooks, err);
    if (st == PELT_OK) st = pelt__fin_pass_create(&r->fins, fur, &fs, &hooks, err);
    if (st == PELT_OK) st = pelt__shadow_pass_create(&r->shadow, &hooks, err);
    if (st == PELT_OK) st = pelt__ground_pass_create(&r->ground, &hooks, err);
    if (st == PELT_OK) st = pelt__gpu_mesh_create(&r->mesh, mesh, fur, &hooks, err);
    pelt__strands_pass_create(&r->strands, fur, &hooks);
    if (st == PELT_OK) st = pelt__gpu_fur_create(&r->textures, fur, &fs, &hooks, err);
    if (st == PELT_OK) {
        pelt__gpu_blocks_create(&r->blocks);
        pelt__gpu_blocks_set_fur(&r->blocks, fur, &fs);
    }
    pelt__gl_state_reset();
    if (st != PELT_OK) {
        pelt_renderer_destroy(r);
        return st;
    }
    *out = r;
    return PELT_OK;
}

void pelt_renderer_destroy(pelt_renderer *r)
{
    if (!r) return;
    pelt__shell_pass_destroy(&r->shells);
    pelt__fin_pass_destroy(&r->fins);
    pelt__shadow_pass_destroy(&r->shadow);
    pelt__ground_pass_destroy(&r->ground);
    pelt__strands_pass_destroy(&r->strands);
    pelt__skin_pass_destroy(&r->skin);
    pelt__gpu_blocks_destroy(&r->blocks);
    pelt__gpu_fur_destroy(&r->textures);
    pelt__gpu_mesh_destroy(&r->mesh);
    const pelt_hooks hooks = r->hooks;
    pelt__free(&hooks.allocator, r);
}

/* Brings GPU copies up to date with what changed in the fur since the last
 * upload: the tip buffer in place, the colour texture when it was set,
 * only the changed rectangle of the wetness mask, the look block. */
static void upload(pelt_renderer *r)
{
    pelt__gl_unpack_defaults();
    pelt__fur_snapshot fs; /* one read of the fur for the three */
    pelt__fur_gpu_snapshot(r->fur, &fs);
    r->pending_upload += pelt__gpu_mesh_upload(&r->mesh, r->fur, &fs);
    unsigned mask_rect[4];
    r->pending_upload += pelt__gpu_fur_upload(&r->textures, r->fur, &fs, mask_rect);
    r->pending_upload += pelt__gpu_mesh_update_split(&r->mesh, &fs, mask_rect);
    r->pending_upload += pelt__gpu_blocks_set_fur(&r->blocks, r->fur, &fs);
}

void pelt_renderer_upload(pelt_renderer *r)
{
    upload(r);
    pelt__gl_state_reset();
}

pelt_status pelt_renderer_set_shadows(pelt_renderer *r, const pelt_shadow_desc *shadows, pelt_error *err)
{
    if (!r) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_renderer_set_shadows: renderer is NULL");
    pelt_shadow_desc d = shadows ? *shadows : (pelt_shadow_desc){0};
    if (d.map_size && (d.map_size < 16 || d.map_size > PELT_SHADOW_MAX_MAP_SIZE))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "shadow map size %u is outside 16..%u", d.map_size,
                          PELT_SHADOW_MAX_MAP_SIZE);
    if (d.slices > PELT_SHADOW_MAX_SLICES)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%u shadow slices: at most %u", d.slices,
                          PELT_SHADOW_MAX_SLICES);
    if (!isfinite(d.softness) || !isfinite(d.depth) || !isfinite(d.density))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "shadow softness, depth and density must be finite");
    d = pelt__shadow_resolved(&d);
    r->shadow_desc.enabled = false;
    if (d.enabled) {
        pelt_status st = pelt__shadow_pass_resize(&r->shadow, d.map_size, err);
        pelt__gl_state_reset();
        if (st != PELT_OK) return st;
    }
    r->shadow_desc = d;
    return PELT_OK;
}

void pelt_renderer_set_ground(pelt_renderer *r, const pelt_ground_desc *ground)
{
    if (r) r->ground_desc = pelt__ground_resolved(ground);
}

/* The passes in frame order (docs/architecture.md, One frame): a new pass
 * is its file (gl/NAME_pass.c, gl/passes.h) and a row here, with its state
 * in pelt_renderer. Each row runs when the plan says so. */
typedef struct pass_row {
    const char *name;
    bool (*wanted)(const pelt__frame_plan *plan);
    void (*run)(pelt_renderer *r, const pelt__pass_frame *frame, const pelt__frame_plan *plan);
} pass_row;

static bool want_light(const pelt__frame_plan *p) { return p->light_maps; }
static bool want_ground(const pelt__frame_plan *p) { return p->ground; }
static bool want_skin(const pelt__frame_plan *p) { return p->skin; }
static bool want_fins(const pelt__frame_plan *p) { return p->fins; }
static bool want_shells(const pelt__frame_plan *p) { return p->shells; }
static bool want_strands(const pelt__frame_plan *p) { return p->strands; }

static void run_light(pelt_renderer *r, const pelt__pass_frame *f, const pelt__frame_plan *p)
{
    if (p->strands)
        pelt__shadow_pass_draw_strands(&r->shadow, &r->strands, f, &p->light_pass);
    else
        pelt__shadow_pass_draw(&r->shadow, &r->shells, f, &p->light_pass);
    pelt__shadow_pass_bind(&r->shadow);
}

/* The strand reference has no counterpart of Kenwright's inter-fur
 * shadows: where the shells draw them and the light's maps are off, its
 * hairs shade each other through maps drawn from the hairs themselves
 * (docs/reference.md, The reference's hairs shade each other), keeping
 * Silva's gamma as the shells do. Made on the first such frame. */
static pelt_shadow_desc reference_self_shadow(pelt_renderer *r, const pelt_draw_desc *draw)
{
    if (draw->mode != PELT_DRAW_STRANDS || r->shadow_desc.enabled || draw->debug.no_inter_shadow ||
        !pelt_fur_get_desc(r->fur).look.inter_shadow)
        return r->shadow_desc;
    const pelt_shadow_desc want = {.enabled = true, .map_size = PELT__REFERENCE_SHADOW_MAP,
                                   .slices = PELT__REFERENCE_SHADOW_SLICES, .keep_gamma = true};
    pelt_shadow_desc d = pelt__shadow_resolved(&want);
    if (pelt__shadow_pass_resize(&r->shadow, d.map_size, NULL) != PELT_OK) return r->shadow_desc;
    return d;
}

static void run_ground(pelt_renderer *r, const pelt__pass_frame *f, const pelt__frame_plan *p)
{
    pelt__ground_pass_draw(&r->ground, f, p->disc, r->ground_desc.color);
}

static void run_skin(pelt_renderer *r, const pelt__pass_frame *f, const pelt__frame_plan *p)
{
    (void)p;
    pelt__skin_pass_draw(&r->skin, f);
}

static void run_strands(pelt_renderer *r, const pelt__pass_frame *f, const pelt__frame_plan *p)
{
    (void)p;
    pelt__strands_pass_draw(&r->strands, f);
}

static void run_fins(pelt_renderer *r, const pelt__pass_frame *f, const pelt__frame_plan *p)
{
    (void)p;
    pelt__fin_pass_draw(&r->fins, f);
}

/* The outline's hairs over the shells: the fin pass's fins of this frame. */
static void run_outline(pelt_renderer *r, const pelt__pass_frame *f, const pelt__frame_plan *p)
{
    (void)p;
    pelt__fin_pass_draw_outline(&r->fins, f);
}

/* The view split (pelt__fur_gpu_view_split): brought up to this frame's
 * view where the dry shells' program draws the frame, or where a wet frame
 * draws wet and dry apart (each part split so). True when it holds the
 * drawn triangles. */
static bool view_split(pelt_renderer *r, const pelt__pass_frame *f)
{
    const pelt_draw_desc *d = f->draw;
    if (d->debug.no_view_split || d->debug.floor_shader || d->debug.plain_shells) return false;
    const bool wet = f->shell_features & PELT__SHELL_WET;
    if (wet && !pelt__shell_pass_wet_apart(f)) return false;
    const float *m = f->view->model;
    pelt__view_split_desc vd = {
        .level = f->lod.mesh_level,
        .full_mesh = f->lod.full_mesh,
        .model_scale = sqrtf(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]),
        .eye = {f->view->eye[0], f->view->eye[1], f->view->eye[2]},
        .margin = PELT__VIEW_SPLIT_MARGIN,
    };
    memcpy(vd.model, m, sizeof vd.model);
    /* The clip w row of proj x view (the vertex stage's u_view_proj), where
     * it gates the read by the shells' spacing on screen. */
    float view_proj[16];
    pelt__mat4_mul(view_proj, f->view->proj, f->view->view);
    vd.shell_spacing = f->lod.shell_view[0];
    for (int c = 0; c < 4; c++) vd.w_row[c] = view_proj[4 * c + 3];
    f->stats->upload_bytes += wet ? pelt__gpu_mesh_update_view_wet(&r->mesh, r->fur, &vd)
                                  : pelt__gpu_mesh_update_view(&r->mesh, r->fur, &vd);
    return r->mesh.view_ok;
}

static void run_shells(pelt_renderer *r, const pelt__pass_frame *f, const pelt__frame_plan *p)
{
    if (!p->gpu_skin) {
        pelt__pass_frame split = *f;
        split.view_split = view_split(r, f);
        pelt__shell_pass_draw(&r->shells, &split);
        return;
    }
    f->stats->upload_bytes += pelt__gpu_mesh_upload_bones(&r->mesh, r->fur);
    glActiveTexture(GL_TEXTURE0 + PELT_UNIT_BONES);
    glBindTexture(GL_TEXTURE_2D, r->mesh.bone_texture);
    glActiveTexture(GL_TEXTURE0);
    glBindVertexArray(r->mesh.vao_skin);
    pelt__pass_frame skinned = *f;
    skinned.shell_features |= PELT__SHELL_GPU_SKIN;
    pelt__shell_pass_draw(&r->shells, &skinned);
}

static const pass_row passes[] = {
    {"light", want_light, run_light},    /* the light's maps first: the others receive them */
    {"ground", want_ground, run_ground},
    {"skin", want_skin, run_skin},       /* opaque, depth write */
    {"strands", want_strands, run_strands}, /* the strand reference, in place of fins and shells */
    {"fins", want_fins, run_fins},
    {"shells", want_shells, run_shells}, /* blended inner to outer */
    {"outline", want_fins, run_outline}, /* the outline's hairs, over the shells */
};

void pelt_renderer_draw(pelt_renderer *r, const pelt_view *view, const pelt_draw_desc *draw)
{
    static const pelt_draw_desc everything = {0};
    if (!draw) draw = &everything;
    upload(r);
    const pelt__frame_switches sw = {
        .skin = !draw->no_skin,
        .fins = !draw->no_fins,
        .shells = !draw->debug.no_shells,
        .inter_shadow = !draw->debug.no_inter_shadow,
        .shadows = !draw->debug.no_shadows,
        .cull_shells = draw->debug.cull_shells,
        .one_height = draw->first_layer || draw->layer_count,
        .flat_shells = draw->debug.flat_shells,
        .lod_off = draw->debug.lod_off,
        .sub_shells = !draw->debug.no_sub_shells,
        .as_dry = draw->debug.as_dry,
        .gpu_skin = draw->debug.skin_in_vertex_stage,
        .strands = draw->mode == PELT_DRAW_STRANDS,
    };
    const pelt_shadow_desc shadow = reference_self_shadow(r, draw);
    const pelt__frame_setup setup = {shadow, r->shadow.size, r->ground_desc, r->mesh.skinned};
    pelt__frame_plan plan;
    pelt__frame_plan_make(r->fur, view, &sw, &setup, &r->ground_cache, &plan);

    pelt_render_stats stats = {0};
    stats.upload_bytes = r->pending_upload + pelt__gpu_blocks_set_frame(&r->blocks, view, draw, &plan.shadow);
    r->pending_upload = 0;
    stats.mesh_level = plan.lod.mesh_level;
    stats.fin_level = plan.lod.fin_level;
    stats.mesh_triangles = plan.lod.full_mesh ? r->mesh.triangle_count : r->mesh.level_triangles[plan.lod.mesh_level];
    stats.shell_level = plan.lod.shell_level;
    stats.shell_blend = plan.lod.shell_blend;
    stats.culled = plan.lod.cull && plan.shells;

    glBindVertexArray(r->mesh.vao);
    pelt__gpu_fur_bind(&r->textures);
    pelt__gpu_blocks_bind(&r->blocks);
    const pelt__pass_frame frame = {&r->mesh, r->layers, draw, &stats, plan.lod, view, plan.shell_features};
    for (size_t i = 0; i < sizeof passes / sizeof passes[0]; i++)
        if (passes[i].wanted(&plan)) passes[i].run(r, &frame, &plan);
    pelt__gl_state_reset();
    r->stats = stats;
}

pelt_render_stats pelt_renderer_get_stats(const pelt_renderer *r) { return r->stats; }
