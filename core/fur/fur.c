/* pelt_fur: parameters, synthesized fur texture and per-vertex fur state. */
#include "core/fur/fur_internal.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/fur/fur_shape.h"
#include "core/fur/fur_params.h"
#include "core/fur/furtex.h"
#include "core/mesh/triangle_area.h"
#include "core/base/vec.h"
#include "core/base/workers.h"
#include "core/wet/clump.h"
#include "core/wet/picture.h"
#include "pelt/dynamics.h"
#include "pelt/wetness.h"

#include <stdlib.h>
#include <string.h>

void pelt__fur_desc_defaults(pelt_fur_desc *d, const pelt_mesh *mesh)
{
    size_t count;
    const pelt_param *rows = pelt_fur_params(&count);
    pelt__params_defaults(rows, count, d);
    /* The defaults the rows call derived: they scale with the mesh or
       follow other fields. */
    float diag = mesh ? pelt_mesh_diagonal(mesh) : 1.0f;
    if (!(diag > 0.0f)) diag = 1.0f;
    if (d->length == 0.0f) d->length = 0.03f * diag;
    /* Tiles per world unit: five fur tiles across the bounding diagonal. */
    if (d->look.tiling == 0.0f) d->look.tiling = 5.0f / diag;
    if (d->dynamics.spring_k == 0.0f) d->dynamics.spring_k = d->dynamics.mass * 9.81f / (0.4f * d->length);
    if (d->dynamics.damping == 0.0f) d->dynamics.damping = 0.5f * sqrtf(d->dynamics.spring_k * d->dynamics.mass);
    if (d->fins.density == 0.0f) d->fins.density = (float)d->look.texture_size / 16.0f;
    /* The same hair at every texture size: texture_size only resolves it. */
    if (d->look.strand_radius == 0.0f) d->look.strand_radius = 1.6f * (float)d->look.texture_size / 256.0f;
    if (d->wet.clump_size == 0.0f) {
        /* Wet tufts about as wide as the hair is long, holding tens of
           hairs: between 20 and 100 at the texture's density. */
        float hairs_per_area = d->look.density * d->look.tiling * d->look.tiling;
        float lo = sqrtf(20.0f / hairs_per_area), hi = sqrtf(100.0f / hairs_per_area);
        d->wet.clump_size = d->length < lo ? lo : d->length > hi ? hi : d->length;
    }
    d->layers = pelt__fur_curl_layers(d);
}

float pelt__fur_curl_turns(const pelt_fur_desc *d)
{
    float turns = 0.0f;
    if (d->look.curl_radius > 0.0f) turns += fabsf(d->look.curl_frequency) / 6.2831853f;
    if (d->look.strand_curl > 0.0f) turns += fabsf(d->look.strand_curl_turns);
    return turns;
}

/* A shell draws its slab of a curled hair flat: the arc the hair turns
 * through within it, at one height. 32 shells give the six turns of Silva
 * Fig. 7d's many small curls 67 degrees each, and the helix reads as rings
 * printed one above the other (docs/method.md); layers_per_turn shells a
 * turn keep it a helix. */
unsigned pelt__fur_curl_layers(const pelt_fur_desc *d)
{
    float need = ceilf(pelt__fur_curl_turns(d) * d->layers_per_turn - 1e-3f);
    if (!(need > (float)d->layers)) return d->layers;
    return need < 256.0f ? (unsigned)need : 256u;
}

bool pelt__fur_has_ringlets(const pelt_fur_desc *d)
{
    return d->look.curl_phase != PELT_CURL_COHERENT && d->look.curl_radius > 0.0f;
}

float pelt__fur_vertex_curl_radius(const pelt_fur_desc *d)
{
    return pelt__fur_has_ringlets(d) ? 0.0f : d->look.curl_radius;
}

float pelt__fur_clump_lean(const pelt_fur_desc *d)
{
    return d->wet.clumps == PELT_CLUMPS_NATURAL ? d->wet.clump_lean : 0.0f;
}

float pelt__fur_wet_lie(const pelt_fur_desc *d)
{
    return d->wet.lie * 3.14159265f / 180.0f;
}

/* Every field in its row's range (core/fur/fur_params.c), then what one
 * row cannot say alone. */
static pelt_status check_desc(const pelt_fur_desc *d, pelt_error *err)
{
    size_t count;
    const pelt_param *rows = pelt_fur_params(&count);
    pelt_status st = pelt__params_check(rows, count, d, "fur", err);
    if (st != PELT_OK) return st;
    if (d->fins.density > (float)d->look.texture_size)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "fur fins.density %g must be at most look.texture_size %u",
                          (double)d->fins.density, d->look.texture_size);
    return PELT_OK;
}

/* Fur-texture coordinates in tiles. With an atlas the mesh carries patch
 * coordinates already; otherwise the mesh uvs are scaled by the mean
 * world length of one uv unit along u and along v, so hairs come out round
 * whatever the uv map's aspect (the torus's uv square is 2.5x longer
 * around the hole than around the tube). */
static void compute_fur_uvs(const pelt_mesh_data *m, float tiling, float *out, float fur_per_uv[2])
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
        /* Locks a few curl radii across, in texels of the full curl for
         * every curl level. */
        if (d->look.curl_phase == PELT_CURL_RINGLETS) td.ringlet_lock = d->look.curl_lock * td.ringlet_radius;
    }
    return td;
}

/* Level k of the ringlets holds the curl at 1 - k / (levels - 1) of its
 * full radius; without ringlets the one level is the texture as it is. */
static float ringlet_level_radius(float full, unsigned k, unsigned levels)
{
    return levels > 1 ? full * (1.0f - (float)k / (float)(levels - 1)) : full;
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
    const pelt_mesh_data mesh_data = pelt_mesh_get_data(mesh);
    f->texture_slices = d.layers + 1;
    pelt__furtex_desc td = pelt__fur_texture_desc(&d);
    f->ringlet_levels = pelt__fur_has_ringlets(&d) ? PELT__RINGLET_LEVELS : 1;
    size_t bytes = pelt__furtex_bytes(&td);
    f->texture = bytes ? pelt__alloc_zero(a, f->ringlet_levels, bytes) : NULL;
    f->fur_uvs = pelt__alloc_zero(a, mesh_data.vertex_count, 2 * sizeof(float));
    pelt__strand_params sp = {d.length, d.dynamics.spring_k, d.dynamics.mass, d.dynamics.damping, d.seed};
    st = pelt__strands_create(mesh, &sp, &f->desc.hooks.allocator, &f->strands, err);
    if (st != PELT_OK) {
        pelt_fur_destroy(f);
        return st;
    }
    f->tips = pelt__strands_tip_offsets(f->strands);
    st = pelt__workers_create(d.dynamics.threads, a, &d.hooks.logger, &f->workers, err);
    if (st != PELT_OK) {
        pelt_fur_destroy(f);
        return st;
    }
    pelt__strands_set_workers(f->strands, f->workers);
    st = pelt__bvh_build(mesh, &f->desc.hooks.allocator, &f->bvh, err);
    pelt__water_desc wd = {d.wet.mask_size, d.wet.clumps == PELT_CLUMPS_NATURAL ? d.wet.clump_size : 0.0f, d.seed};
    if (st == PELT_OK) st = pelt__water_create(mesh, f->bvh, &wd, &f->desc.hooks.allocator, &f->water, err);
    if (st == PELT_OK) st = pelt__groom_init(&f->groom, mesh_data.vertex_count, &f->desc.hooks.allocator, err);
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
    f->fin_texture = fin_bytes ? pelt__alloc_zero(a, f->ringlet_levels, fin_bytes) : NULL;
    if (!f->texture || !f->fur_uvs || !f->fin_texture) {
        pelt_fur_destroy(f);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the fur texture (%zu bytes)", bytes);
    }
    float full = td.ringlet_radius;
    for (unsigned k = 0; k < f->ringlet_levels; k++) {
        pelt__furtex_desc level = td;
        level.ringlet_radius = ringlet_level_radius(full, k, f->ringlet_levels);
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
    /* The fins hold the same ringlet levels: wet fins lose their curl too. */
    for (unsigned k = 0; k < f->ringlet_levels; k++) {
        pelt__fintex_desc level = fd;
        level.hair.ringlet_radius = ringlet_level_radius(full, k, f->ringlet_levels);
        pelt__fintex_generate(&level, f->fin_texture + (size_t)k * fin_bytes);
    }
    f->fin_width = d.look.texture_size;
    f->fin_height = fd.height;
    compute_fur_uvs(&mesh_data, d.look.tiling, f->fur_uvs, f->fur_per_uv);
    f->tips_version = 1;
    *out = f;
    return PELT_OK;
}

pelt_status pelt_fur_desc_curl_preset(pelt_fur_desc *d, const pelt_mesh *mesh, const char *name,
                                      pelt_error *err)
{
    float omega = 0.0f, radius_fraction = 0.0f;
    if (!name || !pelt__curl_preset(name, &omega, &radius_fraction))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "unknown curl preset '%s' (%s, %s, %s, %s)",
                          name ? name : "(null)", pelt_curl_preset_names[0], pelt_curl_preset_names[1],
                          pelt_curl_preset_names[2], pelt_curl_preset_names[3]);
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
    pelt__workers_destroy(f->workers);
    pelt__water_destroy(f->water);
    pelt__bvh_destroy(f->bvh);
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

/* Water's weight on the strands (docs/dynamics.md, Wet fur hangs): the
 * strand of a vertex at wetness rho carries wet.weight * rho of its tip's
 * mass, rho the mask's texel at the vertex's uv (the one the shells'
 * vertex stage reads). Dry fur costs one test a step. */
static void water_load(pelt_fur *f)
{
    const pelt__wetness *mask = pelt__water_mask(f->water);
    const bool wet = !pelt__rect_empty(mask->wet);
    if (!wet && !f->water_loaded) return;
    float *load = pelt__strands_water_load(f->strands);
    const pelt_mesh_data m = pelt_mesh_get_data(f->mesh);
    const float weight = f->desc.wet.weight;
    for (size_t i = 0; i < m.vertex_count; i++)
        load[i] = wet ? weight * pelt__clump_texel(mask->texels, mask->width, mask->height, m.uvs + 2 * i)[3]
                      : 0.0f;
    f->water_loaded = wet;
}

void pelt_fur_step(pelt_fur *f, float dt, const pelt_forces *forces)
{
    if (!(dt > 0.0f)) return;
    water_load(f);
    pelt__strands_step(f->strands, dt, forces, f->time);
    pelt__water_step(f->water, dt);
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
    return pelt__water_drop_uv(f->water, d, 1, err);
}

pelt_status pelt_fur_add_droplets(pelt_fur *f, const pelt_droplet *d, size_t count, pelt_error *err)
{
    return pelt__water_drop_uv(f->water, d, count, err);
}

pelt_status pelt_fur_add_droplet_at(pelt_fur *f, size_t triangle, const float bary[3],
                                    float radius_world, float wetness, pelt_error *err)
{
    return pelt__water_drop_at(f->water, triangle, bary, radius_world, wetness, err);
}

bool pelt_fur_add_droplet_ray(pelt_fur *f, const float origin[3], const float direction[3],
                              float radius_world, float wetness)
{
    return pelt__water_drop_ray(f->water, origin, direction, radius_world, wetness);
}

void pelt_fur_add_random_droplets(pelt_fur *f, const pelt_rain *rain, unsigned count)
{
    pelt__water_random_drops(f->water, rain, count);
}

void pelt_fur_set_rain(pelt_fur *f, const pelt_rain *rain) { pelt__water_set_rain(f->water, rain); }

void pelt_fur_clear_wetness(pelt_fur *f) { pelt__water_clear(f->water); }

void pelt_fur_set_rain_rate(pelt_fur *f, float rate) { pelt__water_set_rain_rate(f->water, rate); }

void pelt_fur_set_dry_rate(pelt_fur *f, float rate) { pelt__water_set_dry_rate(f->water, rate); }

pelt_status pelt_fur_paint_wetness(pelt_fur *f, const uint8_t *grey, unsigned w, unsigned h,
                                   float wetness, pelt_error *err)
{
    return pelt__water_paint(f->water, grey, w, h, wetness, &f->desc.hooks.allocator, err);
}

unsigned pelt_fur_mask_size(const pelt_fur *f) { return pelt__water_mask(f->water)->width; }

void pelt_fur_mask_picture(const pelt_fur *f, uint8_t *rgba) { pelt__wetness_to_rgba8(pelt__water_mask(f->water), rgba); }
