/* pelt view: a window to orbit, comb, wet, dry and blow on fur, live.
 * Private to the pelt command; the pieces, one concern each:
 *   cmd_view.c     the command: flags, the scene, the frame loop, rebuilds
 *   view_window.c  the GLFW window and its OpenGL 3.3 core context; input
 *                  arrives as view_events
 *   view_input.c   view_events -> camera, tools and keys
 *   view_script.c  --script: timed view_events for deterministic runs
 *   view_hud.c     the HUD text (stb_easy_font) and its tiny GL program
 * The window is the command's, not the library's: libpelt and its
 * packages stay free of GLFW and X11, and an embedder brings its own
 * window and context (README, "The library"). */
#ifndef PELT_APPS_VIEW_H
#define PELT_APPS_VIEW_H

#include "apps/cli.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* ---- events: from the window or from a script ---------------------------- */

typedef enum view_event_type {
    VIEW_EV_MOVE,       /* cursor at (x, y), pixels from the top left */
    VIEW_EV_BUTTON,     /* button 0 left, 1 right, 2 middle; press or release */
    VIEW_EV_SCROLL,     /* wheel: y clicks (positive: away from the user) */
    VIEW_EV_KEY,        /* GLFW key code, press or release, mods */
    VIEW_EV_DROP,       /* a file dropped on the window: path */
    VIEW_EV_SCREENSHOT, /* script: save the window's pixels to path */
    VIEW_EV_EXIT        /* script: end the run */
} view_event_type;

#define VIEW_PATH_MAX 1024

typedef struct view_event {
    view_event_type type;
    float x, y;
    int button;
    int key;
    int mods; /* GLFW_MOD_SHIFT, GLFW_MOD_CONTROL... */
    bool press;
    char path[VIEW_PATH_MAX];
} view_event;

/* ---- the window ------------------------------------------------------------ */

typedef struct view_window view_window;

/* Opens a window of w x h pixels with an OpenGL 3.3 core context and
 * `samples` multisampling (output.msaa: what render draws), current on
 * this thread. False with a message in err (no display, no GLX...). */
bool view_window_open(const char *title, unsigned w, unsigned h, unsigned samples, view_window **out,
                      char *err, size_t err_size);
void view_window_close(view_window *w);
/* Collects pending input (never blocks). */
void view_window_poll(view_window *w);
/* The next queued event; false when none is left. */
bool view_window_next_event(view_window *w, view_event *out);
bool view_window_should_close(const view_window *w);
void view_window_framebuffer_size(const view_window *w, unsigned *width, unsigned *height);
void view_window_swap(view_window *w);
void view_window_set_title(view_window *w, const char *title);
/* Reads the back buffer (what the next swap shows), top row first. */
void view_window_read_rgba8(view_window *w, uint8_t *rgba, unsigned width, unsigned height);
/* Seconds since GLFW started. */
double view_window_time(void);
/* Calls frame(user) once a frame until it returns false, then
 * finish(user). On the desktop a loop that returns after finish; in the
 * browser the page's animation frames drive it and it never returns. */
void view_window_run(view_window *w, bool (*frame)(void *), void (*finish)(void *), void *user);

/* ---- the script ------------------------------------------------------------ */

typedef struct view_script view_script;

/* Reads a script file (docs/viewer.md): one timed event a line. frame_dt is
 * the fixed step, used to spread a drag over frames. False with a message
 * naming the file and line. */
bool view_script_load(const char *path, float frame_dt, view_script **out, char *err,
                      size_t err_size);
void view_script_free(view_script *s);
/* The next event due at time t (seconds from the first frame), in file
 * order; false when none is due. */
bool view_script_next(view_script *s, float t, view_event *out);
/* True once every event has been handed out. */
bool view_script_done(const view_script *s);

/* ---- the HUD ---------------------------------------------------------------- */

typedef struct view_hud view_hud;

bool view_hud_create(view_hud **out, char *err, size_t err_size);
void view_hud_destroy(view_hud *h);
/* Draws text (lines separated by '\n') at pixel (x, y) from the top left of
 * a width x height framebuffer, on a dark translucent panel, scaled by
 * `scale`. Colour changes inline: "\x01" white, "\x02" red, "\x03" grey,
 * "\x04" yellow. Leaves GL state as the renderer's contract states it. */
void view_hud_text(view_hud *h, const char *text, float x, float y, float scale,
                   unsigned width, unsigned height);
/* The brush: a ring of radius r pixels around (cx, cy). */
void view_hud_ring(view_hud *h, float cx, float cy, float r, unsigned width, unsigned height);

/* ---- the viewer ------------------------------------------------------------- */

typedef enum view_tool { VIEW_TOOL_ORBIT = 0, VIEW_TOOL_WATER, VIEW_TOOL_DRYER, VIEW_TOOL_COMB,
                         VIEW_TOOL_LENGTH, VIEW_TOOL_COUNT } view_tool;

/* What the input asks the frame loop to do (it owns the objects). */
typedef enum view_request {
    VIEW_REQ_NONE = 0,
    VIEW_REQ_REBUILD = 1 << 0,    /* layers or curl changed: new fur, groom kept */
    VIEW_REQ_RESET = 1 << 1,      /* the scene as it was started, camera too */
    VIEW_REQ_RELOAD = 1 << 2,     /* read the scene file again */
    VIEW_REQ_SCREENSHOT = 1 << 3, /* the next frame to PNG */
    VIEW_REQ_SAVE_GROOM = 1 << 4,
    VIEW_REQ_LOAD_MESH = 1 << 5,  /* drop_path */
    VIEW_REQ_EXIT = 1 << 6
} view_request;

typedef struct view_state {
    /* camera */
    pelt_camera camera;
    unsigned width, height;
    /* mouse */
    float mx, my, last_x, last_y;
    bool button[3];
    bool shift;
    bool orbiting;        /* a drag that turns the camera */
    float hold_seconds;   /* the left button has been down this long */
    float rain_carry;     /* the held water tool's fraction of a drop */
    /* tools */
    view_tool tool;
    float radius;         /* world units */
    float diagonal;       /* of the mesh, world units: scales radius and zoom */
    float blow_seconds;   /* the dryer's air lasts this much longer */
    float blow_dir[3];    /* world units: along the ray through the cursor */
    float blow_center[3]; /* world units: where that ray meets the mesh */
    bool was_blowing;
    uint32_t rng;
    /* switches */
    bool wind_on, gravity_on, rain_on;
    float wind_strength;  /* acceleration along wind_dir */
    float wind_dir[3];
    pelt_forces scene_forces; /* the scene's, to switch back to */
    bool forces_touched;  /* wind or gravity switched: the scene's no longer hold */
    float rain_rate;
    int preset;           /* place in the curl cycle (view_preset_name) */
    unsigned layers;
    bool fins, shadows;   /* the fin pass, Kenwright's inter-fur shadows */
    bool light_shadows;   /* the light's shadow maps (docs/shadows.md) */
    bool lod;             /* level of detail (fur.lod auto, or the scene's fixed levels) or off */
    bool help, hud;
    /* requests and messages */
    unsigned requests;
    char drop_path[VIEW_PATH_MAX];
    char message[512];
    bool message_is_error;
    float message_seconds; /* shown this much longer */
} view_state;

/* The viewer's curl cycle: 0 = the scene's own curl, then the curl looks
 * of pelt_curl_preset_names; view_preset_of(name) is a name's place in it. */
const char *view_preset_name(int i);
int view_preset_of(const char *name);
/* The scene's layers, or the library's default when it leaves them 0. */
unsigned view_scene_layers(const pelt_scene *sc);

/* The state for a freshly made instance (camera, forces, radius). */
void view_input_init(view_state *st, pelt_scene_instance *inst, const pelt_scene *scene);
/* Carries the camera, forces and rain switches over to a new instance
 * (after a rebuild or a reload). */
void view_input_apply(view_state *st, pelt_scene_instance *inst);
/* One event: camera moves, tool strokes, key switches. */
void view_input_event(view_state *st, pelt_scene_instance *inst, const view_event *e);
/* Continuous effects before a step of dt seconds: rain under a held
 * water tool, the dryer's drying and air, forces and rain switches. */
void view_input_frame(view_state *st, pelt_scene_instance *inst, float dt);
/* A HUD message for a few seconds (also printed to stderr). */
void view_message(view_state *st, bool error, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* The help overlay's text: every key and tool. */
const char *view_help_text(void);
const char *view_tool_name(view_tool t);
/* The brush radius in pixels at the camera's target distance. */
float view_brush_pixels(const view_state *st);

#endif
