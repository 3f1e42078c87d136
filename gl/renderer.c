/* The fur renderer (Lengyel et al. 2001 §2.3, Silva et al. §4): owns the
 * shared GPU objects (gl/gpu.h) and the passes (gl/passes.h) and runs one
 * frame: upload what changed, bind the shared objects, skin, shells, then
 * leave GL state as pelt/render.h states. */
#include "pelt/render.h"

#include "core/base/error.h"
#include "core/fur/fur_gpu.h"
#include "gl/passes.h"

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
    pelt__gpu_mesh_bind_tables(&r->mesh);
    pelt__gpu_blocks_bind(&r->blocks);
    const pelt__pass_frame frame = {&r->mesh, r->layers, draw, &stats};
    /* Frame order (DESIGN.md): skin, fins, shells. */
    if (!draw->no_skin) pelt__skin_pass_draw(&r->skin, &frame);
    if (!draw->no_fins) pelt__fin_pass_draw(&r->fins, &frame);
    if (!draw->no_shells) pelt__shell_pass_draw(&r->shells, &frame);
    pelt__gl_state_reset();
    r->stats = stats;
}

pelt_render_stats pelt_renderer_get_stats(const pelt_renderer *r) { return r->stats; }
