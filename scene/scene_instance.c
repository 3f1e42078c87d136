/* A scene made real: mesh, atlas, fur, colour, water, camera and clock
 * (pelt/scene_instance.h). The one path from a scene file to fur. */
#include "pelt/scene_instance.h"

#include "pelt/atlas.h"
#include "pelt/dynamics.h"
#include "pelt/groom.h"
#include "pelt/wetness.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/vec.h"
#include "scene/scene_image.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stb_image.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Degrees to radians; the framed camera's distance beyond the tightest
 * fit (pelt_camera_frame), so the outermost hair keeps off the edge. */
#define PI_DEG (3.14159265358979f / 180.0f)
#define FRAME_MARGIN 0.04f

struct pelt_scene_instance {
    pelt_hooks hooks;
    pelt_scene scene;       /* a copy; owns its wind keys, never droplets */
    pelt_mesh *mesh;
    pelt_fur *fur;
    pelt_camera camera;     /* the scene's, framed on a mesh file */
    pelt_view view;
    float time;
    bool armed;             /* past the settling: the rain schedule runs */
    bool rain_override;     /* set_rain_rate: the schedule no longer applies */
    bool animated;          /* animation.name plays: the mesh is posed each step */
    size_t animation;       /* which one */
    float *pose;            /* room for a pose: positions, normals (3 n each), tangents (4 n) */
    float up_fix[16];       /* turns the mesh's up axis to +Y (mesh.up) */
    pelt_scene_instance_stats stats;
};

static pelt_status load_mesh(const pelt_scene_mesh *m, pelt_mesh **mesh, pelt_error *err)
{
    switch (m->shape) {
    case PELT_SHAPE_TORUS:
        return pelt_mesh_torus(m->major_radius, m->minor_radius, m->major_segments,
                               m->minor_segments, mesh, err);
    case PELT_SHAPE_SPHERE:
        return pelt_mesh_sphere(m->radius, m->slices, m->stacks, mesh, err);
    case PELT_SHAPE_SQUARE:
        return pelt_mesh_square(m->size, m->subdivisions, mesh, err);
    case PELT_SHAPE_FILE:
        return pelt_mesh_load(m->file, mesh, err);
    }
    return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "mesh.shape: unknown shape %d", (int)m->shape);
}

/* Gives a mesh file an atlas (Lengyel §2.1): its own uvs when they are a
 * valid injective map, else patches; procedural shapes keep their uvs
 * unless the scene asks for patches. Replaces inst->mesh with the atlas
 * mesh and sets *mask_size to the atlas's (the mask is the atlas's space). */
static pelt_status build_atlas(pelt_scene_instance *inst, const char *cache_dir,
                               unsigned *mask_size, pelt_error *err)
{
    const pelt_scene *sc = &inst->scene;
    if (sc->mesh.shape != PELT_SHAPE_FILE && sc->atlas.mode != PELT_ATLAS_PATCHES)
        return PELT_OK;
    char cache[1024];
    pelt_atlas_desc ad = sc->atlas;
    ad.mask_size = sc->fur.wet.mask_size; /* 0: the atlas picks, growing with the mesh */
    /* The same fur density as pelt_fur_create's default: 5 tiles per diagonal. */
    float diag = pelt_mesh_diagonal(inst->mesh);
    ad.texel_density = sc->atlas.texel_density > 0.0f ? sc->atlas.texel_density
                       : diag > 0.0f                  ? 5.0f / diag
                                                      : 0.0f;
    if (sc->atlas_direction_from == PELT_DIRECTION_VERTEX_COLORS) {
        ad.vertex_directions = pelt_mesh_directions(inst->mesh);
        if (!ad.vertex_directions)
            return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                              "atlas.direction_from is \"vertex-colors\" but '%s' has no vertex colours",
                              sc->mesh.file);
    }
    ad.seed = sc->fur.seed;
    if (!cache_dir) cache_dir = pelt_atlas_default_cache_dir(cache, sizeof cache) ? cache : NULL;
    ad.cache_dir = cache_dir;
    ad.hooks = inst->hooks; /* the uv warning reaches our logger from there */
    pelt_atlas *atlas = NULL;
    pelt_error aerr = {0};
    if (pelt_atlas_create(inst->mesh, &ad, &atlas, &aerr) != PELT_OK)
        return pelt__fail(err, aerr.status, "atlas: %s", aerr.message);
    const pelt_atlas_stats *st = pelt_atlas_get_stats(atlas);
    *mask_size = st->mask_size;
    inst->stats.atlas_seconds = st->build_seconds;
    inst->stats.atlas_from_cache = st->from_cache;
    inst->stats.atlas_patches = st->mode_used == PELT_ATLAS_PATCHES ? st->patch_count : 0;
    pelt_mesh *split = pelt_atlas_take_mesh(atlas);
    pelt_atlas_destroy(atlas);
    if (!split) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "atlas: out of memory");
    pelt_mesh_destroy(inst->mesh);
    inst->mesh = split;
    return PELT_OK;
}

/* The colour texture: an image file or a procedural pattern. */
static pelt_status apply_color(pelt_scene_instance *inst, pelt_error *err)
{
    const pelt_scene *sc = &inst->scene;
    pelt_error e = {0};
    if (sc->texture.image[0]) {
        int w, h;
        uint8_t *rgba;
        pelt_status st = pelt__scene_load_image("texture.image", sc->texture.image, 4, &rgba, &w, &h, err);
        if (st != PELT_OK) return st;
        st = pelt_fur_set_color_texture(inst->fur, rgba, (unsigned)w, (unsigned)h, &e);
        stbi_image_free(rgba);
        if (st != PELT_OK)
            return pelt__fail(err, st, "texture.image '%s': %s", sc->texture.image, e.message);
        return PELT_OK;
    }
    if (sc->texture.pattern != PELT_COLOR_PATTERN_NONE) {
        pelt_status st = pelt_fur_set_color_pattern(inst->fur, sc->texture.pattern, sc->fur.seed, &e);
        if (st != PELT_OK) return pelt__fail(err, st, "texture.pattern: %s", e.message);
    }
    return PELT_OK;
}

/* Droplets, random drops and a painted image at time 0. */
static pelt_status apply_water(pelt_scene_instance *inst, const pelt_scene *sc, pelt_error *err)
{
    const pelt_scene_wetness *w = &sc->wetness;
    pelt_error e = {0};
    for (size_t i = 0; i < w->droplet_count; i++)
        if (pelt_fur_add_droplet(inst->fur, &w->droplets[i], &e) != PELT_OK)
            return pelt__fail(err, e.status, "wetness.droplets[%zu]: %s", i, e.message);
    if (w->drops) {
        pelt_rain r = {0.0f, w->drops_radius[0], w->drops_radius[1], w->drops_wetness[0],
                       w->drops_wetness[1], w->drops_seed};
        pelt_fur_add_random_droplets(inst->fur, &r, w->drops);
    }
    if (w->mask_image[0]) {
        int iw, ih;
        uint8_t *grey;
        pelt_status st = pelt__scene_load_image("wetness.mask_image", w->mask_image, 1, &grey, &iw, &ih, err);
        if (st != PELT_OK) return st;
        st = pelt_fur_paint_wetness(inst->fur, grey, (unsigned)iw, (unsigned)ih,
                                    w->mask_image_wetness, &e);
        stbi_image_free(grey);
        if (st != PELT_OK)
            return pelt__fail(err, st, "wetness.mask_image '%s': %s", w->mask_image, e.message);
    }
    return PELT_OK;
}

/* One groom map: an image file read as RGBA into one field. */
static pelt_status apply_map(pelt_scene_instance *inst, const char *key, const char *path,
                             pelt_groom_field field, float lo, float hi, pelt_error *err)
{
    if (!path[0]) return PELT_OK;
    int w, h;
    uint8_t *rgba;
    pelt_status st = pelt__scene_load_image(key, path, 4, &rgba, &w, &h, err);
    if (st != PELT_OK) return st;
    pelt_error e = {0};
    st = pelt_fur_groom_from_image(inst->fur, field, rgba, (unsigned)w, (unsigned)h, lo, hi, &e);
    stbi_image_free(rgba);
    if (st != PELT_OK) return pelt__fail(err, st, "%s '%s': %s", key, path, e.message);
    return PELT_OK;
}

/* Grooming (Lengyel et al. §3): maps, vertex colours, the groom file, in
 * that order; the strokes come once the camera is placed. */
static pelt_status apply_groom(pelt_scene_instance *inst, pelt_error *err)
{
    const pelt_scene_groom *g = &inst->scene.groom;
    pelt_status st = apply_map(inst, "fur.length_map", g->length_map, PELT_GROOM_LENGTH,
                               g->length_range[0], g->length_range[1], err);
    if (st == PELT_OK)
        st = apply_map(inst, "fur.density_map", g->density_map, PELT_GROOM_DENSITY,
                       g->density_range[0], g->density_range[1], err);
    if (st == PELT_OK)
        st = apply_map(inst, "fur.flow_map", g->flow_map, PELT_GROOM_FLOW, 0.0f, g->flow_strength, err);
    if (st == PELT_OK)
        st = apply_map(inst, "fur.color_map", g->color_map, PELT_GROOM_COLOR, 0.0f, 1.0f, err);
    if (st != PELT_OK) return st;
    pelt_error e = {0};
    if (g->vertex_colors == PELT_VERTEX_COLORS_HAIR &&
        pelt_fur_groom_from_vertex_colors(inst->fur, &e) != PELT_OK)
        return pelt__fail(err, e.status, "fur.vertex_colors is \"hair\" but %s has no vertex colours",
                          inst->scene.mesh.shape == PELT_SHAPE_FILE ? inst->scene.mesh.file
                                                                    : "a procedural mesh");
    if (g->file[0] && pelt_fur_load_groom(inst->fur, g->file, &e) != PELT_OK)
        return pelt__fail(err, e.status, "fur.groom: %s", e.message);
    return PELT_OK;
}

/* How far the fur reaches from vertex i (mesh units): the strand's length
 * (the fins' hair may be longer), sheared by the comb and the groom's lean,
 * plus the curl's radius; grooming scales all of it. */
static float fur_reach(const pelt_fur_desc *d, const pelt_groom_value *g)
{
    float slant = tanf(clampf(d->comb.slant, 0.0f, 60.0f) * PI_DEG);
    float lean = sqrtf(g->lean[0] * g->lean[0] + g->lean[1] * g->lean[1]);
    float length = d->length * fmaxf(1.0f, d->fins.length);
    return g->length * (length * (1.0f + slant + lean) + fabsf(d->look.curl_radius));
}

/* mesh.up: the rotation that takes the mesh's up axis to +Y. */
static void up_rotation(const pelt_scene *sc, const pelt_mesh *mesh, float m[16])
{
    static const float axes[7][3] = {{0, 0, 0}, {0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}};
    float up[3];
    if (sc->mesh.up == PELT_UP_FILE) pelt_mesh_up(mesh, up);
    else memcpy(up, axes[sc->mesh.up], sizeof up);
    memset(m, 0, 16 * sizeof *m);
    m[15] = 1.0f;
    /* The columns are where x, y, z go: up goes to +Y. */
    int a = fabsf(up[0]) > 0.5f ? 0 : fabsf(up[2]) > 0.5f ? 2 : 1;
    float s = up[a] < 0.0f ? -1.0f : 1.0f;
    if (a == 1) { /* +Y: identity; -Y: half a turn about X */
        m[0] = 1.0f, m[5] = s, m[10] = s;
    } else if (a == 2) { /* +Z to +Y: a quarter turn about X */
        m[0] = 1.0f, m[6] = -s, m[9] = s;
    } else { /* +X to +Y: a quarter turn about Z */
        m[1] = s, m[4] = -s, m[10] = 1.0f;
    }
}

/* The model matrix at time t: the scene's placement after mesh.up. */
static void place_at(pelt_scene_instance *inst, float t)
{
    float placed[16];
    pelt_scene_model_at(&inst->scene, t, placed);
    for (int c = 0; c < 4; c++)
        for (int i = 0; i < 4; i++)
            inst->view.model[4 * c + i] = placed[i] * inst->up_fix[4 * c] + placed[4 + i] * inst->up_fix[4 * c + 1] +
                                          placed[8 + i] * inst->up_fix[4 * c + 2] +
                                          placed[12 + i] * inst->up_fix[4 * c + 3];
}

/* A mesh file seen through the default camera is framed (pelt_camera_frame):
 * the camera aims at the centre of the bounding sphere of the mesh and its
 * fur as placed at time 0 (mesh.up, mesh.rotation, mesh.scale; posed when
 * an animation plays), from a three-quarter view about +Y, at the distance
 * that fits it in the picture. Any camera key keeps the scene's camera as
 * it is. Out of memory keeps it too. */
static void frame_camera(pelt_scene_instance *inst)
{
    const pelt_scene *sc = &inst->scene;
    inst->camera = sc->camera;
    pelt_scene defaults;
    pelt_scene_defaults(&defaults);
    bool default_camera = !memcmp(&sc->camera, &defaults.camera, sizeof sc->camera);
    pelt_scene_free(&defaults);
    if (sc->mesh.shape != PELT_SHAPE_FILE || !default_camera) return;
    pelt_mesh_data md = pelt_mesh_get_data(inst->mesh);
    size_t n = md.vertex_count;
    float *pos = pelt__alloc_zero(&inst->hooks.allocator, n, 4 * sizeof(float));
    if (!pos) return;
    float *reach = pos + 3 * n;
    float model[16];
    place_at(inst, 0.0f);
    memcpy(model, inst->view.model, sizeof model);
    const float *at = md.positions;
    if (inst->animated) {
        float *p = inst->pose, *nrm = p + 3 * n, *tan = p + 6 * n;
        if (pelt_mesh_pose(inst->mesh, inst->animation, 0.0f, p, nrm, tan, NULL) == PELT_OK) at = p;
    }
    float scale = sqrtf(model[0] * model[0] + model[1] * model[1] + model[2] * model[2]);
    pelt_fur_desc fd = pelt_fur_get_desc(inst->fur);
    for (size_t i = 0; i < n; i++) {
        v3_store(pos + 3 * i, pelt__mat4_apply(model, v3_load(at + 3 * i), 1.0f));
        pelt_groom_value g = pelt_fur_get_groom(inst->fur, i);
        reach[i] = scale * fur_reach(&fd, &g);
    }
    float aspect = (float)sc->output.width / (float)sc->output.height;
    pelt_camera_frame(&inst->camera, pos, reach, n, aspect, FRAME_MARGIN);
    pelt__free(&inst->hooks.allocator, pos);
}

/* Places the mesh and steps the fur by dt under the forces of time t. */
static void step_at(pelt_scene_instance *inst, float t, float dt)
{
    const pelt_scene *sc = &inst->scene;
    place_at(inst, t);
    pelt_fur_set_transform(inst->fur, inst->view.model, NULL);
    if (inst->animated) {
        size_t n = pelt_mesh_get_data(inst->mesh).vertex_count;
        float *p = inst->pose, *nrm = p + 3 * n, *tan = p + 6 * n;
        if (pelt_mesh_pose(inst->mesh, inst->animation, t, p, nrm, tan, NULL) == PELT_OK)
            pelt_fur_set_pose(inst->fur, p, nrm, tan, NULL);
    }
    pelt_forces forces = sc->forces;
    pelt_scene_wind_at(sc, t, forces.wind);
    const pelt_scene_wetness *w = &sc->wetness;
    bool raining = t >= w->rain_start && (w->rain_stop == 0.0f || t < w->rain_stop);
    if (inst->armed)
        pelt_fur_set_rain_rate(inst->fur, raining || inst->rain_override ? w->rain.rate : 0.0f);
    pelt_fur_step(inst->fur, dt, &forces);
}

/* World units to mesh units: the model matrix's scale (uniform). */
static float mesh_units(const pelt_view *v)
{
    float s = sqrtf(v->model[0] * v->model[0] + v->model[1] * v->model[1] + v->model[2] * v->model[2]);
    return s > 0.0f && isfinite(s) ? 1.0f / s : 1.0f;
}

/* A brush where the ray through pixel (px, py) meets the mesh: radius
 * and delta in world units, plus a drag in pixels turned into a delta
 * across the view plane at the hit's distance from the eye. */
static bool brush_at_pixel(pelt_scene_instance *inst, float px, float py, const pelt_brush *b,
                           const float drag[2])
{
    const pelt_view *v = &inst->view;
    float o[3], d[3], p[3];
    if (!pelt_view_pixel_ray(v, px, py, o, d) || !pelt_fur_pick(inst->fur, o, d, p)) return false;
    float scale = mesh_units(v);
    pelt_brush local = *b;
    local.radius = b->radius * scale;
    for (int k = 0; k < 3; k++) local.delta[k] = b->delta[k] * scale;
    if (drag && (drag[0] != 0.0f || drag[1] != 0.0f)) {
        float o2[3], d2[3];
        if (!pelt_view_pixel_ray(v, px + drag[0], py + drag[1], o2, d2)) return false;
        pelt_vec3 to_hit = v3_sub(v3_load(p), v3_load(o));
        pelt_vec3 dir2 = v3_norm_or(v3_load(d2), v3(0.0f, 0.0f, 0.0f));
        float q[3];
        v3_store(q, v3_mad(v3_load(o2), dir2, v3_len(to_hit)));
        for (int k = 0; k < 3; k++) local.delta[k] += q[k] - p[k];
    }
    return pelt_fur_brush(inst->fur, p, &local, NULL, NULL) == PELT_OK;
}

/* The scene's strokes, on the first frame's view. */
static pelt_status apply_strokes(pelt_scene_instance *inst, const pelt_scene *sc, pelt_error *err)
{
    for (size_t i = 0; i < sc->groom.stroke_count; i++) {
        const pelt_scene_stroke *s = &sc->groom.strokes[i];
        if (isfinite(s->at[0])) {
            /* World radius and delta to mesh units, as at a pixel. */
            pelt_brush local = s->brush;
            float scale = mesh_units(&inst->view);
            local.radius *= scale;
            for (int k = 0; k < 3; k++) local.delta[k] *= scale;
            pelt_error e = {0};
            if (pelt_fur_brush(inst->fur, s->at, &local, NULL, &e) != PELT_OK)
                return pelt__fail(err, e.status, "strokes[%zu]: %s", i, e.message);
            continue;
        }
        if (!brush_at_pixel(inst, s->pixel[0], s->pixel[1], &s->brush, s->drag))
            return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                              "strokes[%zu]: pixel (%g, %g) does not see the mesh", i,
                              (double)s->pixel[0], (double)s->pixel[1]);
    }
    return PELT_OK;
}

/* The copy keeps the wind keys (advance reads them) and drops the
 * droplets and strokes (used once, at instantiation, from the caller's
 * scene). */
static pelt_status copy_scene(pelt_scene_instance *inst, const pelt_scene *sc, pelt_error *err)
{
    inst->scene = *sc;
    inst->scene.wetness.droplets = NULL;
    inst->scene.wetness.droplet_count = 0;
    inst->scene.animation.wind_keys = NULL;
    inst->scene.animation.wind_key_count = 0;
    inst->scene.groom.strokes = NULL;
    inst->scene.groom.stroke_count = 0;
    size_t n = sc->animation.wind_key_count;
    if (n && sc->animation.wind_keys) {
        pelt_wind_key *keys = pelt__alloc_zero(&inst->hooks.allocator, n, sizeof *keys);
        if (!keys) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for %zu wind keys", n);
        memcpy(keys, sc->animation.wind_keys, n * sizeof *keys);
        inst->scene.animation.wind_keys = keys;
        inst->scene.animation.wind_key_count = n;
    }
    return PELT_OK;
}

/* animation.name: which animation plays, and room for its poses. */
static pelt_status arm_animation(pelt_scene_instance *inst, pelt_error *err)
{
    const pelt_scene *sc = &inst->scene;
    pelt_error e = {0};
    if (pelt_mesh_find_animation(inst->mesh, sc->animation.name, &inst->animation, &e) != PELT_OK)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "animation.name: %s: %s",
                          sc->mesh.shape == PELT_SHAPE_FILE ? sc->mesh.file : "the procedural mesh", e.message);
    size_t n = pelt_mesh_get_data(inst->mesh).vertex_count;
    inst->pose = pelt__alloc_zero(&inst->hooks.allocator, n, 10 * sizeof(float));
    if (!inst->pose) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the animation's poses");
    inst->animated = true;
    return PELT_OK;
}

static pelt_status instantiate(pelt_scene_instance *inst, const pelt_scene *sc,
                               const pelt_scene_instance_desc *desc, pelt_error *err)
{
    pelt_status st = copy_scene(inst, sc, err);
    if (st == PELT_OK) st = load_mesh(&sc->mesh, &inst->mesh, err);
    if (st == PELT_OK && sc->mesh.simplify > 0 && sc->mesh.simplify < pelt_mesh_get_stats(inst->mesh).triangle_count) {
        pelt_mesh *coarse = NULL;
        st = pelt_mesh_simplify(inst->mesh, sc->mesh.simplify, &coarse, err);
        pelt_mesh_destroy(inst->mesh);
        inst->mesh = coarse;
    }
    /* What validation dropped is the loaded mesh's to tell: an atlas made
     * from it replaces it with a mesh that dropped nothing. */
    size_t dropped = st == PELT_OK ? pelt_mesh_get_stats(inst->mesh).dropped_degenerate : 0;
    unsigned mask_size = sc->fur.wet.mask_size;
    if (st == PELT_OK) st = build_atlas(inst, desc->cache_dir, &mask_size, err);
    if (st != PELT_OK) return st;
    pelt_mesh_stats ms = pelt_mesh_get_stats(inst->mesh);
    if (dropped)
        pelt__log(&inst->hooks.logger, PELT_LOG_WARNING, "%zu degenerate triangle(s) dropped",
                  dropped);
    if (ms.fallback_uvs)
        pelt__log(&inst->hooks.logger, PELT_LOG_WARNING,
                  "the mesh has no uvs; using a spherical fallback mapping (expect stretched fur "
                  "near the poles)");

    pelt_fur_desc fd = sc->fur;
    fd.wet.mask_size = mask_size;
    if (!fd.hooks.allocator.alloc && !fd.hooks.logger.func) fd.hooks = inst->hooks;
    if (sc->fur_preset[0]) {
        st = pelt_fur_desc_curl_preset(&fd, inst->mesh, sc->fur_preset, err);
        if (st != PELT_OK) return st;
    }
    st = pelt_fur_create(inst->mesh, &fd, &inst->fur, err);
    if (st == PELT_OK && sc->animation.name[0]) st = arm_animation(inst, err);
    if (st == PELT_OK) st = apply_color(inst, err);
    if (st == PELT_OK) st = apply_water(inst, sc, err);
    if (st == PELT_OK) st = apply_groom(inst, err);
    if (st != PELT_OK) return st;

    up_rotation(sc, inst->mesh, inst->up_fix);
    frame_camera(inst);
    const pelt_scene_output *o = &sc->output;
    pelt_camera_to_view(&inst->camera, (float)o->width / (float)o->height, &inst->view);
    inst->view.light = sc->light;
    inst->view.width = o->width;
    inst->view.height = o->height;
    place_at(inst, 0.0f);
    st = apply_strokes(inst, sc, err);
    if (st != PELT_OK) return st;

    /* Settle under the forces of time 0, so a still shows the fur bent by
     * gravity rather than mid-spring; rain and drying start afterwards. */
    float settle = desc->settle_seconds == 0.0f ? 1.5f : desc->settle_seconds;
    int settle_steps = settle > 0.0f ? (int)lroundf(settle * 60.0f) : 0;
    for (int i = 0; i < settle_steps; i++) step_at(inst, 0.0f, 1.0f / 60.0f);
    pelt_fur_set_rain(inst->fur, &sc->wetness.rain);
    pelt_fur_set_dry_rate(inst->fur, sc->wetness.dry_rate);
    inst->armed = true;
    return PELT_OK;
}

pelt_status pelt_scene_instantiate(const pelt_scene *sc, const pelt_scene_instance_desc *desc,
                                   pelt_scene_instance **out, pelt_error *err)
{
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_scene_instantiate: out is NULL");
    *out = NULL;
    if (!sc) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_scene_instantiate: scene is NULL");
    if (sc->output.width == 0 || sc->output.height == 0)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "output size must not be 0");
    pelt_scene_instance_desc d = desc ? *desc : (pelt_scene_instance_desc){0};
    pelt_status st = pelt__hooks_check(&d.hooks, "pelt_scene_instance_desc", err);
    if (st != PELT_OK) return st;
    pelt_hooks hooks = d.hooks;
    pelt_scene_instance *inst = pelt__alloc_zero(&hooks.allocator, 1, sizeof *inst);
    if (!inst) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory");
    inst->hooks = hooks;
    st = instantiate(inst, sc, &d, err);
    if (st != PELT_OK) {
        pelt_scene_instance_destroy(inst);
        return st;
    }
    *out = inst;
    return PELT_OK;
}

void pelt_scene_instance_destroy(pelt_scene_instance *inst)
{
    if (!inst) return;
    pelt_fur_destroy(inst->fur);
    pelt_mesh_destroy(inst->mesh);
    pelt__free(&inst->hooks.allocator, inst->scene.animation.wind_keys);
    pelt__free(&inst->hooks.allocator, inst->pose);
    pelt_allocator a = inst->hooks.allocator;
    pelt__free(&a, inst);
}

void pelt_scene_instance_advance(pelt_scene_instance *inst, float dt)
{
    if (!(dt > 0.0f) || !isfinite(dt)) return;
    inst->time += dt;
    step_at(inst, inst->time, dt);
}

float pelt_scene_instance_time(const pelt_scene_instance *inst) { return inst->time; }

const pelt_mesh *pelt_scene_instance_mesh(const pelt_scene_instance *inst) { return inst->mesh; }

pelt_fur *pelt_scene_instance_fur(pelt_scene_instance *inst) { return inst->fur; }

pelt_view pelt_scene_instance_view(const pelt_scene_instance *inst) { return inst->view; }

bool pelt_scene_instance_drop_at_pixel(pelt_scene_instance *inst, float px, float py, float radius,
                                       float wetness)
{
    float origin[3], dir[3];
    return pelt_view_pixel_ray(&inst->view, px, py, origin, dir) &&
           pelt_fur_add_droplet_ray(inst->fur, origin, dir, radius, wetness);
}

bool pelt_scene_instance_brush_at_pixel(pelt_scene_instance *inst, float px, float py,
                                        const pelt_brush *brush, const float drag[2])
{
    return inst && brush && brush_at_pixel(inst, px, py, brush, drag);
}

pelt_camera pelt_scene_instance_camera(const pelt_scene_instance *inst) { return inst->camera; }

void pelt_scene_instance_set_camera(pelt_scene_instance *inst, const pelt_camera *camera,
                                    unsigned width, unsigned height)
{
    if (!inst || !camera) return;
    inst->camera = *camera;
    pelt_view v;
    unsigned w = width ? width : inst->view.width, h = height ? height : inst->view.height;
    pelt_camera_to_view(&inst->camera, (float)w / (float)h, &v);
    memcpy(inst->view.view, v.view, sizeof v.view);
    memcpy(inst->view.proj, v.proj, sizeof v.proj);
    memcpy(inst->view.eye, v.eye, sizeof v.eye);
    inst->view.width = w;
    inst->view.height = h;
}

pelt_forces pelt_scene_instance_forces(const pelt_scene_instance *inst)
{
    pelt_forces f = inst->scene.forces;
    pelt_scene_wind_at(&inst->scene, inst->time, f.wind);
    return f;
}

void pelt_scene_instance_set_forces(pelt_scene_instance *inst, const pelt_forces *forces)
{
    if (!inst || !forces) return;
    inst->scene.forces = *forces;
    pelt__free(&inst->hooks.allocator, inst->scene.animation.wind_keys);
    inst->scene.animation.wind_keys = NULL;
    inst->scene.animation.wind_key_count = 0;
}

void pelt_scene_instance_set_rain_rate(pelt_scene_instance *inst, float rate)
{
    if (!inst || !(rate >= 0.0f) || !isfinite(rate)) return;
    inst->scene.wetness.rain.rate = rate;
    inst->rain_override = true;
    if (inst->armed) pelt_fur_set_rain_rate(inst->fur, rate);
}

pelt_scene_instance_stats pelt_scene_instance_get_stats(const pelt_scene_instance *inst)
{
    return inst->stats;
}
