/* Loading a scene into a headless context and drawing its frames. */
#include "apps/cli.h"

#include "pelt/atlas.h"

#include <epoxy/gl.h>
#include <errno.h>
#include <math.h>
#include <stb_image.h>
#include <stb_image_write.h>
#include <stdlib.h>
#include <string.h>

static pelt_status load_mesh(const pelt_scene *sc, pelt_mesh **mesh, pelt_error *err)
{
    const pelt_scene_mesh *m = &sc->mesh;
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
    return PELT_ERR_INVALID_ARGUMENT;
}

/* Gives a mesh file an atlas (Lengyel §2.1): its own uvs when they are a
 * valid injective map, else patches; procedural shapes keep their uvs
 * unless the scene asks for patches. Replaces *mesh with the atlas mesh. */
static bool build_atlas(const char *cmd, const pelt_scene *sc, pelt_mesh **mesh,
                        unsigned *mask_size, cli_session *s)
{
    if (sc->mesh.shape != PELT_SHAPE_FILE && sc->atlas.mode != PELT_ATLAS_PATCHES) return true;
    float lo[3], hi[3];
    pelt_mesh_bounds(*mesh, lo, hi);
    float dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    float diag = sqrtf(dx * dx + dy * dy + dz * dz);
    char cache[1024];
    pelt_atlas_desc ad = {0};
    ad.mode = (int)sc->atlas.mode;
    /* The atlas is the wetness mask's space: they share one size. The
     * default 256 grows with big meshes (the atlas picks it). */
    ad.mask_size = sc->fur.wet.mask_size;
    /* The same fur density as pelt_fur_create's default: 5 tiles per diagonal. */
    ad.texel_density = sc->atlas.texel_density > 0.0f ? sc->atlas.texel_density
                       : diag > 0.0f                  ? 5.0f / diag
                                                      : 0.0f;
    memcpy(ad.direction, sc->atlas.direction, sizeof ad.direction);
    if (sc->atlas.direction_from == PELT_DIRECTION_VERTEX_COLORS) {
        ad.vertex_directions = pelt_mesh_directions(*mesh);
        if (!ad.vertex_directions) {
            cli_error(cmd, "atlas.direction_from is \"vertex-colors\" but '%s' has no vertex colours",
                      sc->mesh.file);
            return false;
        }
    }
    ad.max_stretch = sc->atlas.max_stretch;
    ad.seed = sc->fur.seed;
    ad.cache_dir = pelt_atlas_default_cache_dir(cache, sizeof cache) ? cache : NULL;
    pelt_atlas *atlas = NULL;
    pelt_error err = {0};
    if (pelt_atlas_create(*mesh, &ad, &atlas, &err) != PELT_OK) {
        cli_error(cmd, "atlas: %s", err.message);
        return false;
    }
    const pelt_atlas_stats *st = pelt_atlas_get_stats(atlas);
    if (st->uv_warning[0])
        fprintf(stderr, "pelt %s: warning: not using the mesh's uvs: %s; grew %zu patches\n", cmd,
                st->uv_warning, st->patch_count);
    *mask_size = st->mask_size;
    s->atlas_seconds = st->build_seconds;
    s->atlas_from_cache = st->from_cache;
    pelt_mesh *split = pelt_atlas_take_mesh(atlas);
    pelt_atlas_destroy(atlas);
    if (!split) {
        cli_error(cmd, "atlas: out of memory");
        return false;
    }
    pelt_mesh_destroy(*mesh);
    *mesh = split;
    return true;
}

/* Loads an image with stb_image; errors name the scene key and the file,
 * with the system's reason when the file cannot be opened. */
static uint8_t *load_image(const char *cmd, const char *key, const char *path, int channels,
                           int *w, int *h)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        cli_error(cmd, "%s: cannot open '%s': %s", key, path, strerror(errno));
        return NULL;
    }
    int n;
    uint8_t *px = stbi_load_from_file(f, w, h, &n, channels);
    fclose(f);
    if (!px) cli_error(cmd, "%s: '%s' is not a readable image (%s)", key, path, stbi_failure_reason());
    return px;
}

/* The colour texture: an image file or a procedural pattern. */
static bool apply_color(const char *cmd, const pelt_scene *sc, pelt_fur *fur)
{
    pelt_error err = {0};
    if (sc->texture.image[0]) {
        int w, h;
        uint8_t *rgba = load_image(cmd, "texture.image", sc->texture.image, 4, &w, &h);
        if (!rgba) return false;
        pelt_status st = pelt_fur_set_color_texture(fur, rgba, (unsigned)w, (unsigned)h, &err);
        stbi_image_free(rgba);
        if (st != PELT_OK) {
            cli_error(cmd, "texture.image '%s': %s", sc->texture.image, err.message);
            return false;
        }
        return true;
    }
    if (sc->texture.pattern != PELT_COLOR_PATTERN_NONE &&
        pelt_fur_set_color_pattern(fur, sc->texture.pattern, sc->fur.seed,
                                   &err) != PELT_OK) {
        cli_error(cmd, "texture.pattern: %s", err.message);
        return false;
    }
    return true;
}

/* Droplets, random drops, a painted image, rain and drying from the scene. */
static bool apply_wetness(const char *cmd, const pelt_scene *sc, pelt_fur *fur)
{
    const pelt_scene_wetness *w = &sc->wetness;
    pelt_error err = {0};
    for (size_t i = 0; i < w->droplet_count; i++)
        if (pelt_fur_add_droplet(fur, &w->droplets[i], &err) != PELT_OK) {
            cli_error(cmd, "wetness.droplets[%zu]: %s", i, err.message);
            return false;
        }
    if (w->drops) {
        pelt_rain r = {0.0f, w->drops_radius[0], w->drops_radius[1], w->drops_wetness[0],
                       w->drops_wetness[1], w->drops_seed};
        pelt_fur_add_random_droplets(fur, &r, w->drops);
    }
    if (w->mask_image[0]) {
        int iw, ih;
        uint8_t *grey = load_image(cmd, "wetness.mask_image", w->mask_image, 1, &iw, &ih);
        if (!grey) return false;
        pelt_status st = pelt_fur_paint_wetness(fur, grey, (unsigned)iw, (unsigned)ih,
                                                w->mask_image_wetness, &err);
        stbi_image_free(grey);
        if (st != PELT_OK) {
            cli_error(cmd, "wetness.mask_image '%s': %s", w->mask_image, err.message);
            return false;
        }
    }
    return true;
}

bool cli_session_open(const char *cmd, const pelt_scene *sc, cli_session *s)
{
    memset(s, 0, sizeof *s);
    pelt_error err = {0};
    if (load_mesh(sc, &s->mesh, &err) != PELT_OK) {
        cli_error(cmd, "%s", err.message);
        return false;
    }
    unsigned mask_size = sc->fur.wet.mask_size;
    if (!build_atlas(cmd, sc, &s->mesh, &mask_size, s)) {
        cli_session_close(s);
        return false;
    }
    pelt_mesh_stats ms = pelt_mesh_get_stats(s->mesh);
    if (ms.dropped_degenerate)
        fprintf(stderr, "pelt %s: warning: %zu degenerate triangle(s) dropped\n", cmd,
                ms.dropped_degenerate);
    if (ms.fallback_uvs)
        fprintf(stderr, "pelt %s: warning: the mesh has no uvs; using a spherical fallback "
                        "mapping (expect stretched fur near the poles)\n", cmd);

    pelt_fur_desc fd = sc->fur;
    if (sc->fur_preset[0] && pelt_fur_desc_curl_preset(&fd, s->mesh, sc->fur_preset, &err) != PELT_OK) {
        cli_error(cmd, "%s", err.message);
        cli_session_close(s);
        return false;
    }
    fd.wet.mask_size = mask_size;
    if (pelt_fur_create(s->mesh, &fd, &s->fur, &err) != PELT_OK) {
        cli_error(cmd, "%s", err.message);
        cli_session_close(s);
        return false;
    }
    if (!apply_color(cmd, sc, s->fur) || !apply_wetness(cmd, sc, s->fur)) {
        cli_session_close(s);
        return false;
    }
    pelt_headless_desc hd = {sc->output.width, sc->output.height, sc->output.msaa, false};
    if (pelt_headless_create(&hd, &s->gl, &err) != PELT_OK ||
        pelt_renderer_create(s->mesh, s->fur, NULL, &s->renderer, &err) != PELT_OK) {
        cli_error(cmd, "%s", err.message);
        cli_session_close(s);
        return false;
    }
    s->pixels = malloc((size_t)sc->output.width * sc->output.height * 4);
    if (!s->pixels) {
        cli_error(cmd, "out of memory for a %ux%u image", sc->output.width, sc->output.height);
        cli_session_close(s);
        return false;
    }
    /* A mesh file seen through the default camera is framed: the camera
     * aims at the middle of its bounds from a distance that fits it. */
    pelt_camera cam = sc->camera;
    pelt_scene defaults;
    pelt_scene_defaults(&defaults);
    if (sc->mesh.shape == PELT_SHAPE_FILE &&
        !memcmp(&cam, &defaults.camera, sizeof cam)) {
        float lo[3], hi[3];
        pelt_mesh_bounds(s->mesh, lo, hi);
        float radius = 0.0f;
        for (int k = 0; k < 3; k++) {
            cam.target[k] = 0.5f * (lo[k] + hi[k]);
            radius += 0.25f * (hi[k] - lo[k]) * (hi[k] - lo[k]);
        }
        radius = sqrtf(radius);
        cam.distance = 0.8f * radius / sinf(cam.fov_y * 0.5f * 3.14159265f / 180.0f);
    }
    pelt_scene_free(&defaults);
    float aspect = (float)sc->output.width / (float)sc->output.height;
    pelt_camera_to_view(&cam, aspect, &s->view);
    s->view.light = sc->light;
    s->view.width = sc->output.width;
    s->view.height = sc->output.height;
    /* Let the fur settle under the forces of time 0 before the first
     * frame, so a still shows it bent by gravity rather than mid-spring. */
    for (int i = 0; i < 90; i++) cli_session_advance(s, sc, 0.0f, 1.0f / 60.0f);
    /* Rain and drying start with the first frame, not during the settling. */
    pelt_fur_set_rain(s->fur, &sc->wetness.rain);
    pelt_fur_set_dry_rate(s->fur, sc->wetness.dry_rate);
    s->settled = true;
    return true;
}

void cli_session_close(cli_session *s)
{
    pelt_renderer_destroy(s->renderer);
    pelt_headless_destroy(s->gl);
    pelt_fur_destroy(s->fur);
    pelt_mesh_destroy(s->mesh);
    free(s->pixels);
    memset(s, 0, sizeof *s);
}

void cli_session_drop_at(cli_session *s, const cli_options *o)
{
    for (int i = 0; i < o->drop_count; i++) {
        float origin[3], dir[3];
        const float *d = o->drops[i];
        if (!pelt_view_pixel_ray(&s->view, d[0], d[1], origin, dir) ||
            !pelt_fur_add_droplet_ray(s->fur, origin, dir, d[2], 1.0f))
            fprintf(stderr, "pelt: warning: --drop-at %g,%g misses the mesh\n", (double)d[0],
                    (double)d[1]);
    }
}

void cli_session_advance(cli_session *s, const pelt_scene *sc, float t, float dt)
{
    pelt_scene_model_at(sc, t, s->view.model);
    pelt_fur_set_transform(s->fur, s->view.model, NULL);
    pelt_forces forces = sc->forces;
    pelt_scene_wind_at(sc, t, forces.wind);
    const pelt_scene_wetness *w = &sc->wetness;
    bool raining = t >= w->rain_start && (w->rain_stop == 0.0f || t < w->rain_stop);
    if (s->settled) pelt_fur_set_rain_rate(s->fur, raining ? w->rain.rate : 0.0f);
    pelt_fur_step(s->fur, dt, &forces);
}

void cli_session_draw(cli_session *s, const pelt_scene *sc)
{
    pelt_headless_bind(s->gl);
    const float *bg = sc->output.background;
    glClearColor(bg[0], bg[1], bg[2], bg[3]);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    pelt_renderer_draw(s->renderer, &s->view, NULL);
}

bool cli_write_png(const char *cmd, const char *path, const uint8_t *rgba, unsigned w, unsigned h)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        cli_error(cmd, "cannot write '%s': %s", path, strerror(errno));
        return false;
    }
    fclose(f);
    if (!stbi_write_png(path, (int)w, (int)h, 4, rgba, (int)w * 4)) {
        cli_error(cmd, "cannot write PNG '%s'", path);
        remove(path);
        return false;
    }
    return true;
}
