/* pelt — scene files: everything one render needs (mesh, fur, textures,
 * camera, light, output, forces, animation, wetness, atlas), read from JSON
 * and overridable one key at a time from the command line.
 *
 * The format, key by key, is in docs/scene-format.md. Every key has the
 * same name in JSON as the field path here (the JSON key "camera.yaw",
 * that is {"camera": {"yaw": 30}}, is scene.camera.yaw), except the fur's
 * parameters, which live in the nested pelt_fur_desc (see `fur` below). */
#ifndef PELT_SCENE_H
#define PELT_SCENE_H

#include "pelt/animation.h"
#include "pelt/atlas.h"
#include "pelt/base.h"
#include "pelt/camera.h"
#include "pelt/dynamics.h"
#include "pelt/fur.h"
#include "pelt/groom.h"
#include "pelt/render.h"
#include "pelt/shadow.h"
#include "pelt/wetness.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PELT_SCENE_PATH_MAX 1024u     /* bytes of a stored path, with the NUL */
#define PELT_SCENE_NAME_MAX 32u       /* bytes of a stored preset name */
#define PELT_SCENE_FILE_MAX (16u << 20) /* scene files above 16 MiB are refused */
#define PELT_SCENE_MAX_DROPLETS 1000000u
#define PELT_SCENE_MAX_WIND_KEYS 65536u
#define PELT_SCENE_MAX_STROKES 65536u

/* Where the mesh comes from. 0 is the default (the Table 1 torus). */
typedef enum pelt_scene_shape {
    PELT_SHAPE_TORUS = 0, /* pelt_mesh_torus */
    PELT_SHAPE_SPHERE,    /* pelt_mesh_sphere */
    PELT_SHAPE_SQUARE,    /* pelt_mesh_square */
    PELT_SHAPE_FILE       /* pelt_mesh_load(mesh.file) */
} pelt_scene_shape;

typedef enum pelt_scene_up {
    PELT_UP_FILE = 0, PELT_UP_POS_Y, PELT_UP_NEG_Y, PELT_UP_POS_X, PELT_UP_NEG_X, PELT_UP_POS_Z, PELT_UP_NEG_Z
} pelt_scene_up;

typedef struct pelt_scene_mesh {
    pelt_scene_shape shape;         /* default TORUS */
    char file[PELT_SCENE_PATH_MAX]; /* shape FILE: path, resolved against the
                                       scene file's directory; "" otherwise */
    /* torus: defaults 1.0, 0.4, 78, 60 -> 9,360 triangles (Silva Table 1) */
    float major_radius, minor_radius;
    unsigned major_segments, minor_segments;
    /* sphere: defaults radius 1.0, 64 slices, 32 stacks */
    float radius;
    unsigned slices, stacks;
    /* square in the XZ plane, normal +Y (Silva Fig. 4b): defaults side 2.0,
       16 subdivisions per side */
    float size;
    unsigned subdivisions;
    /* simplify: when above 0 and below the mesh's triangle count, the mesh
       is first simplified to about this many triangles (pelt_mesh_simplify) */
    unsigned simplify;
    /* placement: rotation in degrees about X, then Y, then Z; uniform scale
       (default 1). Applied before the animation (pelt_scene_model_at). */
    float rotation[3];
    float scale;
    /* Which of the mesh's axes is up, turned to +Y before the placement
       above: the file's own (FBX metadata, else +Y; the default) or one
       of the axes (pelt_scene_up). */
    pelt_scene_up up;
} pelt_scene_mesh;

typedef struct pelt_scene_texture {
    /* Colour texture: an image file (resolved against the scene's directory)
       OR a procedural pattern, never both; "" and NONE mean no texture. */
    char image[PELT_SCENE_PATH_MAX];
    pelt_color_pattern pattern;     /* default NONE */
    /* The key "texture.scale" (repeats per uv unit) is fur.look.color_scale. */
} pelt_scene_texture;

typedef struct pelt_scene_output {
    unsigned width, height; /* pixels, default 800 x 600 (Table 1), 1..16384 */
    unsigned msaa;          /* samples, 0 = off (default), at most 16 */
    float background[4];    /* RGBA as written to the image (sRGB), default (0.10, 0.11, 0.13, 1) */
    /* "output.exposure" and "output.tone" are draw.exposure (default 1,
       0.01..64) and draw.tone (filmic, none): the picture from the linear
       light (docs/shading.md). */
} pelt_scene_output;

/* Wind at a time; keyframes are linearly interpolated. */
typedef struct pelt_wind_key {
    float time;    /* seconds, >= 0, strictly increasing along the list */
    float wind[3]; /* same meaning as pelt_forces.wind */
} pelt_wind_key;

typedef struct pelt_scene_animation {
    unsigned frames;        /* images to write, default 1 (a still) */
    float fps;              /* frames per second, default 30; frame i is at
                               time i / fps, the duration is frames / fps */
    /* A skinned mesh's animation, by name or index (pelt/animation.h), ""
       (default) for none: it plays from time 0, looping; the fur's roots
       follow the surface and its tips lag. */
    char name[PELT_ANIMATION_NAME_MAX];
    float turntable;        /* degrees per second about +Y, default 0 */
    float shake_amplitude;  /* world units along X, default 0 */
    float shake_frequency;  /* Hz, default 2 */
    float bounce_height;    /* world units along +Y, default 0 */
    float bounce_frequency; /* bounces per second, default 1 */
    /* Wind keyframes, or NULL/0: then forces.wind holds at all times.
       Owned by the scene; pelt_scene_free frees it. */
    pelt_wind_key *wind_keys;
    size_t wind_key_count;
} pelt_scene_animation;

/* Water on the fur over time. The mask's size and the clump look
 * (the keys wetness.mask_size, clump_blend, clump_tightness, darken) live
 * in the fur desc: scene.fur.wet. */
typedef struct pelt_scene_wetness {
    /* Droplets placed at time 0, in mask uv units (pelt_droplet). Owned by
       the scene; pelt_scene_free frees it. */
    pelt_droplet *droplets;
    size_t droplet_count;
    /* Random droplets at time 0, seeded; radius and wetness drawn
       uniformly from the ranges (defaults radius 0.02..0.06,
       wetness 0.6..1.0, seed 1, count 0). */
    unsigned drops;
    uint32_t drops_seed;
    float drops_radius[2];
    float drops_wetness[2];
    pelt_rain rain;         /* default rate 0, same ranges as drops, seed 1 */
    float rain_start;       /* seconds when the rain begins, default 0 */
    float rain_stop;        /* seconds when it ends, 0 = never (default) */
    float dry_rate;         /* wetness lost per second, default 0 */
    /* Greyscale image painted as water (Silva Fig. 12c): a texel's wetness
       is its grey level times mask_image_wetness (default 1). "" = none. */
    char mask_image[PELT_SCENE_PATH_MAX];
    float mask_image_wetness;
} pelt_scene_wetness;

/* What the mesh file's vertex colours are, besides a possible flow map
 * for the atlas (atlas.direction_from). */
typedef enum pelt_vertex_colors_use {
    PELT_VERTEX_COLORS_IGNORE = 0, /* default */
    PELT_VERTEX_COLORS_HAIR        /* the hair colour (Lengyel's dog) */
} pelt_vertex_colors_use;

/* A scripted brush stroke (pelt/groom.h), applied when the scene is made.
 * It lands where the camera's ray through `pixel` meets the mesh (the
 * first frame's view), or at the mesh-local point `at`. */
typedef struct pelt_scene_stroke {
    pelt_brush brush;  /* tool, strength, amount, color; radius and delta in
                          world units (the mesh's times mesh.scale) */
    float pixel[2];    /* x right, y down, in output pixels */
    float at[3];       /* mesh-local; NaN (the default) = use pixel */
    float drag[2];     /* comb: the drag in pixels across the view plane at
                          the stroke's depth (x right, y down), added to
                          delta; default 0 */
} pelt_scene_stroke;

/* Grooming (docs/grooming.md): applied in this order when the scene is
 * made: maps, vertex colours, the groom file (it replaces every field),
 * then the strokes. */
typedef struct pelt_scene_groom {
    char file[PELT_SCENE_PATH_MAX];        /* "fur.groom": a groom PLY, "" none */
    char length_map[PELT_SCENE_PATH_MAX];  /* grey -> length_range */
    float length_range[2];                 /* default [0, 1] */
    char density_map[PELT_SCENE_PATH_MAX]; /* grey -> density_range */
    float density_range[2];                /* default [0, 1] */
    char flow_map[PELT_SCENE_PATH_MAX];    /* rg -> lean (2 rg - 1) * flow_strength */
    float flow_strength;                   /* default 1 (45 degrees at full red) */
    char color_map[PELT_SCENE_PATH_MAX];   /* rgb -> hair colour, alpha -> weight */
    pelt_vertex_colors_use vertex_colors;  /* default IGNORE */
    /* Owned by the scene; pelt_scene_free frees them. */
    pelt_scene_stroke *strokes;
    size_t stroke_count;
} pelt_scene_groom;

/* Where the atlas's direction field comes from (atlas.direction_from). */
typedef enum pelt_direction_source {
    PELT_DIRECTION_GLOBAL = 0,   /* atlas.direction, projected per vertex */
    PELT_DIRECTION_VERTEX_COLORS /* the mesh's vertex colours as a flow map */
} pelt_direction_source;

/* A whole scene. Plain data: copy it freely, but the three arrays
 * (wetness.droplets, animation.wind_keys, groom.strokes) are owned by exactly one copy,
 * which pelt_scene_free releases. */
typedef struct pelt_scene {
    pelt_scene_mesh mesh;
    /* The fur desc, whole: one home per parameter. JSON keys map onto it
       (docs/scene-format.md): "fur.*" -> layers, length, seed, look.*,
       comb.slant; "dynamics.*" -> dynamics.*; "wetness.mask_size",
       "wetness.clump_*", "wetness.darken" -> wet.*; "texture.scale" ->
       look.color_scale. Left zero by pelt_scene_defaults: pelt_fur_create
       fills each field from its row (pelt/params.h, Table 1's
       256 x 256 texture among them). */
    pelt_fur_desc fur;
    /* One of the curl looks of Silva Fig. 7: "straight", "wavy",
       "few-large-curls", "many-small-curls" (also spelt "large_curls",
       "small_curls"), or "" (none, default); pelt_fur_desc_curl_preset
       turns it into omega and K_alpha = radius_fraction * length when the
       scene is instantiated. An explicit non-zero fur.look.curl_frequency /
       curl_radius wins over the preset's value. */
    char fur_preset[PELT_SCENE_NAME_MAX];
    pelt_scene_texture texture;
    pelt_camera camera;    /* default yaw 30, pitch 25, distance 4.2, fov_y 40, target 0 */
    pelt_light light;      /* default direction (0.5, 1, 0.8), colour 1, ambient 0.25 */
    pelt_shadow_desc shadows; /* the light's shadows: off by default (pelt/shadow.h);
                                 keys shadows.*, "shadows.gamma" is keep_gamma */
    pelt_ground_desc ground;  /* a ground plane: off by default (the Table 1 set-up) */
    pelt_scene_output output;
    pelt_forces forces;    /* default pelt_forces_default() */
    pelt_scene_animation animation;
    pelt_scene_wetness wetness;
    /* How the surface gets its atlas (Lengyel §2.1), whole (pelt/atlas.h):
       "atlas.mode", "texel_density" (0 here = the fur's 5 / bounding-box
       diagonal), "direction" (zero = combed down), "max_stretch". The
       runner adds the mask size, seed, cache and hooks. */
    pelt_atlas_desc atlas;
    /* The global atlas.direction (default) or the mesh file's per-vertex
       directions, read from its first vertex colour set as a flow map. */
    pelt_direction_source atlas_direction_from;
    /* What to draw, whole (pelt/render.h): "draw.skin", "draw.fins" and
       "draw.shells" set no_skin, no_fins and debug.no_shells inverted.
       pelt_scene_defaults draws everything. Without the fins the
       back-facing shells near the silhouette carry it (docs/lod.md). */
    pelt_draw_desc draw;
    /* render.strand_samples: the strand reference (draw.mode, "render.mode")
       is drawn at this many times the output's width and height, then
       box-filtered down for hair coverage; default 4 (docs/reference.md). */
    unsigned strand_samples;
    pelt_scene_groom groom; /* JSON keys "fur.groom", "fur.length_map"...
                               and the top-level "strokes" list */
} pelt_scene;

/* Fills *s with the defaults (the paper's Table 1 set-up: torus 78 x 60,
 * 800 x 600, fur texture and mask 256). Does not free: *s may be
 * uninitialised. */
void pelt_scene_defaults(pelt_scene *s);

/* Reads a scene file: starts from the defaults and overlays every key the
 * file holds. Relative mesh, texture and mask image paths resolve against
 * the file's directory. *s is overwritten without being freed (call
 * pelt_scene_free first if it owns arrays). On success the caller frees *s
 * with pelt_scene_free; on failure *s holds the defaults and owns nothing.
 * Errors: PELT_ERR_IO (missing, unreadable, larger than
 * PELT_SCENE_FILE_MAX), PELT_ERR_FORMAT (empty, JSON syntax with its line,
 * unknown key, duplicate key, wrong type, value out of range); the message
 * names the file and the key. */
pelt_status pelt_scene_load(const char *path, pelt_scene *s, pelt_error *err);

/* As pelt_scene_load, from NUL-terminated JSON text. name_for_errors (may be
 * NULL: "scene") starts every message, and relative paths resolve against
 * its directory when it contains a '/'. */
pelt_status pelt_scene_parse(const char *json_text, const char *name_for_errors,
                             pelt_scene *s, pelt_error *err);

/* Sets one key from a string, for command-line overrides such as
 * --set fur.layers=32. `value` is read as JSON when it parses as JSON
 * (32, [1,0,0], {"radius":0.1}, "torus") and as a bare string otherwise
 * (torus, meshes/bunny.off). The same validation and messages as a file,
 * starting with "--set". A whole group may be set (key "camera" with an
 * object). Relative paths stay relative to the working directory. On
 * failure *s is unchanged. */
pelt_status pelt_scene_set(pelt_scene *s, const char *key_path, const char *value,
                           pelt_error *err);

/* Frees the arrays *s owns and sets them to NULL/0. NULL is allowed. */
void pelt_scene_free(pelt_scene *s);

/* The i-th key a scene file and pelt_scene_set accept, as a dotted path
 * ("fur.layers"), in the order of the key table; NULL past the last. For
 * help text and shell completion. */
const char *pelt_scene_key_name(size_t i);

/* Wind at time t in seconds: forces.wind when there are no keyframes, else
 * the keyframes linearly interpolated, held constant before the first and
 * after the last. No allocation. */
void pelt_scene_wind_at(const pelt_scene *s, float t, float out[3]);

/* The mesh's model matrix at time t (column-major, as pelt_view.model):
 * translate(shake, bounce) * rotateY(turntable * t) * rotation * scale, with
 * shake x = A sin(2 pi f t) and bounce y = H |sin(pi f t)|. No allocation. */
void pelt_scene_model_at(const pelt_scene *s, float t, float model[16]);

#ifdef __cplusplus
}
#endif
#endif
