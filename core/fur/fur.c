/* pelt_fur: parameters, synthesized fur texture and per-vertex fur state. */
#include "core/fur/fur_internal.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/fur/fur_shape.h"
#include "core/fur/furtex.h"
#include "core/mesh/mesh_internal.h"
#include "core/base/vec.h"
#include "core/wet/paint.h"
#include "core/wet/picture.h"
#include "pelt/dynamics.h"
#include "pelt/wetness.h"

#include <stdlib.h>
#include <string.h>

void pelt__fur_desc_defaults(pelt_fur_desc *d, const pelt_mesh *mesh)
{
    float diag = mesh ? pelt_mesh_diagonal(mesh) : 1.0f;
    if (!(diag > 0.0f)) diag = 1.0f;
    if (d->layers == 0) d->layers = 16;
    if (d->length == 0.0f) d->length = 0.03f * diag;
    if (d->look.texture_size == 0) d->look.texture_size = 256;
    if (d->seed == 0) d->seed = 1;
    if (d->look.density == 0.0f) d->look.density = 3000.0f;
    if (d->look.strand_radius == 0.0f) d->look.strand_radius = 1.6f;
    if (d->look.taper == 0.0f) d->look.taper = 0.8f;
    if (d->look.strand_curl_turns == 0.0f) d->look.strand_curl_turns = 2.0f;
    /* Tiles per world unit: five fur tiles across the bounding diagonal. */
    if (d->look.tiling == 0.0f) d->look.tiling = 5.0f / diag;
    if (d->look.color[0] == 0.0f && d->look.color[1] == 0.0f && d->look.color[2] == 0.0f) {
        d->look.color[0] = 0.55f; d->look.color[1] = 0.34f; d->look.color[2] = 0.18f;
    }
    if (d->look.tip_color[0] == 0.0f && d->look.tip_color[1] == 0.0f && d->look.tip_color[2] == 0.0f) {
        d->look.tip_color[0] = 1.0f; d->look.tip_color[1] = 0.82f; d->look.tip_color[2] = 0.58f;
    }
    if (d->look.skin_color[0] == 0.0f && d->look.skin_color[1] == 0.0f && d->look.skin_color[2] == 0.0f) {
        d->look.skin_color[0] = 0.78f; d->look.skin_color[1] = 0.56f; d->look.skin_color[2] = 0.47f;
    }
    if (d->look.specular[0] == 0.0f && d->look.specular[1] == 0.0f && d->look.specular[2] == 0.0f)
        d->look.specular[0] = 0.9f, d->look.specular[1] = 0.85f, d->look.specular[2] = 0.8f;
    if (d->look.shininess == 0.0f) d->look.shininess = 20.0f;
    if (d->look.shadow == 0.0f) d->look.shadow = 2.0f;
    if (d->dynamics.mass == 0.0f) d->dynamics.mass = 1.0f;
    if (d->dynamics.spring_k == 0.0f) d->dynamics.spring_k = d->dynamics.mass * 9.81f / (0.4f * d->length);
    if (d->dynamics.damping == 0.0f) d->dynamics.damping = 0.5f * sqrtf(d->dynamics.spring_k * d->dynamics.mass);
    if (d->wet.mask_size == 0) d->wet.mask_size = 256;
    if (d->wet.clump_blend == 0.0f) d->wet.clump_blend = 0.5f;
    if (d->wet.clump_tightness == 0.0f) d->wet.clump_tightness = 0.9f;
    if (d->wet.darken == 0.0f) d->wet.darken = 0.35f;
    if (d->wet.gloss == 0.0f) d->wet.gloss = 2.0f;
    if (d->wet.gloss_sharpness == 0.0f) d->wet.gloss_sharpness = 4.0f;
    if (d->look.color_scale == 0.0f) d->look.color_scale = 1.0f;
    if (d->look.inter_shadow_offset == 0.0f) d->look.inter_shadow_offset = 4.0f;
    if (d->look.inter_shadow_darkness == 0.0f) d->look.inter_shadow_darkness = 0.8f;
    if (d->look.diffuse_power == 0.0f) d->look.diffuse_power = 1.0f;
    if (d->fins.length == 0.0f) d->fins.length = 1.0f;
    if (d->fins.density == 0.0f) d->fins.density = (float)d->look.texture_size / 16.0f;
    if (d->fins.curl_turns == 0.0f) d->fins.curl_turns = 2.0f;
    if (d->lod.shell_pixels == 0.0f) d->lod.shell_pixels = 1.0f;
    if (d->lod.mesh_error_pixels == 0.0f) d->lod.mesh_error_pixels = 0.5f;
    if (d->lod.mesh_edge_pixels == 0.0f) d->lod.mesh_edge_pixels = 8.0f;
}

bool pelt__fur_has_ringlets(const pelt_fur_desc *d)
{
    return d->look.curl_phase == PELT_CURL_RINGLETS && d->look.curl_radius > 0.0f;
}

float pelt__fur_vertex_curl_radius(const pelt_fur_desc *d)
{
    return pelt__fur_has_ringlets(d) ? 0.0f : d->look.curl_radius;
}

static pelt_status check_desc(const pelt_fur_desc *d, pelt_error *err)
{
    if (d->layers < 1 || d->layers > 256)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "fur layers must be 1..256, got %u", d->layers);
    if (d->look.texture_size < 8 || d->look.texture_size > 4096)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "fur texture size must be 8..4096, got %u",
                          d->look.texture_size);
    const float positive[] = {d->length, d->look.density, d->look.strand_radius, d->look.tiling, d->look.shininess};
    const char *names[] = {"length", "density", "strand radius", "tiling", "shininess"};
    for (size_t i = 0; i < sizeof positive / sizeof positive[0]; i++)
        if (!(positive[i] > 0.0f) || !isfinite(positive[i]))
            return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "fur %s must be a positive number, got %g",
                              names[i], (double)positive[i]);
    if (d->look.density > 1e6f)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "fur density %g is too high (max 1e6)", (double)d->look.density);
    if (d->look.strand_radius > 64.0f)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "fur strand radius %g texels is too large (max 64)",
                          (double)d->look.strand_radius);
    if (!(d->look.taper >= 0.0f && d->look.taper <= 1.0f))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "fur taper must be in [0, 1], got %g", (double)d->look.taper);
    if (!(d->look.strand_curl >= 0.0f && d->look.strand_curl <= 64.0f) ||
        !(d->look.strand_curl_turns > 0.0f && d->look.strand_curl_turns <= 32.0f) ||
        (unsigned)d->look.strand_curl_shape > PELT_STRAND_CURL_WAVE)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "fur strand curl must be 0..64 texels with 0..32 turns and a known shape, got "
                          "%g texels, %g turns",
                          (double)d->look.strand_curl, (double)d->look.strand_curl_turns);
    if (!(d->look.shadow >= 1.0f) || !isfinite(d->look.shadow))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "fur shadow K must be >= 1, got %g", (double)d->look.shadow);
    if (!(d->dynamics.mass > 0.0f) || !(d->dynamics.spring_k > 0.0f) || !(d->dynamics.damping >= 0.0f) || !isfinite(d->dynamics.mass) ||
        !isfinite(d->dynamics.spring_k) || !isfinite(d->dynamics.damping))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "fur mass and spring constant must be positive, damping >= 0");
    if (d->wet.mask_size > 8192)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "wetness mask size must be 1..8192, got %u", d->wet.mask_size);
    if (!(d->wet.clump_blend >= 0.0f && d->wet.clump_blend <= 1.0f) ||
        !(d->wet.clump_tightness > 0.0f && d->wet.clump_tightness <= 1.0f) ||
        !(d->wet.darken >= 0.0f && d->wet.darken < 1.0f))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "clump blend must be in [0,1], tightness in (0,1], wet darkening in [0,1)");
    if (!(d->wet.clump_size >= 0.0f) || !isfinite(d->wet.clump_size))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "wet clump size must be >= 0, got %g",
                          (double)d->wet.clump_size);
    if (!(d->wet.gloss >= 1.0f && d->wet.gloss <= 16.0f) ||
        !(d->wet.gloss_sharpness >= 1.0f && d->wet.gloss_sharpness <= 64.0f))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "wet gloss must be in [1, 16] and its sharpness in [1, 64], got %g and %g",
                          (double)d->wet.gloss, (double)d->wet.gloss_sharpness);
    if (!(d->comb.slant >= 0.0f && d->comb.slant <= 60.0f))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "fur slant must be 0..60 degrees, got %g",
                          (double)d->comb.slant);
    if (!(d->look.color_scale > 0.0f) || !isfinite(d->look.color_scale))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "colour scale must be positive");
    if (!isfinite(d->look.curl_frequency) || !isfinite(d->look.curl_radius) || d->look.curl_radius < 0.0f)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "curl frequency and radius must be finite, radius >= 0");
    if ((unsigned)d->look.curl_phase > PELT_CURL_COHERENT)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "curl phase must be ringlets or coherent, got %d",
                          (int)d->look.curl_phase);
    if (!(d->look.inter_shadow_offset > 0.0f && d->look.inter_shadow_offset <= 64.0f) ||
        !(d->look.inter_shadow_darkness > 0.0f && d->look.inter_shadow_darkness <= 1.0f) ||
        !(d->look.diffuse_power > 0.0f && d->look.diffuse_power <= 256.0f) ||
        (unsigned)d->look.shading > PELT_SHADING_LENGYEL_TABLE)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "inter-fur shadow offset must be in (0, 64] texels, darkness in (0, 1], "
                          "diffuse power in (0, 256], shading a known model");
    if (!(d->fins.length > 0.0f && d->fins.length <= 8.0f) || !(d->fins.density > 0.0f) ||
        !(d->fins.density <= (float)d->look.texture_size) || !(d->fins.curl >= 0.0f && d->fins.curl <= 64.0f) ||
        !(d->fins.curl_turns > 0.0f && d->fins.curl_turns <= 64.0f))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "fin length must be in (0, 8], density in (0, texture size], curl in [0, 64] "
                          "texels, curl turns in (0, 64]");
    if ((unsigned)d->lod.mode > PELT_LOD_FIXED || d->lod.shell_level > 8 || d->lod.mesh_level > 11 ||
        !(d->lod.shell_pixels > 0.0f && d->lod.shell_pixels <= 64.0f) ||
        !(d->lod.mesh_error_pixels > 0.0f && d->lod.mesh_error_pixels <= 64.0f) ||
        !(d->lod.mesh_edge_pixels > 0.0f && d->lod.mesh_edge_pixels <= 1024.0f))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "level of detail: mode auto, off or fixed, shell level 0..8, mesh level 0..11, shell pixels and "
                          "mesh error pixels in (0, 64], mesh edge pixels in (0, 1024]");
    return PELT_OK;
}

/* Fur-texture coordinates in tiles. With an atlas the mesh carries patch
 * coordinates already; otherwise the mesh uvs are scaled by the mean
 * world length of one uv unit along u and along v, so hairs come out round
 * whatever the uv map's aspect (the torus's uv square is 2.5x longer
 * around the hole than around the tube). */
static void compute_fur_uvs(const pelt_mesh *m, float tiling, float *out, float fur_per_uv[2])
{
    if (m->fur_uvs) {
        /* Patch coordinates from an atlas: within a patch fur uvs are a
         * similarity of the atlas uvs; measure its scale for the clump
         * displacement (mask space to fur space). */
        memcpy(out, m->fur_uvs, m->vertex_count * 2 * sizeof(float));
        double fur_area = 0.0, uv_area = 0.0;
        for (size_t t = 0; t < m->triangle_count; t++) {
            uv_area += pelt__triangle_area_2d(m, m->uvs, t);
            fur_area += pelt__triangle_area_2d(m, m->fur_uvs, t);
        }
        float k = uv_area > 0.0 ? (float)sqrt(fur_area / uv_area) : tiling;
        fur_per_uv[0] = fur_per_uv[1] = k;
        return;
    }
    double su = 0.0, sv = 0.0, wsum = 0.0;
    for (size_t t = 0; t < m->triangle_count; t++) {
        const uint32_t *ix = m->indices + 3 * t;
        pelt_vec3 p0 = v3_load(m->positions + 3 * ix[0]);
        pelt_vec3 e1 = v3_sub(v3_load(m->positions + 3 * ix[1]), p0);
        pelt_vec3 e2 = v3_sub(v3_load(m->positions + 3 * ix[2]), p0);
        const float *a = m->uvs + 2 * ix[0], *b = m->uvs + 2 * ix[1], *c = m->uvs + 2 * ix[2];
        float du1 = b[0] - a[0], dv1 = b[1] - a[1], du2 = c[0] - a[0], dv2 = c[1] - a[1];
        float det = du1 * dv2 - du2 * dv1;
        float area = v3_len(v3_cross(e1, e2));
        if (fabsf(det) < 1e-12f || area <= 0.0f) continue;
        /* Columns of the Jacobian dP/du and dP/dv. */
        pelt_vec3 dpu = v3_scale(v3_sub(v3_scale(e1, dv2), v3_scale(e2, dv1)), 1.0f / det);
        pelt_vec3 dpv = v3_scale(v3_sub(v3_scale(e2, du1), v3_scale(e1, du2)), 1.0f / det);
        su += area * v3_len(dpu);
        sv += area * v3_len(dpv);
        wsum += area;
    }
    float scale_u = wsum > 0.0 ? (float)(su / wsum) : 1.0f;
    float scale_v = wsum > 0.0 ? (float)(sv / wsum) : 1.0f;
    fur_per_uv[0] = scale_u * tiling;
    fur_per_uv[1] = scale_v * tiling;
    for (size_t i = 0; i < m->vertex_count; i++) {
        out[2 * i + 0] = m->uvs[2 * i + 0] * scale_u * tiling;
        out[2 * i + 1] = m->uvs[2 * i + 1] * scale_v * tiling;
    }
}

pelt__furtex_desc pelt__fur_texture_desc(const pelt_fur_desc *d)
{
    pelt__furtex_desc td = {d->look.texture_size, d->layers, d->seed, d->look.density, d->look.strand_radius,
                            d->look.taper, d->look.strand_curl, d->look.strand_curl_turns,
                            d->look.strand_curl_shape == PELT_STRAND_CURL_WAVE, 0.0f, 0.0f};
    /* Ringlets (docs/method.md): Silva's curl drawn strand by strand into
     * the texture, K_alpha in texels (the texture tiles `tiling` times per
     * world unit), at full, half and no amplitude for the shells to blend
     * by wetness. */
    if (pelt__fur_has_ringlets(d)) {
        td.ringlet_radius = d->look.curl_radius * d->look.tiling * (float)d->look.texture_size;
        td.ringlet_omega = d->look.curl_frequency;
    }
    return td;
}

pelt_status pelt_fur_create(const pelt_mesh *mesh, const pelt_fur_desc *desc, pelt_fur **out,
                            pelt_error *err)
{
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_fur_create: out is NULL");
    *out = NULL;
    if (!mesh) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_fur_create: mesh is NULL");
    pelt_fur_desc d = desc ? *desc : (pelt_fur_desc){0};
    pelt__fur_desc_defaults(&d, mesh);
    pelt_status st = check_desc(&d, err);
    if (st == PELT_OK) st = pelt__hooks_check(&d.hooks, "pelt_fur_desc", err);
    if (st != PELT_OK) return st;

    const pelt_allocator *a = &d.hooks.allocator;
    pelt_fur *f = pelt__alloc_zero(a, 1, sizeof *f);
    if (!f) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory");
    f->desc = d;
    f->mesh = mesh;
    f->texture_slices = d.layers + 1;
    pelt__furtex_desc td = pelt__fur_texture_desc(&d);
    f->ringlet_levels = pelt__fur_has_ringlets(&d) ? PELT__RINGLET_LEVELS : 1;
    size_t bytes = pelt__furtex_bytes(&td);
    f->texture = bytes ? pelt__alloc_zero(a, f->ringlet_levels, bytes) : NULL;
    f->fur_uvs = pelt__alloc_zero(a, mesh->vertex_count, 2 * sizeof(float));
    pelt__strand_params sp = {d.length, d.dynamics.spring_k, d.dynamics.mass, d.dynamics.damping, d.seed};
    st = pelt__strands_create(mesh, &sp, &f->desc.hooks.allocator, &f->strands, err);
    if (st != PELT_OK) {
        pelt_fur_destroy(f);
        return st;
    }
    f->tips = pelt__strands_tip_offsets(f->strands);
    st = pelt__wetness_create(d.wet.mask_size, d.wet.mask_size, &f->desc.hooks.allocator, &f->wetness, err);
    if (st == PELT_OK && d.wet.clump_size > 0.0f)
        st = pelt__clump_cells_create(mesh, f->wetness->width, f->wetness->height, d.wet.clump_size, d.seed,
                                      &f->desc.hooks.allocator, &f->clump_cells, err);
    if (st == PELT_OK) st = pelt__surface_index_create(mesh, &f->desc.hooks.allocator, &f->surface, err);
    if (st == PELT_OK) st = pelt__bvh_build(mesh, &f->desc.hooks.allocator, &f->bvh, err);
    if (st == PELT_OK) st = pelt__rain_create(mesh, &f->desc.hooks.allocator, &f->rain, err);
    if (st == PELT_OK) st = pelt__groom_init(&f->groom, mesh->vertex_count, &f->desc.hooks.allocator, err);
    /* Level 0 holds the fins of the full mesh; with level of detail off
     * there is nothing coarser to build. */
    if (st == PELT_OK)
        st = pelt__lod_chain_build(mesh, d.seed, d.lod.mode == PELT_LOD_OFF ? 1 : 0, &f->desc.hooks.allocator,
                                   &f->lod, err);
    if (st != PELT_OK) {
        pelt_fur_destroy(f);
        return st;
    }
    /* The fin texture: the same hair sideways, a quarter as tall as wide. */
    pelt__fintex_desc fd = {td, d.look.texture_size / 4 < 8 ? 8 : d.look.texture_size / 4, d.fins.density,
                            d.fins.curl, d.fins.curl_turns};
    size_t fin_bytes = pelt__fintex_bytes(&fd);
    f->fin_texture = fin_bytes ? pelt__alloc(a, fin_bytes) : NULL;
    if (!f->texture || !f->fur_uvs || !f->fin_texture) {
        pelt_fur_destroy(f);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the fur texture (%zu bytes)", bytes);
    }
    /* Level k of the ringlets holds the curl at 1 - k / (levels - 1) of
     * its amplitude; without ringlets the one level is the volume. */
    float full = td.ringlet_radius;
    for (unsigned k = 0; k < f->ringlet_levels; k++) {
        pelt__furtex_desc level = td;
        if (f->ringlet_levels > 1) level.ringlet_radius = full * (1.0f - (float)k / (float)(f->ringlet_levels - 1));
        pelt__furtex_generate(&level, f->texture + (size_t)k * bytes);
    }
    /* Lengyel §2.4: the coarser shell levels, composited from the volume,
     * for each ringlet level. */
    if (d.lod.mode != PELT_LOD_OFF && pelt__lod_shell_extra_slices(d.layers) > 0) {
        f->lod_slice_count = (unsigned)pelt__lod_shell_extra_slices(d.layers);
        size_t lod_bytes = (size_t)f->lod_slice_count * d.look.texture_size * d.look.texture_size * 4;
        f->lod_slices = pelt__alloc_zero(a, f->ringlet_levels, lod_bytes);
        if (!f->lod_slices) {
            pelt_fur_destroy(f);
            return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the shell levels of detail");
        }
        for (unsigned k = 0; k < f->ringlet_levels; k++)
            pelt__lod_shell_composite(f->texture + (size_t)k * bytes, d.look.texture_size, d.layers,
                                      f->lod_slices + (size_t)k * lod_bytes);
    }
    pelt__fintex_generate(&fd, f->fin_texture);
    f->fin_width = d.look.texture_size;
    f->fin_height = fd.height;
    compute_fur_uvs(mesh, d.look.tiling, f->fur_uvs, f->fur_per_uv);
    f->tips_version = 1;
    *out = f;
    return PELT_OK;
}

pelt_status pelt_fur_desc_curl_preset(pelt_fur_desc *d, const pelt_mesh *mesh, const char *name,
                                      pelt_error *err)
{
    float omega = 0.0f, radius_fraction = 0.0f;
    if (!name || !pelt__curl_preset(name, &omega, &radius_fraction))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "unknown curl preset '%s' (straight, wavy, few-large-curls, many-small-curls)",
                          name ? name : "(null)");
    pelt_fur_desc resolved = *d;
    pelt__fur_desc_defaults(&resolved, mesh);
    if (d->look.curl_frequency == 0.0f) d->look.curl_frequency = omega;
    if (d->look.curl_radius == 0.0f) d->look.curl_radius = radius_fraction * resolved.length;
    return PELT_OK;
}

void pelt_fur_destroy(pelt_fur *f)
{
    if (!f) return;
    pelt_allocator a = f->desc.hooks.allocator;
    pelt__free(&a, f->texture);
    pelt__free(&a, f->fur_uvs);
    pelt__free(&a, f->color_texture);
    pelt__strands_destroy(f->strands);
    pelt__wetness_destroy(f->wetness);
    pelt__clump_cells_destroy(f->clump_cells);
    pelt__surface_index_destroy(f->surface);
    pelt__bvh_destroy(f->bvh);
    pelt__rain_destroy(f->rain);
    pelt__groom_free(&f->groom);
    pelt__lod_chain_free(&f->lod, &a);
    pelt__free(&a, f->lod_slices);
    pelt__free(&a, f->fin_texture);
    pelt__free(&a, f->pose);
    pelt__free(&a, f);
}

pelt_status pelt_fur_set_transform(pelt_fur *f, const float model[16], pelt_error *err)
{
    if (!pelt__strands_set_transform(f->strands, model))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "fur transform must be finite and invertible");
    return PELT_OK;
}

pelt_status pelt_fur_set_pose(pelt_fur *f, const float *positions, const float *normals, const float *tangents,
                              pelt_error *err)
{
    const pelt_mesh_data m = pelt_mesh_get_data(f->mesh);
    if (!positions || !normals || !tangents)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_fur_set_pose: positions, normals and tangents are needed");
    for (size_t i = 0; i < m.vertex_count; i++) {
        bool finite = true;
        for (int k = 0; k < 3; k++) finite &= isfinite(positions[3 * i + k]) && isfinite(normals[3 * i + k]);
        for (int k = 0; k < 4; k++) finite &= isfinite(tangents[4 * i + k]) != 0;
        if (!finite) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_fur_set_pose: vertex %zu is not finite", i);
    }
    if (!f->pose) {
        f->pose = pelt__alloc_zero(&f->desc.hooks.allocator, m.vertex_count, 10 * sizeof(float));
        if (!f->pose) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "pelt_fur_set_pose: out of memory");
    }
    float *p = f->pose;
    for (size_t i = 0; i < m.vertex_count; i++) {
        memcpy(p + 10 * i, positions + 3 * i, 3 * sizeof *p);
        memcpy(p + 10 * i + 3, normals + 3 * i, 3 * sizeof *p);
        memcpy(p + 10 * i + 6, tangents + 4 * i, 4 * sizeof *p);
    }
    pelt__strands_set_pose(f->strands, positions, normals);
    f->pose_version++;
    return PELT_OK;
}

/* Natural clumps: water lands between water_begin and water_end, which
 * clumps the cells it touched anew (core/wet/clump_cells.h). The mask's
 * dirty rectangle is set aside meanwhile, so that what this call changed
 * can be told apart, and is then grown back. */
static void water_begin(pelt_fur *f, unsigned saved[4])
{
    memcpy(saved, f->wetness->dirty, 4 * sizeof saved[0]);
    if (f->clump_cells) pelt__rect_clear(f->wetness->dirty);
}

static void water_end(pelt_fur *f, const unsigned saved[4])
{
    if (!f->clump_cells) return;
    unsigned changed[4];
    memcpy(changed, f->wetness->dirty, sizeof changed);
    pelt__clump_cells_apply(f->clump_cells, f->wetness, changed);
    pelt__rect_union(f->wetness->dirty, saved);
}

void pelt_fur_step(pelt_fur *f, float dt, const pelt_forces *forces)
{
    if (!(dt > 0.0f)) return;
    pelt__strands_step(f->strands, dt, forces, f->time);
    unsigned saved[4];
    water_begin(f, saved);
    pelt__rain_step(f->rain, f->wetness, f->surface, f->bvh, dt);
    water_end(f, saved);
    if (f->dry_rate > 0.0f) pelt__wetness_dry(f->wetness, f->dry_rate, dt);
    f->time += dt;
    f->tips_version++;
}

void pelt_fur_reset(pelt_fur *f)
{
    pelt__strands_reset(f->strands);
    f->time = 0.0f;
    f->tips_version++;
}

pelt_fur_desc pelt_fur_get_desc(const pelt_fur *f) { return f->desc; }

bool pelt_fur_pick(const pelt_fur *f, const float origin[3], const float direction[3], float hit[3])
{
    pelt__hit h;
    if (!f || !origin || !direction || !pelt__bvh_raycast(f->bvh, origin, direction, INFINITY, &h))
        return false;
    if (hit)
        for (int k = 0; k < 3; k++) hit[k] = origin[k] + h.t * direction[k];
    return true;
}

pelt_status pelt_fur_set_color_texture(pelt_fur *f, const uint8_t *rgba, unsigned w, unsigned h,
                                       pelt_error *err)
{
    if (!rgba || w == 0 || h == 0 || w > 16384 || h > 16384)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "colour texture must be 1..16384 texels a side");
    const pelt_allocator *a = &f->desc.hooks.allocator;
    uint8_t *copy = pelt__alloc_zero(a, (size_t)w * h, 4);
    if (!copy) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for a %ux%u colour texture", w, h);
    memcpy(copy, rgba, (size_t)w * h * 4);
    pelt__free(a, f->color_texture);
    f->color_texture = copy;
    f->color_width = w;
    f->color_height = h;
    f->color_version++;
    return PELT_OK;
}

pelt_status pelt_fur_add_droplet(pelt_fur *f, const pelt_droplet *d, pelt_error *err)
{
    unsigned saved[4];
    water_begin(f, saved);
    pelt_status st = pelt__wetness_add_droplet(f->wetness, d, err);
    water_end(f, saved);
    return st;
}

pelt_status pelt_fur_add_droplets(pelt_fur *f, const pelt_droplet *d, size_t count, pelt_error *err)
{
    unsigned saved[4];
    water_begin(f, saved);
    pelt_status st = pelt__wetness_add_droplets(f->wetness, d, count, err);
    water_end(f, saved);
    return st;
}

pelt_status pelt_fur_add_droplet_at(pelt_fur *f, size_t triangle, const float bary[3],
                                    float radius_world, float wetness, pelt_error *err)
{
    /* By distance on the surface, across patch borders (issue 5). */
    unsigned saved[4];
    water_begin(f, saved);
    pelt_status st = pelt__droplet_surface(f->wetness, f->mesh, f->surface, triangle, bary, radius_world,
                                           wetness, err);
    water_end(f, saved);
    return st;
}

bool pelt_fur_add_droplet_ray(pelt_fur *f, const float origin[3], const float direction[3],
                              float radius_world, float wetness)
{
    unsigned saved[4];
    water_begin(f, saved);
    bool hit = pelt__droplet_ray(f->wetness, f->mesh, f->surface, f->bvh, origin, direction,
                                 radius_world, wetness);
    water_end(f, saved);
    return hit;
}

void pelt_fur_add_random_droplets(pelt_fur *f, const pelt_rain *rain, unsigned count)
{
    unsigned saved[4];
    water_begin(f, saved);
    pelt__rain_random_drops(f->rain, rain, count, f->wetness, f->surface);
    water_end(f, saved);
}

void pelt_fur_set_rain(pelt_fur *f, const pelt_rain *rain) { pelt__rain_set(f->rain, rain); }

void pelt_fur_clear_wetness(pelt_fur *f) { pelt__wetness_clear(f->wetness); }

void pelt_fur_set_rain_rate(pelt_fur *f, float rate) { pelt__rain_set_rate(f->rain, rate); }

void pelt_fur_set_dry_rate(pelt_fur *f, float rate)
{
    f->dry_rate = isfinite(rate) && rate > 0.0f ? rate : 0.0f;
}

pelt_status pelt_fur_paint_wetness(pelt_fur *f, const uint8_t *grey, unsigned w, unsigned h,
                                   float wetness, pelt_error *err)
{
    if (!grey || w == 0 || h == 0)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "wetness image is empty");
    /* Scale the grey levels by `wetness` into a copy the painter reads. */
    const pelt_allocator *a = &f->desc.hooks.allocator;
    uint8_t *scaled = pelt__alloc_zero(a, (size_t)w * h, 1);
    if (!scaled) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for a %ux%u image", w, h);
    float k = clampf(wetness, 0.0f, 1.0f);
    for (size_t i = 0; i < (size_t)w * h; i++) scaled[i] = (uint8_t)(grey[i] * k + 0.5f);
    unsigned saved[4];
    water_begin(f, saved);
    pelt_status st = pelt__wetness_paint_image(f->wetness, scaled, w, h, NULL, err);
    water_end(f, saved);
    pelt__free(a, scaled);
    return st;
}

unsigned pelt_fur_mask_size(const pelt_fur *f) { return f->wetness->width; }

void pelt_fur_mask_picture(const pelt_fur *f, uint8_t *rgba) { pelt__wetness_to_rgba8(f->wetness, rgba); }
