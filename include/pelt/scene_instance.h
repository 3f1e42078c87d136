/* pelt — a scene made real: the mesh (with its atlas), the fur, its colour
 * and water, the camera and the animation clock. The one path from a
 * scene (pelt/scene.h) to fur that `pelt render`, `pelt bench`, the coming
 * window and embedders all share. GL-free: draw it with pelt_renderer
 * (pelt/render.h) or anything else. */
#ifndef PELT_SCENE_INSTANCE_H
#define PELT_SCENE_INSTANCE_H

#include "pelt/base.h"
#include "pelt/camera.h"
#include "pelt/fur.h"
#include "pelt/mesh.h"
#include "pelt/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pelt_scene_instance pelt_scene_instance;

typedef struct pelt_scene_instance_desc {
    /* Where built atlases are cached: NULL = pelt_atlas_default_cache_dir(),
     * "" = no cache. */
    const char *cache_dir;
    /* Allocator and logger for the instance and everything it makes (the
     * scene's fur.hooks, when set, win for the fur). Warnings (degenerate
     * triangles dropped, a mesh's uvs not used) go to the logger. */
    pelt_hooks hooks;
    /* Seconds of settling under the forces of time 0 before the first
     * frame, so a still shows fur bent by gravity, not mid-spring;
     * 0 = 1.5 s, negative = none. */
    float settle_seconds;
} pelt_scene_instance_desc;

/* What making the instance did. */
typedef struct pelt_scene_instance_stats {
    double atlas_seconds;   /* atlas build (or cache load) time, 0 when none */
    bool atlas_from_cache;
    size_t atlas_patches;   /* 0 when the mesh's own uvs were used */
} pelt_scene_instance_stats;

/* Loads or makes the mesh (mesh.*), gives a mesh file its atlas (atlas.*),
 * makes the fur (fur.*, a curl preset), its colour (texture.*) and water
 * (wetness.droplets, drops, mask_image), frames a mesh file in the default
 * camera, lets the fur settle, then arms rain and drying (wetness.rain,
 * dry_rate) for the first frame. The scene is copied; it need not outlive
 * the instance. Errors name the scene key and file at fault. desc may be
 * NULL. Free with pelt_scene_instance_destroy. */
pelt_status pelt_scene_instantiate(const pelt_scene *scene, const pelt_scene_instance_desc *desc,
                                   pelt_scene_instance **out, pelt_error *err);
void pelt_scene_instance_destroy(pelt_scene_instance *inst);

/* Advances the clock by dt seconds: places the mesh where the animation
 * has it at the new time (turntable, shake, bounce), blows the wind of that
 * time, lets it rain while the schedule says so, and steps the fur by dt.
 * No allocation, no I/O. */
void pelt_scene_instance_advance(pelt_scene_instance *inst, float dt);

/* Seconds advanced since the first frame (0 at the first frame). */
float pelt_scene_instance_time(const pelt_scene_instance *inst);

/* Owned by the instance. The fur may be changed (droplets, forces...). */
const pelt_mesh *pelt_scene_instance_mesh(const pelt_scene_instance *inst);
pelt_fur *pelt_scene_instance_fur(pelt_scene_instance *inst);

/* The view of the scene's camera, light and output size, with the mesh's
 * model matrix at the current time. */
pelt_view pelt_scene_instance_view(const pelt_scene_instance *inst);

/* The orbit camera the view is made from: the scene's, framed on a mesh
 * file. */
pelt_camera pelt_scene_instance_camera(const pelt_scene_instance *inst);

/* Moves the camera and resizes the output (a window that is orbited,
 * zoomed, panned or resized): the view, and with it drop_at_pixel and
 * brush_at_pixel, follow from now on. width or height 0 keeps the current
 * size. */
void pelt_scene_instance_set_camera(pelt_scene_instance *inst, const pelt_camera *camera,
                                    unsigned width, unsigned height);

/* The forces of the current time (the scene's, with the wind of its
 * keyframes at that time), and forces that hold from now on, replacing
 * forces.* and any wind keyframes of the scene (a viewer's wind and
 * gravity switches). */
pelt_forces pelt_scene_instance_forces(const pelt_scene_instance *inst);
void pelt_scene_instance_set_forces(pelt_scene_instance *inst, const pelt_forces *forces);

/* Rain at `rate` drops per second from now on, replacing the scene's
 * schedule (wetness.rain_start / rain_stop); 0 stops it. */
void pelt_scene_instance_set_rain_rate(pelt_scene_instance *inst, float rate);

/* A droplet where the ray through pixel (px, py) of the view meets the
 * mesh (radius in world units). False when it misses. */
bool pelt_scene_instance_drop_at_pixel(pelt_scene_instance *inst, float px, float py,
                                       float radius, float wetness);

/* A brush stroke (pelt/groom.h) where the ray through pixel (px, py) meets
 * the mesh; the brush's radius and delta are in world units. `drag` (may
 * be NULL) adds a drag of (dx, dy) pixels across the view plane at the
 * stroke's depth to the delta: Lengyel et al.'s local combing under the
 * mouse. False when the pixel misses the mesh or the brush is invalid. */
bool pelt_scene_instance_brush_at_pixel(pelt_scene_instance *inst, float px, float py,
                                        const pelt_brush *brush, const float drag[2]);

pelt_scene_instance_stats pelt_scene_instance_get_stats(const pelt_scene_instance *inst);

#ifdef __cplusplus
}
#endif
#endif
