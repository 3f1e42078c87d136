/* One frame's plan (frame_plan.h): levels of detail, the light's frame,
 * the ground disc, the shader's features and the passes. */
#include "core/fur/frame_plan.h"

#include "core/base/vec.h"
#include "core/fur/fur_gpu.h"
#include "core/fur/shadow_map.h"

#include <math.h>
#include <string.h>

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

/* The clip w of the vertex in view nearest the eye (a margin of a tenth
 * round the view: the fur reaches past), or infinity where none is: the
 * fur is seen largest there. A pass over the vertices: the bounding
 * sphere's nearest point says nothing once the eye is inside it (a
 * close-up). */
static float nearest_view_w(const pelt_fur *fur, const pelt_view *v)
{
    pelt__fur_snapshot fs;
    pelt__fur_gpu_snapshot(fur, &fs);
    const pelt_mesh_data md = pelt_mesh_get_data(fs.mesh);
    float vp[16], mvp[16];
    pelt__mat4_mul(vp, v->proj, v->view);
    pelt__mat4_mul(mvp, vp, v->model);
    float nearest = INFINITY;
    for (size_t i = 0; i < md.vertex_count; i++) {
        const float *p = fs.pose ? fs.pose + 10 * i : md.positions + 3 * i;
        float c[4];
        for (int r = 0; r < 4; r++) c[r] = mvp[r] * p[0] + mvp[4 + r] * p[1] + mvp[8 + r] * p[2] + mvp[12 + r];
        if (!(c[3] > 0.0f) || fabsf(c[0]) > 1.1f * c[3] || fabsf(c[1]) > 1.1f * c[3] || c[2] < -c[3]) continue;
        nearest = fminf(nearest, c[3]);
    }
    return nearest;
}

/* Pixels per world unit at clip w `nearest` (orthographic: any w). */
static float pixels_per_unit_at(const pelt_view *v, float nearest)
{
    return v->proj[5] * 0.5f * (float)v->height * model_scale(v->model) /
           (v->proj[11] == 0.0f ? 1.0f : fmaxf(nearest, 1e-6f));
}

/* The wet sub shells' measure (pelt__frame_lod.tuft_pull): how far, in
 * pixels where the fur is seen largest, the tufts' pull moves a hair at
 * the rim of a tuft of the mean width (wet.clump_size) over the whole
 * profile. */
static float tuft_sweep_pixels(const pelt_fur_desc *fd, const pelt_view *v, float nearest)
{
    if (!isfinite(nearest) || v->height == 0) return 0.0f;
    float sweep = fd->wet.clump_tightness * 0.5f * fd->wet.clump_size * pixels_per_unit_at(v, nearest);
    return isfinite(sweep) ? fminf(sweep, 4.0f * (float)v->height) : 0.0f;
}

/* The levels of detail for this view (core/fur/lod.h): the geometric level
 * by the error it makes on screen, the shell level by the fur's length on
 * screen, both measured at the bounding sphere's point nearest the eye. */
static pelt__frame_lod choose_lod(const pelt_fur *fur, const pelt_fur_desc *fd, const pelt_view *v,
                                  const pelt__frame_switches *sw)
{
    pelt__frame_lod l;
    memset(&l, 0, sizeof l);
    l.back_reach = -1.0f;
    l.fur_px = INFINITY;
    const pelt_fur_lod fl = fd->lod;
    l.texture_taps = fl.texture_taps > 1 ? fl.texture_taps : 1;
    l.texture_aniso = fl.texture_aniso > 1.0f ? fl.texture_aniso : 1.0f;
    l.edge_depth = fl.edge_depth > 1.0f ? fl.edge_depth : 1.0f;
    pelt__fur_snapshot fs;
    pelt__fur_gpu_snapshot(fur, &fs);
    const pelt__lod_chain *c = fs.lod;
    if (fl.mode == PELT_LOD_OFF || sw->lod_off || c->count == 0) {
        l.full_mesh = true;
        return l;
    }
    bool closed = c->closed && c->winding != 0;
    l.cull = closed && (sw->cull_shells > 0 || (sw->cull_shells == 0 && sw->fins));
    l.cull_skin = closed;
    /* Back-facing shells far round the back are hidden by the skin: a
     * closed mesh's front, and on an open mesh (whose skin is drawn on both
     * sides) the patch's own skin, which stands between the eye and the
     * fur growing away from it. Near the silhouette they stay: their hair
     * crosses the outline (on a closed mesh the fins carry it instead, and
     * every back-facing shell is culled). */
    bool reach = closed ? !l.cull && sw->cull_shells == 0 : sw->cull_shells >= 0 && sw->skin;
    l.back_reach = reach ? fl.back_reach : -1.0f;
    l.front_cw = c->winding < 0;
    unsigned shell_levels = pelt__lod_shell_levels(fd->layers);
    if (fl.mode == PELT_LOD_FIXED) {
        l.mesh_level = fl.mesh_level < c->count ? fl.mesh_level : c->count - 1;
        l.fin_level = l.mesh_level;
        l.shell_level = sw->one_height ? 0 : fl.shell_level < shell_levels ? fl.shell_level : shell_levels - 1;
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
    /* Fins up to a slab of the fin texture apart (docs/lod.md, The fins' own level). */
    const float slab = fd->look.tiling > 0.0f ? fd->fins.density / ((float)fd->look.texture_size * fd->look.tiling) : 0.0f;
    l.fin_level = pelt__lod_pick_fins(c, l.mesh_level, ppu, fl.mesh_error_pixels, slab);
    float fur_px = fd->length * ppu;
    l.fur_px = isfinite(fur_px) ? fur_px : INFINITY;
    if (!sw->one_height) pelt__lod_shell_choice(fd->layers, fur_px, fl.shell_pixels, &l.shell_level, &l.shell_blend);
    /* Where the fur is seen face-on a vertex needs fewer shells: it blends
     * towards the next level as far as its foreshortened spacing allows. */
    if (!sw->one_height && !sw->flat_shells && l.shell_level + 1 < shell_levels && fd->length > 0.0f) {
        l.shell_view[0] = fd->length * pixels_per_unit_at(v, 1.0f) * (float)(1u << l.shell_level) / (float)fd->layers;
        l.shell_view[1] = fl.shell_pixels;
    }
    /* A fin's strip follows the bent and curled strand to within a pixel:
     * on llvmpipe a fin costs its triangles as much as its pixels. */
    l.fin_row_error = ppu > 0.0f && isfinite(ppu) ? 1.0f / ppu : 0.0f;
    return l;
}

/* The light's frame and what the light pass draws (docs/shadows.md): an
 * orthographic frame around the mesh's bounding sphere grown by the fur,
 * a geometric level whose error stays under the maps' texels, and the
 * coarsest shell level of at most 4 shells (Lengyel's composited levels
 * keep the fur's opacity). Returns whether the light pass runs. */
static bool shadow_frame(const pelt_fur *fur, const pelt_fur_desc *fd, const pelt_view *v,
                         const pelt__frame_switches *sw, const pelt__frame_setup *setup, pelt__frame_shadow *fs,
                         pelt__shadow_frame *sf)
{
    memset(fs, 0, sizeof *fs);
    memset(sf, 0, sizeof *sf);
    const pelt_shadow_desc *d = &setup->shadow;
    pelt__fur_snapshot snap;
    pelt__fur_gpu_snapshot(fur, &snap);
    const pelt__lod_chain *c = snap.lod;
    float scale = model_scale(v->model), center[3];
    transform_point(v->model, c->center, center);
    float radius = (c->radius + 1.5f * fd->length) * scale;
    const float depth_range = 2.0f; /* radii behind the centre: room for a ground */
    float clip[16];
    pelt__shadow_light_frame(center, radius, v->light.direction, depth_range, fs->light_matrix, clip);
    bool on = d->enabled && sw->shadows && setup->shadow_map_size > 0;
    if (!on) return false;
    float depth_unit = radius * (1.0f + depth_range), texel = 2.0f * radius / (float)d->map_size;
    fs->map[0] = 1.0f;
    fs->map[1] = (float)d->slices;
    fs->map[2] = 1.0f / (float)d->map_size;
    fs->map[3] = d->softness;
    fs->slab[0] = d->depth * fd->length * scale / depth_unit;
    fs->slab[1] = d->density;
    fs->slab[2] = (1.5f + d->softness) * texel / depth_unit;
    fs->slab[3] = d->keep_gamma ? 1.0f : 0.0f;

    unsigned slices_lod = snap.lod_slices;
    if (fd->lod.mode == PELT_LOD_OFF || c->count <= 1) {
        sf->full_mesh = true;
    } else {
        float ppu = (float)d->map_size / (2.0f * radius) * scale; /* map texels per mesh unit */
        sf->mesh_level = fd->lod.mode == PELT_LOD_FIXED
                             ? (fd->lod.mesh_level < c->count ? fd->lod.mesh_level : c->count - 1)
                             : pelt__lod_pick(c, ppu, fd->lod.mesh_error_pixels, fd->lod.mesh_edge_pixels);
    }
    if (slices_lod)
        while (sf->shell_level + 1 < pelt__lod_shell_levels(fd->layers) &&
               pelt__lod_shell_count(fd->layers, sf->shell_level) > 4)
            sf->shell_level++;
    sf->cull = c->closed && c->winding != 0;
    sf->front_cw = c->winding < 0;
    return true;
}

/* The ground's disc: under the bounding sphere's centre, at the mesh's
 * lowest world height. That height depends on the model's y row alone, so
 * the vertices are scanned again only when it turns: not for a turntable
 * about +Y or a bounce (its translation is added after). */
static void ground_disc(const pelt_fur *fur, const pelt_view *v, float size, pelt__ground_cache *cache,
                        float disc[4])
{
    pelt__fur_snapshot fs;
    pelt__fur_gpu_snapshot(fur, &fs);
    const float *m = v->model;
    const float row[3] = {m[1], m[5], m[9]};
    if (!cache->valid || memcmp(cache->row, row, sizeof row)) {
        const pelt_mesh_data md = pelt_mesh_get_data(fs.mesh);
        float lowest = INFINITY;
        for (size_t i = 0; i < md.vertex_count; i++) {
            const float *p = md.positions + 3 * i;
            lowest = fminf(lowest, row[0] * p[0] + row[1] * p[1] + row[2] * p[2]);
        }
        memcpy(cache->row, row, sizeof row);
        cache->low = isfinite(lowest) ? lowest : 0.0f;
        cache->valid = true;
    }
    const pelt__lod_chain *c = fs.lod;
    float center[3];
    transform_point(v->model, c->center, center);
    disc[0] = center[0];
    disc[1] = cache->low + m[13];
    disc[2] = center[2];
    disc[3] = size * c->radius * model_scale(v->model);
}

/* The shell shader's features this frame needs (PELT__SHELL_*). */
static unsigned shell_features(const pelt_fur *fur, const pelt_fur_desc *fd, const pelt__frame_lod *lod,
                               const pelt__frame_switches *sw, bool light_maps)
{
    pelt__fur_snapshot fs;
    pelt__fur_gpu_snapshot(fur, &fs);
    unsigned f = 0;
    if (fs.any_wet && !sw->as_dry) f |= PELT__SHELL_WET;
    /* Curly hair lit along its curl: ringlets, or the texture's own curl. */
    if (fs.ringlet_levels > 1 || fd->look.strand_curl > 0.0f) f |= PELT__SHELL_RINGLETS;
    if (fd->look.inter_shadow && sw->inter_shadow) f |= PELT__SHELL_INTER_SHADOW;
    if (lod->shell_blend > 0.0f) f |= PELT__SHELL_LOD_BLEND;
    if (lod->texture_taps > 1) f |= PELT__SHELL_FUR_TAPS;
    if (fs.color) f |= PELT__SHELL_COLOR_TEXTURE;
    /* Neither model bit: Scheuermann-Marschner (gl/shaders/fur_light.glsl). */
    if (fd->look.shading == PELT_SHADING_LENGYEL_TABLE) f |= PELT__SHELL_LIGHT_TABLE;
    if (fd->look.shading == PELT_SHADING_KAJIYA_KAY) f |= PELT__SHELL_KAJIYA_KAY;
    if (light_maps) f |= PELT__SHELL_SHADOW_MAP;
    return f;
}

void pelt__frame_plan_make(const pelt_fur *fur, const pelt_view *view, const pelt__frame_switches *sw,
                           const pelt__frame_setup *setup, pelt__ground_cache *cache, pelt__frame_plan *out)
{
    memset(out, 0, sizeof *out);
    const pelt_fur_desc fd = pelt_fur_get_desc(fur);
    out->light_maps = shadow_frame(fur, &fd, view, sw, setup, &out->shadow, &out->light_pass);
    out->lod = choose_lod(fur, &fd, view, sw);
    out->shell_features = shell_features(fur, &fd, &out->lod, sw, out->light_maps);
    const bool wet_sub = (out->shell_features & PELT__SHELL_WET) && sw->sub_shells && !sw->one_height;
    /* The level's spacing seen side-on, pixels x clip w per unit of groom
     * length (as the view budget's, whether or not it is on). */
    const float step = (float)(1u << out->lod.shell_level) / (float)(fd.layers ? fd.layers : 1);
    const float side_w = fd.length * pixels_per_unit_at(view, 1.0f) * step;
    /* No vertex's layers stand further apart than at the bounding sphere's
     * nearest point, but for its depth (clip w) being less than its
     * distance off the view's axis: by at most the cosine of the view's
     * corner, with the margin of a tenth the pass allows round the view.
     * Where they stand close even so, no pass over the vertices. */
    const float corner = view->proj[11] == 0.0f ? 1.0f
                                                : 1.1f * sqrtf(1.0f + 1.0f / (view->proj[0] * view->proj[0]) +
                                                               1.0f / (view->proj[5] * view->proj[5]));
    const float side_bound = out->lod.fur_px * corner * step;
    const bool view_sub = fd.lod.sub_shells > 1 && sw->sub_shells && !sw->one_height && !out->lod.full_mesh &&
                          side_w > 0.0f && !(side_bound <= PELT__SUB_SHELL_PIXELS);
    const float nearest = wet_sub || view_sub ? nearest_view_w(fur, view) : INFINITY;
    if (wet_sub) {
        out->lod.tuft_pull[0] = fd.wet.clump_blend;
        out->lod.tuft_pull[1] = tuft_sweep_pixels(&fd, view, nearest);
    }
    /* Close up, the layers' rows show edge-on: each layer in sub shells. */
    out->lod.sub_shells = 1;
    if (view_sub && isfinite(nearest))
        out->lod.sub_shells = pelt__lod_sub_shells(side_w / fmaxf(nearest, 1e-6f), fd.lod.sub_shells);
    /* Per vertex, as the view's budget weighs the spacing (none with it off). */
    if (out->lod.sub_shells > 1 && !sw->flat_shells) out->lod.sub_side = side_w;
    if (out->light_maps) out->light_pass.features = out->shell_features & (PELT__SHELL_WET | PELT__SHELL_RINGLETS);
    out->ground = setup->ground.enabled;
    if (out->ground) ground_disc(fur, view, setup->ground.size, cache, out->disc);
    out->skin = sw->skin;
    out->fins = sw->fins;
    out->shells = sw->shells;
    out->gpu_skin = sw->shells && sw->gpu_skin && setup->skinned_mesh;
    if (sw->strands) out->strands = true, out->fins = out->shells = out->gpu_skin = false;
}
