/* The fur renderer (Lengyel et al. 2001 §2.3, Silva et al. §4): owns the
 * shared GPU objects (gl/gpu.h) and the passes (gl/passes.h) and runs one
 * frame: upload what changed, bind the shared objects, skin, shells, then
 * leave GL state as pelt/render.h states. */
#include "pelt/render.h"

#include "core/base/error.h"
#include "core/fur/fur_gpu.h"
#include "gl/passes.h"

#include <math.h>
#include <string.h>

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
    size_t pending_upload; /* bytes uploaded since the last draw */
    pelt_render_stats stats;
};

pelt_status pelt_renderer_create(const pelt_mesh *mesh, pelt_fur *fur,
                                 const pelt_renderer_desc *desc, pelt_renderer **out,
                                 pelt_error *err)
{
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_renderer_create: out is NULL");
    *out = NULL;
    if (!mesh || !fur || pelt__fur_gpu_mesh(fur) != mesh)
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
    if (st == PELT_OK) st = pelt__fin_pass_create(&r->fins, fur, &hooks, err);
    if (st == PELT_OK) st = pelt__gpu_mesh_create(&r->mesh, mesh, fur, &hooks, err);
    if (st == PELT_OK) {
        pelt__gpu_fur_create(&r->textures, fur);
        pelt__gpu_blocks_create(&r->blocks);
        pelt__gpu_blocks_set_fur(&r->blocks, fur);
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
    r->pending_upload += pelt__gpu_mesh_upload(&r->mesh, r->fur);
    r->pending_upload += pelt__gpu_fur_upload(&r->textures, r->fur);
    r->pending_upload += pelt__gpu_blocks_set_fur(&r->blocks, r->fur);
}

void pelt_renderer_upload(pelt_renderer *r)
{
    upload(r);
    pelt__gl_state_reset();
}

/* The levels of detail for this view (core/fur/lod.h): the geometric level
 * by the error it makes on screen, the shell level by the fur's length on
 * screen, both measured at the bounding sphere's point nearest the eye. */
static pelt__frame_lod choose_lod(const pelt_renderer *r, const pelt_view *v, const pelt_draw_desc *draw)
{
    pelt__frame_lod l;
    memset(&l, 0, sizeof l);
    const pelt_fur_lod fl = pelt_fur_get_desc(r->fur).lod;
    const pelt__lod_chain *c = pelt__fur_gpu_lod(r->fur);
    if (fl.mode == PELT_LOD_OFF || c->count == 0) {
        l.full_mesh = true;
        return l;
    }
    bool closed = c->closed && c->winding != 0;
    l.cull = closed && (draw->cull_shells > 0 || (draw->cull_shells == 0 && !draw->no_fins));
    l.front_cw = c->winding < 0;
    bool one_height = draw->first_layer || draw->layer_count; /* inspecting layers: level 0 */
    unsigned shell_levels = pelt__lod_shell_levels(r->layers);
    if (fl.mode == PELT_LOD_FIXED) {
        l.mesh_level = fl.mesh_level < c->count ? fl.mesh_level : c->count - 1;
        l.shell_level = one_height ? 0 : fl.shell_level < shell_levels ? fl.shell_level : shell_levels - 1;
        return l;
    }
    const float *m = v->model;
    float scale = 0.0f;
    for (int col = 0; col < 3; col++)
        scale = fmaxf(scale, sqrtf(m[4 * col] * m[4 * col] + m[4 * col + 1] * m[4 * col + 1] +
                                   m[4 * col + 2] * m[4 * col + 2]));
    float center[3];
    for (int k = 0; k < 3; k++)
        center[k] = m[k] * c->center[0] + m[4 + k] * c->center[1] + m[8 + k] * c->center[2] + m[12 + k];
    float ppu;
    if (v->proj[11] == 0.0f) { /* orthographic: the same size at any distance */
        ppu = v->proj[5] * 0.5f * (float)v->height * scale;
    } else {
        float dx = center[0] - v->eye[0], dy = center[1] - v->eye[1], dz = center[2] - v->eye[2];
        ppu = pelt__lod_pixels_per_unit(v->proj[5], (float)v->height, scale, sqrtf(dx * dx + dy * dy + dz * dz),
                                        c->radius);
    }
    if (v->height == 0) ppu = INFINITY;
    l.mesh_level = pelt__lod_pick(c, ppu, fl.mesh_error_pixels, fl.mesh_edge_pixels);
    float fur_px = pelt_fur_get_desc(r->fur).length * ppu;
    if (!one_height) pelt__lod_shell_choice(r->layers, fur_px, fl.shell_pixels, &l.shell_level, &l.shell_blend);
    /* A fin's strip follows the curved strand in a quad per 8 pixels. */
    l.fin_rows = fur_px < 8.0f ? 1 : fur_px < 16.0f ? 2 : PELT_FIN_ROWS;
    return l;
}

/* The shell shader's features this frame needs (PELT__SHELL_*). */
static unsigned shell_features(const pelt_renderer *r, const pelt__frame_lod *lod, const pelt_draw_desc *draw)
{
    const pelt_fur_look look = pelt_fur_get_desc(r->fur).look;
    unsigned w, h, version;
    unsigned f = 0;
    if (pelt__fur_gpu_any_wet(r->fur)) f |= PELT__SHELL_WET;
    if (look.inter_shadow && !draw->no_inter_shadow) f |= PELT__SHELL_INTER_SHADOW;
    if (lod->shell_blend > 0.0f) f |= PELT__SHELL_LOD_BLEND;
    if (pelt__fur_gpu_color(r->fur, &w, &h, &version)) f |= PELT__SHELL_COLOR_TEXTURE;
    f |= look.shading == PELT_SHADING_LENGYEL_TABLE ? PELT__SHELL_LIGHT_TABLE : PELT__SHELL_KAJIYA_KAY;
    return f;
}

void pelt_renderer_draw(pelt_renderer *r, const pelt_view *view, const pelt_draw_desc *draw)
{
    static const pelt_draw_desc everything = {0};
    if (!draw) draw = &everything;
    upload(r);
    pelt_render_stats stats = {0};
    stats.upload_bytes = r->pending_upload + pelt__gpu_blocks_set_frame(&r->blocks, view);
    r->pending_upload = 0;

    glBindVertexArray(r->mesh.vao);
    pelt__gpu_fur_bind(&r->textures);
    pelt__gpu_blocks_bind(&r->blocks);
    const pelt__frame_lod lod = choose_lod(r, view, draw);
    const pelt__pass_frame frame = {&r->mesh, r->layers, draw, &stats, lod, view, shell_features(r, &lod, draw)};
    stats.mesh_level = frame.lod.mesh_level;
    stats.mesh_triangles = frame.lod.full_mesh ? r->mesh.triangle_count : r->mesh.level_triangles[frame.lod.mesh_level];
    stats.shell_level = frame.lod.shell_level;
    stats.shell_blend = frame.lod.shell_blend;
    stats.culled = frame.lod.cull && !draw->no_shells;
    /* Frame order (DESIGN.md): skin, fins, shells. */
    if (!draw->no_skin) pelt__skin_pass_draw(&r->skin, &frame);
    if (!draw->no_fins) pelt__fin_pass_draw(&r->fins, &frame);
    if (!draw->no_shells) pelt__shell_pass_draw(&r->shells, &frame);
    pelt__gl_state_reset();
    r->stats = stats;
}

pelt_render_stats pelt_renderer_get_stats(const pelt_renderer *r) { return r->stats; }
