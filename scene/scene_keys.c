/* The scene file's key table (scene_keys.h): every key's path, kind, field
 * and range, in one place. */
#include "scene/scene_keys.h"

#include "pelt/atlas.h"
#include "pelt/groom.h"
#include "pelt/params.h"

#include <stddef.h>

static const char *const shape_names[] = {"torus", "sphere", "square", "file", NULL};
static const char *const up_names[] = {"file", "+y", "-y", "+x", "-x", "+z", "-z", NULL};
static const char *const pattern_names[] = {"none", "spots", "stripes", "noise", NULL};
static const char *const direction_names[] = {"global", "vertex-colors", NULL};
static const char *const vertex_colors_names[] = {"ignore", "hair", NULL};
static const char *const render_mode_names[] = {"shells", "strands", NULL};
static const char *const tone_names[] = {"filmic", "none", NULL}; /* pelt_tone */
static const char *const tool_names[] = {"comb", "length", "color", "density", NULL};
#define OFF(field) offsetof(pelt_scene, field)
#define UINT_(p, f, lo, hi, fl) {p, K_UINT, OFF(f), 0, lo, hi, fl, 0, NULL}
#define FLT(p, f, lo, hi, fl) {p, K_FLOAT, OFF(f), 0, lo, hi, fl, 0, NULL}
#define VEC(p, f, n, lo, hi, fl) {p, K_VEC, OFF(f), 0, lo, hi, fl, n, NULL}
#define RANGE(p, f, g, lo, hi) {p, K_RANGE, OFF(f), OFF(g), lo, hi, 0, 0, NULL}
#define SEED(p, f) {p, K_U32, OFF(f), 0, 0, 4294967295.0, 0, 0, NULL}
#define PATH(p, f) {p, K_PATH, OFF(f), 0, 0, 0, 0, 0, NULL}
#define ENUM(p, f, names) {p, K_ENUM, OFF(f), 0, 0, 0, 0, 0, names, NULL}
/* A field of the embedded pelt_fur_desc: its range and default are the
 * library's row (pelt/params.h). */
#define PARAM(p, name) {p, K_PARAM, OFF(fur), 0, 0, 0, 0, 0, NULL, name, pelt_fur_param}
/* A field of the embedded pelt_atlas_desc, as its row says. */
#define ATLAS(p, name) {p, K_PARAM, OFF(atlas), 0, 0, 0, 0, 0, NULL, name, pelt_atlas_param}

static const pelt__scene_key scene_keys[] = {
    ENUM("mesh.shape", mesh.shape, shape_names),
    PATH("mesh.file", mesh.file),
    FLT("mesh.major_radius", mesh.major_radius, 0, BIG, F_LO_OPEN),
    FLT("mesh.minor_radius", mesh.minor_radius, 0, BIG, F_LO_OPEN),
    UINT_("mesh.major_segments", mesh.major_segments, 3, 16384, 0),
    UINT_("mesh.minor_segments", mesh.minor_segments, 3, 16384, 0),
    FLT("mesh.radius", mesh.radius, 0, BIG, F_LO_OPEN),
    UINT_("mesh.slices", mesh.slices, 3, 16384, 0),
    UINT_("mesh.simplify", mesh.simplify, 0, 0x7fffffff, 0),
    UINT_("mesh.stacks", mesh.stacks, 2, 16384, 0),
    FLT("mesh.size", mesh.size, 0, BIG, F_LO_OPEN),
    UINT_("mesh.subdivisions", mesh.subdivisions, 1, 16384, 0),
    VEC("mesh.rotation", mesh.rotation, 3, -BIG, BIG, 0),
    ENUM("mesh.up", mesh.up, up_names),
    FLT("mesh.scale", mesh.scale, 0, BIG, F_LO_OPEN),

    {"fur.preset", K_PRESET, OFF(fur_preset), 0, 0, 0, 0, 0, pelt_curl_preset_names},
    {"animation.name", K_NAME, OFF(animation.name), 0, 0, 0, 0, 0, NULL},
    PARAM("fur.layers", "layers"),
    PARAM("fur.layers_per_turn", "layers_per_turn"),
    PARAM("fur.length", "length"),
    PARAM("fur.texture_size", "look.texture_size"),
    PARAM("fur.seed", "seed"),
    PARAM("fur.density", "look.density"),
    PARAM("fur.strand_radius", "look.strand_radius"),
    PARAM("fur.taper", "look.taper"),
    PARAM("fur.strand_curl", "look.strand_curl"),
    PARAM("fur.strand_curl_turns", "look.strand_curl_turns"),
    PARAM("fur.strand_curl_shape", "look.strand_curl_shape"),
    PARAM("fur.tiling", "look.tiling"),
    PARAM("fur.color", "look.color"),
    PARAM("fur.tip_color", "look.tip_color"),
    PARAM("fur.specular", "look.specular"),
    PARAM("fur.shininess", "look.shininess"),
    PARAM("fur.shadow", "look.shadow"),
    PARAM("fur.curl_frequency", "look.curl_frequency"),
    PARAM("fur.curl_radius", "look.curl_radius"),
    PARAM("fur.curl_phase", "look.curl_phase"),
    PARAM("fur.curl_lock", "look.curl_lock"),
    PARAM("fur.slant", "comb.slant"),
    PARAM("fur.skin_color", "look.skin_color"),
    PARAM("fur.inter_shadow", "look.inter_shadow"),
    PARAM("fur.inter_shadow_offset", "look.inter_shadow_offset"),
    PARAM("fur.inter_shadow_darkness", "look.inter_shadow_darkness"),
    PARAM("shading.model", "look.shading"),
    PARAM("shading.diffuse_power", "look.diffuse_power"),
    PATH("fur.groom", groom.file),
    PARAM("fur.lod", "lod.mode"),
    PARAM("fur.lod_shell_level", "lod.shell_level"),
    PARAM("fur.lod_mesh_level", "lod.mesh_level"),
    PARAM("fur.lod_shell_pixels", "lod.shell_pixels"),
    PARAM("fur.lod_mesh_error", "lod.mesh_error_pixels"),
    PARAM("fur.lod_mesh_edge", "lod.mesh_edge_pixels"),
    PARAM("fur.lod_back_reach", "lod.back_reach"),
    PARAM("fur.texture_taps", "lod.texture_taps"),
    PARAM("fur.texture_aniso", "lod.texture_aniso"),
    PARAM("fur.edge_depth", "lod.edge_depth"),
    PARAM("fur.sub_shells", "lod.sub_shells"),
    PARAM("fins.length", "fins.length"),
    PARAM("fins.density", "fins.density"),
    PARAM("fins.curl", "fins.curl"),
    PARAM("fins.curl_turns", "fins.curl_turns"),
    PARAM("fins.hairs", "fins.hairs"),
    /* The embedded pelt_draw_desc says what to skip; the file says what to draw. */
    {"draw.skin", K_NOT, OFF(draw.no_skin), 0, 0, 0, 0, 0, NULL},
    {"draw.fins", K_NOT, OFF(draw.no_fins), 0, 0, 0, 0, 0, NULL},
    {"draw.shells", K_NOT, OFF(draw.debug.no_shells), 0, 0, 0, 0, 0, NULL},
    {"draw.shell_depth", K_NOT, OFF(draw.debug.no_shell_depth), 0, 0, 0, 0, 0, NULL},
    {"draw.fins_unfaded", K_BOOL, OFF(draw.fins_unfaded), 0, 0, 0, 0, 0, NULL},
    {"draw.outline_hairs", K_NOT, OFF(draw.no_outline_hairs), 0, 0, 0, 0, 0, NULL},
    UINT_("draw.first_layer", draw.first_layer, 0, 255, 0),
    UINT_("draw.layer_count", draw.layer_count, 0, 256, 0),
    ENUM("render.mode", draw.mode, render_mode_names),
    UINT_("render.strand_samples", strand_samples, 1, 8, 0),
    PATH("fur.length_map", groom.length_map),
    RANGE("fur.length_range", groom.length_range[0], groom.length_range[1], 0, PELT_GROOM_MAX_LENGTH),
    PATH("fur.density_map", groom.density_map),
    RANGE("fur.density_range", groom.density_range[0], groom.density_range[1], 0, 1),
    PATH("fur.flow_map", groom.flow_map),
    FLT("fur.flow_strength", groom.flow_strength, 0, PELT_GROOM_MAX_LEAN, 0),
    PATH("fur.color_map", groom.color_map),
    ENUM("fur.vertex_colors", groom.vertex_colors, vertex_colors_names),
    {"strokes", K_STROKES, OFF(groom.strokes), OFF(groom.stroke_count), 0, 0, 0, 0, NULL},

    PATH("texture.image", texture.image),
    ENUM("texture.pattern", texture.pattern, pattern_names),
    PARAM("texture.scale", "look.color_scale"),

    FLT("camera.yaw", camera.yaw, -BIG, BIG, 0),
    FLT("camera.pitch", camera.pitch, -89, 89, 0),
    FLT("camera.distance", camera.distance, 0, BIG, F_LO_OPEN),
    FLT("camera.fov_y", camera.fov_y, 1, 179, 0),
    VEC("camera.target", camera.target, 3, -BIG, BIG, 0),

    VEC("light.direction", light.direction, 3, -BIG, BIG, F_NONZERO),
    VEC("light.color", light.color, 3, 0, BIG, 0),
    FLT("light.ambient", light.ambient, 0, 1, 0),
    {"shadows.enabled", K_BOOL, OFF(shadows.enabled), 0, 0, 0, 0, 0, NULL},
    UINT_("shadows.map_size", shadows.map_size, 16, PELT_SHADOW_MAX_MAP_SIZE, 0),
    UINT_("shadows.slices", shadows.slices, 1, PELT_SHADOW_MAX_SLICES, 0),
    FLT("shadows.softness", shadows.softness, -1, 64, 0),
    FLT("shadows.depth", shadows.depth, 0, 64, F_LO_OPEN),
    FLT("shadows.density", shadows.density, 0, 64, F_LO_OPEN),
    {"shadows.gamma", K_BOOL, OFF(shadows.keep_gamma), 0, 0, 0, 0, 0, NULL},
    {"ground.enabled", K_BOOL, OFF(ground.enabled), 0, 0, 0, 0, 0, NULL},
    VEC("ground.color", ground.color, 3, 0, 1, 0),
    FLT("ground.size", ground.size, 0, 1000, F_LO_OPEN),

    UINT_("output.width", output.width, 1, 16384, 0),
    UINT_("output.height", output.height, 1, 16384, 0),
    UINT_("output.msaa", output.msaa, 0, 16, 0),
    VEC("output.background", output.background, 4, 0, 1, F_ACCEPT3),
    FLT("output.exposure", draw.exposure, 0.01, 64, 0),
    ENUM("output.tone", draw.tone, tone_names),

    VEC("forces.gravity", forces.gravity, 3, -BIG, BIG, 0),
    VEC("forces.wind", forces.wind, 3, -BIG, BIG, 0),
    FLT("forces.gust_strength", forces.gust_strength, 0, BIG, 0),
    FLT("forces.gust_scale", forces.gust_scale, 0, BIG, F_LO_OPEN),
    FLT("forces.gust_frequency", forces.gust_frequency, 0, BIG, 0),

    PARAM("dynamics.spring_k", "dynamics.spring_k"),
    PARAM("dynamics.mass", "dynamics.mass"),
    PARAM("dynamics.damping", "dynamics.damping"),
    PARAM("dynamics.threads", "dynamics.threads"),

    UINT_("animation.frames", animation.frames, 1, 1000000, 0),
    FLT("animation.fps", animation.fps, 0, 1000, F_LO_OPEN),
    FLT("animation.turntable", animation.turntable, -BIG, BIG, 0),
    FLT("animation.shake.amplitude", animation.shake_amplitude, 0, BIG, 0),
    FLT("animation.shake.frequency", animation.shake_frequency, 0, BIG, 0),
    FLT("animation.bounce.height", animation.bounce_height, 0, BIG, 0),
    FLT("animation.bounce.frequency", animation.bounce_frequency, 0, BIG, 0),
    {"animation.wind", K_WINDKEYS, OFF(animation.wind_keys), OFF(animation.wind_key_count),
     0, 0, 0, 0, NULL},

    PARAM("wetness.mask_size", "wet.mask_size"),
    {"wetness.droplets", K_DROPLETS, OFF(wetness.droplets), OFF(wetness.droplet_count),
     0, 0, 0, 0, NULL},
    UINT_("wetness.drops.count", wetness.drops, 0, PELT_SCENE_MAX_DROPLETS, 0),
    SEED("wetness.drops.seed", wetness.drops_seed),
    RANGE("wetness.drops.radius", wetness.drops_radius[0], wetness.drops_radius[1], 0, 1),
    RANGE("wetness.drops.wetness", wetness.drops_wetness[0], wetness.drops_wetness[1], -1, 1),
    FLT("wetness.rain.rate", wetness.rain.rate, 0, BIG, 0),
    RANGE("wetness.rain.radius", wetness.rain.radius_min, wetness.rain.radius_max, 0, 1),
    RANGE("wetness.rain.wetness", wetness.rain.wetness_min, wetness.rain.wetness_max, -1, 1),
    SEED("wetness.rain.seed", wetness.rain.seed),
    FLT("wetness.rain.start", wetness.rain_start, 0, BIG, 0),
    FLT("wetness.rain.stop", wetness.rain_stop, 0, BIG, 0),
    FLT("wetness.dry_rate", wetness.dry_rate, 0, BIG, 0),
    PARAM("wetness.clump_blend", "wet.clump_blend"),
    PARAM("wetness.clump_tightness", "wet.clump_tightness"),
    PARAM("wetness.darken", "wet.darken"),
    PARAM("wetness.clumps", "wet.clumps"),
    PARAM("wetness.strays", "wet.strays"),
    PARAM("wetness.clump_size", "wet.clump_size"),
    PARAM("wetness.gloss", "wet.gloss"),
    PARAM("wetness.gloss_sharpness", "wet.gloss_sharpness"),
    PARAM("wetness.weight", "wet.weight"),
    PARAM("wetness.lie", "wet.lie"),
    PARAM("wetness.clump_lean", "wet.clump_lean"),
    PATH("wetness.mask_image", wetness.mask_image),
    FLT("wetness.mask_image_wetness", wetness.mask_image_wetness, -1, 1, 0),

    ATLAS("atlas.mode", "mode"),
    ATLAS("atlas.texel_density", "texel_density"),
    ATLAS("atlas.direction", "direction"),
    ATLAS("atlas.max_stretch", "max_stretch"),
    ENUM("atlas.direction_from", atlas_direction_from, direction_names),
};

#undef OFF
#define OFF(field) offsetof(pelt_droplet, field)
static const pelt__scene_key droplet_keys[] = {
    {"center", K_VEC, OFF(center), 0, 0, 1, 0, 2, NULL},
    {"radius", K_FLOAT, OFF(radius), 0, 0, 1, F_LO_OPEN, 0, NULL},
    {"wetness", K_FLOAT, OFF(wetness), 0, -1, 1, 0, 0, NULL},
};
#undef OFF
#define OFF(field) offsetof(pelt_wind_key, field)
static const pelt__scene_key wind_key_keys[] = {
    {"time", K_FLOAT, OFF(time), 0, 0, BIG, 0, 0, NULL},
    {"wind", K_VEC, OFF(wind), 0, -BIG, BIG, 0, 3, NULL},
};
#undef OFF
#define OFF(field) offsetof(pelt_scene_stroke, field)
static const pelt__scene_key stroke_keys[] = {
    {"tool", K_ENUM, OFF(brush.tool), 0, 0, 0, 0, 0, tool_names},
    {"radius", K_FLOAT, OFF(brush.radius), 0, 0, BIG, F_LO_OPEN, 0, NULL},
    {"strength", K_FLOAT, OFF(brush.strength), 0, 0, 1, F_LO_OPEN, 0, NULL},
    {"delta", K_VEC, OFF(brush.delta), 0, -BIG, BIG, 0, 3, NULL},
    {"amount", K_FLOAT, OFF(brush.amount), 0, -PELT_GROOM_MAX_LENGTH, PELT_GROOM_MAX_LENGTH, 0, 0, NULL},
    {"color", K_VEC, OFF(brush.color), 0, 0, 1, 0, 3, NULL},
    {"pixel", K_VEC, OFF(pixel), 0, -BIG, BIG, 0, 2, NULL},
    {"at", K_VEC, OFF(at), 0, -BIG, BIG, 0, 3, NULL},
    {"drag", K_VEC, OFF(drag), 0, -BIG, BIG, 0, 2, NULL},
};
#undef OFF

#define TABLE(a) {a, sizeof(a) / sizeof((a)[0])}
const pelt__scene_keys pelt__scene_key_table = TABLE(scene_keys);
const pelt__scene_keys pelt__droplet_key_table = TABLE(droplet_keys);
const pelt__scene_keys pelt__wind_key_table = TABLE(wind_key_keys);
const pelt__scene_keys pelt__stroke_key_table = TABLE(stroke_keys);
