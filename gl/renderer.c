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
    pelt__shadow_pass shadow;
    pelt__ground_pass ground;
    pelt__strands_pass strands;
    pelt_shadow_desc shadow_desc; /* resolved (core/fur/shadow_map.h) */
    pelt_ground_desc ground_desc;
    const pelt_mesh *source; /* the mesh as given: its positions place the ground */
    float ground_row[3];    /* the model's y row the lowest point was found for */
    float ground_low;       /* min over the vertices of that row times them */
    bool ground_valid;
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
    r->source = mesh;

    pelt_status st = pelt__skin_pass_create(&r->skin, &hooks, err);
    if (st == PELT_OK) st = pelt__shell_pass_create(&r->shells, &hooks, err);
    if (st == PELT_OK) st = pelt__fin_pass_create(&r->fins, fur, &hooks, err);
    if (st == PELT_OK) st = pelt__shadow_pass_create(&r->shadow, &hooks, err);
    if (st == PELT_OK) st = pelt__ground_pass_create(&r->ground, &hooks, err);
    if (st == PELT_OK) st = pelt__gpu_mesh_create(&r->mesh, mesh, fur, &hooks, err);
    pelt__strands_pass_create(&r->strands, fur, &hooks);
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
    r->pending_upload += pelt__gpu_mesh_upload(&r->mesh, r->fur);
    r->pending_upload += pelt__gpu_fur_upload(&r->textures, r->fur);
    r->pending_upload += pelt__gpu_blocks_set_fur(&r->blocks, r->fur);
}

void pelt_renderer_upload(pelt_renderer *r)
{
    upload(r);
    pelt__gl_state_reset();
}

/* The largest scale of the model matrix's columns. */
static float model_scale(const float *m)
{
    float scale = 0.0f;
    for (int col = 0; col < 3; col++)
        scale = fmaxf(scale, sqrtf(m[4 * col] * m[4 * col] + m[4 * col + 1] * m[4 * col + 1] +
                                   m[4 * col + 2] * m[4 * col + 2]));
    return scale;
}

static void transform_point(const float *m, const float p[3], float out[3])
{
    for (int k = 0; k < 3; k++) out[k] = m[k] * p[0] + m[4 + k] * p[1] + m[8 + k] * p[2] + m[12 + k];
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
    l.cull_skin = closed;
    l.front_cw = c->winding < 0;
    bool one_height = draw->first_layer || draw->layer_count; /* inspecting layers: level 0 */
    unsigned shell_levels = pelt__lod_shell_levels(r->layers);
    if (fl.mode == PELT_LOD_FIXED) {
        l.mesh_level = fl.mesh_level < c->count ? fl.mesh_level : c->count - 1;
        l.shell_level = one_height ? 0 : fl.shell_level < shell_levels ? fl.shell_level : shell_levels - 1;
        return l;
    }
    float scale = model_scale(v->model), center[3];
    transform_point(v->model, c->center, center);
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
    /* A fin's strip follows the bent and curled strand to within a pixel:
     * on llvmpipe a fin costs its triangles as much as its pixels. */
    l.fin_row_error = ppu > 0.0f && isfinite(ppu) ? 1.0f / ppu : 0.0f;
    return l;
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

/* The light's frame and what the light pass draws (docs/shadows.md): an
 * orthographic frame around the mesh's bounding sphere grown by the fur,
 * a geometric level whose error stays under the maps' texels, and the
 * coarsest shell level of at most 4 shells (Lengyel's composited levels
 * keep the fur's opacity). */
static bool shadow_frame(const pelt_renderer *r, const pelt_view *v, const pelt_draw_desc *draw,
                         pelt__frame_shadow *fs, pelt__shadow_frame *sf)
{
    memset(fs, 0, sizeof *fs);
    memset(sf, 0, sizeof *sf);
    const pelt_shadow_desc *d = &r->shadow_desc;
    const pelt_fur_desc fd = pelt_fur_get_desc(r->fur);
    const pelt__lod_chain *c = pelt__fur_gpu_lod(r->fur);
    float scale = model_scale(v->model), center[3];
    transform_point(v->model, c->center, center);
    float radius = (c->radius + 1.5f * fd.length) * scale;
    const float depth_range = 2.0f; /* radii behind the centre: room for a ground */
    float clip[16];
    pelt__shadow_light_frame(center, radius, v->light.direction, depth_range, fs->light_matrix, clip);
    bool on = d->enabled && !draw->no_shadows && r->shadow.size > 0;
    if (!on) return false;
    float depth_unit = radius * (1.0f + depth_range), texel = 2.0f * radius / (float)d->map_size;
    fs->map[0] = 1.0f;
    fs->map[1] = (float)d->slices;
    fs->map[2] = 1.0f / (float)d->map_size;
    fs->map[3] = d->softness;
    fs->slab[0] = d->depth * fd.length * scale / depth_unit;
    fs->slab[1] = d->density;
    fs->slab[2] = (1.5f + d->softness) * texel / depth_unit;
    fs->slab[3] = d->keep_gamma ? 1.0f : 0.0f;

    unsigned slices_lod;
    pelt__fur_gpu_volume_lod(r->fur, &slices_lod);
    if (fd.lod.mode == PELT_LOD_OFF || c->count <= 1) {
        sf->full_mesh = true;
    } else {
        float ppu = (float)d->map_size / (2.0f * radius) * scale; /* map texels per mesh unit */
        sf->mesh_level = fd.lod.mode == PELT_LOD_FIXED ? (fd.lod.mesh_level < c->count ? fd.lod.mesh_level : c->count - 1)
                                                       : pelt__lod_pick(c, ppu, fd.lod.mesh_error_pixels,
                                                                        fd.lod.mesh_edge_pixels);
    }
    if (slices_lod)
        while (sf->shell_level + 1 < pelt__lod_shell_levels(r->layers) &&
               pelt__lod_shell_count(r->layers, sf->shell_level) > 4)
            sf->shell_level++;
    sf->cull = c->closed && c->winding != 0;
    sf->front_cw = c->winding < 0;
    return true;
}

/* The ground's disc: under the bounding sphere's centre, at the mesh's
 * lowest world height. That height depends on the model's y row alone, so
 * the vertices are scanned again only when it turns: not for a turntable
 * about +Y or a bounce (its translation is added after). */
static void ground_disc(pelt_renderer *r, const pelt_view *v, float disc[4])
{
    const float *m = v->model;
    const float row[3] = {m[1], m[5], m[9]};
    if (!r->ground_valid || memcmp(r->ground_row, row, sizeof row)) {
        const pelt_mesh_data md = pelt_mesh_get_data(r->source);
        float lowest = INFINITY;
        for (size_t i = 0; i < md.vertex_count; i++) {
            const float *p = md.positions + 3 * i;
            lowest = fminf(lowest, row[0] * p[0] + row[1] * p[1] + row[2] * p[2]);
        }
        memcpy(r->ground_row, row, sizeof row);
        r->ground_low = isfinite(lowest) ? lowest : 0.0f;
        r->ground_valid = true;
    }
    const pelt__lod_chain *c = pelt__fur_gpu_lod(r->fur);
    float center[3];
    transform_point(v->model, c->center, center);
    disc[0] = center[0];
    disc[1] = r->ground_low + m[13];
    disc[2] = center[2];
    disc[3] = r->ground_desc.size * c->radius * model_scale(v->model);
}

/* The shell shader's features this frame needs (PELT__SHELL_*). */
static unsigned shell_features(const pelt_renderer *r, const pelt__frame_lod *lod, const pelt_draw_desc *draw)
{
    const pelt_fur_look look = pelt_fur_get_desc(r->fur).look;
    unsigned w, h, version;
    unsigned f = 0;
    if (pelt__fur_gpu_any_wet(r->fur)) {
        f |= PELT__SHELL_WET;
        if (pelt__fur_gpu_ringlet_levels(r->fur) > 1) f |= PELT__SHELL_RINGLETS;
    }
    if (look.inter_shadow && !draw->no_inter_shadow) f |= PELT__SHELL_INTER_SHADOW;
    if (lod->shell_blend > 0.0f) f |= PELT__SHELL_LOD_BLEND;
    if (pelt__fur_gpu_color(r->fur, &w, &h, &version)) f |= PELT__SHELL_COLOR_TEXTURE;
    f |= look.shading == PELT_SHADING_LENGYEL_TABLE ? PELT__SHELL_LIGHT_TABLE : PELT__SHELL_KAJIYA_KAY;
    if (r->shadow_desc.enabled && !draw->no_shadows && r->shadow.size) f |= PELT__SHELL_SHADOW_MAP;
    return f;
}

void pelt_renderer_draw(pelt_renderer *r, const pelt_view *view, const pelt_draw_desc *draw)
{
    static const pelt_draw_desc everything = {0};
    if (!draw) draw = &everything;
    upload(r);
    pelt_render_stats stats = {0};
    pelt__frame_shadow shadow;
    pelt__shadow_frame light_pass;
    bool shadows = shadow_frame(r, view, draw, &shadow, &light_pass);
    stats.upload_bytes = r->pending_upload + pelt__gpu_blocks_set_frame(&r->blocks, view, &shadow);
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
    /* Frame order (DESIGN.md): the light's maps, ground, skin, fins, shells. */
    if (shadows) {
        light_pass.features = frame.shell_features & (PELT__SHELL_WET | PELT__SHELL_RINGLETS);
        pelt__shadow_pass_draw(&r->shadow, &r->shells, &frame, &light_pass);
        pelt__shadow_pass_bind(&r->shadow);
    }
    if (r->ground_desc.enabled) {
        float disc[4];
        ground_disc(r, view, disc);
        pelt__ground_pass_draw(&r->ground, &frame, disc, r->ground_desc.color);
    }
    if (!draw->no_skin) pelt__skin_pass_draw(&r->skin, &frame);
    if (draw->mode == PELT_DRAW_STRANDS) { /* the strand reference in place of fins and shells */
        pelt__strands_pass_draw(&r->strands, &frame);
    } else if (!draw->no_fins) {
        pelt__fin_pass_draw(&r->fins, &frame);
    }
    if (draw->mode == PELT_DRAW_STRANDS) {
        /* drawn above */
    } else if (!draw->no_shells && draw->skin_in_vertex_stage && r->mesh.skinned) {
        stats.upload_bytes += pelt__gpu_mesh_upload_bones(&r->mesh, r->fur);
        glActiveTexture(GL_TEXTURE0 + PELT_UNIT_BONES);
        glBindTexture(GL_TEXTURE_2D, r->mesh.bone_texture);
        glActiveTexture(GL_TEXTURE0);
        glBindVertexArray(r->mesh.vao_skin);
        pelt__pass_frame skinned = frame;
        skinned.shell_features |= PELT__SHELL_GPU_SKIN;
        pelt__shell_pass_draw(&r->shells, &skinned);
    } else if (!draw->no_shells) {
        pelt__shell_pass_draw(&r->shells, &frame);
    }
    pelt__gl_state_reset();
    r->stats = stats;
}

pelt_render_stats pelt_renderer_get_stats(const pelt_renderer *r) { return r->stats; }
