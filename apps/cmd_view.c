/* pelt view: the scene of `pelt render` in a window, live: orbit, zoom,
 * pan, comb, wet, dry and blow on the fur (apps/view.h has the pieces). */
#include "apps/view.h"

#include "gl/gl_api.h"
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define MAX_SHOTS 64

/* ---- flags: render's, then the viewer's own -------------------------------- */

static const cli_flag_doc view_flags[] = {
    {"--script", NULL, "FILE",
     "replay timed input events (moves, clicks, drags, keys, drops; docs/viewer.md) with a "
     "fixed step of 1/30 s a frame", NULL},
    {"--screenshot-at", NULL, "T:FILE",
     "save the window's pixels at T seconds to a PNG (repeatable; fixed 1/30 s steps)", NULL},
    {"--no-hud", NULL, NULL, "start with the HUD hidden (Tab shows it)", NULL},
};
#define VIEW_FLAG_COUNT (sizeof view_flags / sizeof view_flags[0])

bool cli_view_flag(size_t i, cli_flag_doc *out)
{
    if (cli_scene_flag(i, out)) return true;
    size_t n = 0;
    cli_flag_doc d;
    while (cli_scene_flag(n, &d)) n++;
    if (i - n >= VIEW_FLAG_COUNT) return false;
    *out = view_flags[i - n];
    return true;
}

#ifndef PELT_HAVE_GLFW
int cmd_view(int argc, char **argv)
{
    (void)argc, (void)argv;
    cli_error("view", "this pelt was built without GLFW (Debian package libglfw3-dev); "
              "pelt render draws without a window");
    return 1;
}
#else

typedef struct shot {
    float time;
    const char *path;
    bool done;
} shot;

typedef struct view_app {
    /* the command line */
    int argc;
    char **argv;               /* render's flags and the scene file, view's taken out */
    cli_options o;
    const char *scene_path;    /* NULL: no scene file */
    bool has_output, has_frames;
    unsigned max_frames;
    shot shots[MAX_SHOTS];
    int shot_count;
    view_script *script;
    bool scripted;
    /* what the scene becomes */
    char mesh_file[VIEW_PATH_MAX]; /* a dropped mesh, "" = the scene's */
    pelt_scene_instance *inst;
    pelt_renderer *renderer;
    view_window *win;
    view_hud *hud;
    view_state st;
    /* frame bookkeeping */
    uint8_t *pixels;
    size_t pixels_size;
    float wet_share;
    double ms_smooth;
    double *frame_ms;         /* 3 x cap: the whole frame, the fur's draw, the swap */
    unsigned frame_ms_count, frame_ms_cap;
    double draw_ms, swap_ms;  /* this frame's */
    unsigned screenshot_counter;
    char script_shots[16][VIEW_PATH_MAX]; /* this frame's screenshot events */
    struct timespec scene_mtime;
    double mtime_checked;
    /* the run */
    float t;                  /* seconds of the scene's time since the first frame */
    unsigned frame;
    double prev;              /* when the last frame ended */
    int rc;
} view_app;

#define VIEW_FIXED_DT (1.0f / 30.0f) /* a scripted run's step */

static int view_exit_code; /* the last run's, for cmd_view to return */

static void log_to_hud(pelt_log_level level, const char *message, void *user)
{
    if (level <= PELT_LOG_WARNING)
        view_message(user, false, "%s%s", level == PELT_LOG_WARNING ? "warning: " : "", message);
}

/* The scene a build makes: the command line's, with the viewer's changes. */
static pelt_scene build_scene(view_app *a)
{
    pelt_scene s = a->o.scene; /* shallow: the arrays stay a->o's */
    s.fur.layers = a->st.layers;
    snprintf(s.fur_preset, sizeof s.fur_preset, "%s", view_preset_name(a->st.preset));
    if (a->st.shadows) s.fur.look.inter_shadow = true; /* drawn or not per frame */
    if (!a->st.lod) s.fur.lod.mode = PELT_LOD_OFF;
    else if (s.fur.lod.mode == PELT_LOD_OFF) s.fur.lod.mode = PELT_LOD_AUTO;
    if (a->mesh_file[0]) {
        s.mesh.shape = PELT_SHAPE_FILE;
        snprintf(s.mesh.file, sizeof s.mesh.file, "%s", a->mesh_file);
    }
    return s;
}

/* Makes a new instance and renderer for `scene`; on success they replace
 * the old ones (the groom carried over when asked and the mesh is the
 * same); on failure the old ones stay and err says why. */
static bool build(view_app *a, const pelt_scene *scene, bool keep_groom, pelt_error *err)
{
    pelt_scene_instance *inst = NULL;
    pelt_renderer *renderer = NULL;
    pelt_scene_instance_desc d = {.hooks.logger = {log_to_hud, &a->st}};
    if (pelt_scene_instantiate(scene, &d, &inst, err) != PELT_OK) return false;
    if (pelt_renderer_create(pelt_scene_instance_mesh(inst), pelt_scene_instance_fur(inst), NULL,
                             &renderer, err) != PELT_OK) {
        pelt_scene_instance_destroy(inst);
        return false;
    }
    /* The light's maps are made now, so O switches them without a stall. */
    pelt_shadow_desc shadows = scene->shadows;
    shadows.enabled = true;
    pelt_error shadow_err = {0};
    if (pelt_renderer_set_shadows(renderer, &shadows, &shadow_err) != PELT_OK) {
        if (shadow_err.status != PELT_ERR_GL) { /* the scene's settings: refused, as render refuses them */
            *err = shadow_err;
            pelt_renderer_destroy(renderer);
            pelt_scene_instance_destroy(inst);
            return false;
        }
        /* No float render targets here (a WebGL2 without EXT_color_buffer_float):
           the fur draws without the light's shadows, and says so. */
        fprintf(stderr, "pelt view: warning: no shadows from the light: %s\n", shadow_err.message);
    }
    pelt_renderer_set_ground(renderer, &scene->ground);
    if (keep_groom && a->inst) {
        pelt_fur *from = pelt_scene_instance_fur(a->inst), *to = pelt_scene_instance_fur(inst);
        size_t n = pelt_fur_vertex_count(from);
        pelt_groom_value *g = n == pelt_fur_vertex_count(to) ? malloc(n * sizeof *g) : NULL;
        if (g) {
            for (size_t i = 0; i < n; i++) g[i] = pelt_fur_get_groom(from, i);
            pelt_fur_set_groom(to, 0, n, g, NULL);
            free(g);
        }
    }
    pelt_renderer_destroy(a->renderer);
    pelt_scene_instance_destroy(a->inst);
    a->inst = inst;
    a->renderer = renderer;
    return true;
}

static bool scene_mtime(const char *path, struct timespec *out)
{
    struct stat sb;
    if (!path || stat(path, &sb) != 0) return false;
    *out = sb.st_mtim;
    return true;
}

/* Reads the scene file and the flags again. */
static void reload(view_app *a)
{
    cli_options o;
    int rc = cli_parse("view", a->argc, a->argv, &o);
    if (rc) { /* cli_parse printed the message; show its gist too */
        cli_options_free(&o);
        view_message(&a->st, true, "reload failed: %s (see the terminal); the old scene stays",
                     a->scene_path ? a->scene_path : "flags");
        return;
    }
    cli_options old = a->o;
    a->o = o;
    pelt_scene s = build_scene(a);
    s.fur.layers = o.scene.fur.layers; /* the file's layers and curl win on reload */
    snprintf(s.fur_preset, sizeof s.fur_preset, "%s", o.scene.fur_preset);
    pelt_error err = {0};
    if (!build(a, &s, false, &err)) {
        a->o = old;
        cli_options_free(&o);
        view_message(&a->st, true, "%s", err.message);
        return;
    }
    cli_options_free(&old);
    view_state keep = a->st;
    view_input_init(&a->st, a->inst, &a->o.scene);
    a->st.camera = keep.camera, a->st.width = keep.width, a->st.height = keep.height;
    a->st.tool = keep.tool, a->st.radius = keep.radius, a->st.hud = keep.hud, a->st.help = keep.help;
    a->st.lod = keep.lod;
    view_input_apply(&a->st, a->inst);
    view_message(&a->st, false, "reloaded %s", a->scene_path ? a->scene_path : "the scene");
}

static void load_mesh(view_app *a, const char *dropped)
{
    char path[VIEW_PATH_MAX], previous[VIEW_PATH_MAX];
    snprintf(path, sizeof path, "%s", dropped); /* dropped is the state's, which the new scene resets */
    snprintf(previous, sizeof previous, "%s", a->mesh_file);
    snprintf(a->mesh_file, sizeof a->mesh_file, "%s", path);
    pelt_scene s = build_scene(a);
    /* A new mesh is framed by the scene's default camera. */
    pelt_scene defaults;
    pelt_scene_defaults(&defaults);
    s.camera = defaults.camera;
    pelt_scene_free(&defaults);
    s.groom.stroke_count = 0; /* the scene's strokes were for its own mesh */
    s.wetness.droplet_count = 0;
    pelt_error err = {0};
    if (!build(a, &s, false, &err)) {
        snprintf(a->mesh_file, sizeof a->mesh_file, "%s", previous);
        view_message(&a->st, true, "%s", err.message);
        return;
    }
    view_state keep = a->st;
    view_input_init(&a->st, a->inst, &s);
    a->st.width = keep.width, a->st.height = keep.height, a->st.tool = keep.tool;
    a->st.hud = keep.hud, a->st.help = keep.help;
    a->st.radius = 0.05f * a->st.diagonal;
    view_input_apply(&a->st, a->inst);
    view_message(&a->st, false, "loaded %s", path);
}

static void reset(view_app *a)
{
    a->mesh_file[0] = '\0';
    view_state keep = a->st;
    a->st.layers = view_scene_layers(&a->o.scene);
    a->st.lod = a->o.scene.fur.lod.mode != PELT_LOD_OFF;
    a->st.preset = view_preset_of(a->o.scene.fur_preset);
    pelt_scene s = build_scene(a);
    pelt_error err = {0};
    if (!build(a, &s, false, &err)) {
        a->st = keep;
        view_message(&a->st, true, "%s", err.message);
        return;
    }
    view_input_init(&a->st, a->inst, &s);
    a->st.width = keep.width, a->st.height = keep.height;
    a->st.hud = keep.hud;
    view_input_apply(&a->st, a->inst);
    view_message(&a->st, false, "reset");
}

static void rebuild(view_app *a)
{
    pelt_scene s = build_scene(a);
    pelt_error err = {0};
    if (!build(a, &s, true, &err)) {
        view_message(&a->st, true, "%s", err.message);
        return;
    }
    view_input_apply(&a->st, a->inst);
    view_message(&a->st, false, "%u layers, curl %s (groom kept, water and motion start over)",
                 a->st.layers, view_preset_name(a->st.preset)[0] ? view_preset_name(a->st.preset) : "as the scene");
}

static bool write_screenshot(view_app *a, const char *path)
{
    size_t need = (size_t)a->st.width * a->st.height * 4;
    if (need > a->pixels_size) {
        uint8_t *p = realloc(a->pixels, need);
        if (!p) {
            view_message(&a->st, true, "out of memory for a screenshot");
            return false;
        }
        a->pixels = p;
        a->pixels_size = need;
    }
    view_window_read_rgba8(a->win, a->pixels, a->st.width, a->st.height);
    if (!cli_write_png("view", path, a->pixels, a->st.width, a->st.height)) {
        view_message(&a->st, true, "cannot write the screenshot '%s'", path);
        return false;
    }
    return true;
}

static void save_groom(view_app *a)
{
    const char *path = a->o.groom_out ? a->o.groom_out : "pelt-groom.ply";
    pelt_error err = {0};
    if (pelt_fur_save_groom(pelt_scene_instance_fur(a->inst), path, &err) != PELT_OK)
        view_message(&a->st, true, "save groom: %s", err.message);
    else
        view_message(&a->st, false, "groom saved to %s", path);
}

static void handle_requests(view_app *a)
{
    unsigned r = a->st.requests;
    unsigned later = r & (VIEW_REQ_SCREENSHOT | VIEW_REQ_EXIT); /* those come after the draw */
    a->st.requests = 0;
    if (r & VIEW_REQ_RESET) reset(a);
    if (r & VIEW_REQ_RELOAD) reload(a);
    if (r & VIEW_REQ_LOAD_MESH) load_mesh(a, a->st.drop_path);
    if (r & VIEW_REQ_REBUILD) rebuild(a);
    if (r & VIEW_REQ_SAVE_GROOM) save_groom(a);
    a->st.requests |= later; /* a reset or reload starts the state afresh */
}

static float wet_share(pelt_fur *fur)
{
    unsigned n = pelt_fur_mask_size(fur);
    uint8_t *px = malloc((size_t)n * n * 4);
    if (!px) return 0.0f;
    pelt_fur_mask_picture(fur, px);
    size_t wet = 0;
    for (size_t i = 0; i < (size_t)n * n; i++) wet += px[4 * i + 2] > 0;
    free(px);
    return (float)wet / (float)((size_t)n * n);
}

static void draw_hud(view_app *a)
{
    const view_state *st = &a->st;
    pelt_render_stats rs = pelt_renderer_get_stats(a->renderer);
    size_t tris = pelt_mesh_get_stats(pelt_scene_instance_mesh(a->inst)).triangle_count;
    char text[2048];
    int n = snprintf(text, sizeof text,
                     "\x04pelt view\x01  %.1f fps  %.1f ms/frame\n"
                     "triangles %zu a frame (mesh %zu: skin, %u shells%s)  layers %u\n"
                     "tool %s  radius %.3f   \x03[H] help\x01\n"
                     "wet %.1f%% of the surface\n"
                     "wind %s %.0f  gravity %s  rain %s  curl %s\n"
                     "fins %s  inter-fur shadows %s  light's shadows %s",
                     a->ms_smooth > 0.0 ? 1000.0 / a->ms_smooth : 0.0, a->ms_smooth, rs.triangles,
                     tris, rs.shell_instances, st->fins ? ", fins" : "", st->layers, view_tool_name(st->tool),
                     (double)st->radius, 100.0 * (double)a->wet_share,
                     st->wind_on ? "on" : "off", (double)st->wind_strength,
                     st->gravity_on ? "on" : "off", st->rain_on ? "on" : "off",
                     view_preset_name(st->preset)[0] ? view_preset_name(st->preset) : "-",
                     st->fins ? "on" : "off", st->shadows ? "on" : "off", st->light_shadows ? "on" : "off");
    if (st->lod)
        n += snprintf(text + n, sizeof text - (size_t)n, "\nlevel of detail: mesh level %u (%zu triangles), shell level %u",
                      rs.mesh_level, rs.mesh_triangles, rs.shell_level);
    else
        n += snprintf(text + n, sizeof text - (size_t)n, "\nlevel of detail off");
    float scale = st->width >= 700 ? 1.5f : 1.0f;
    if (st->message[0] && st->message_seconds > 0.0f) {
        /* Wrapped to the window: about 6 pixels a character. */
        size_t cols = (size_t)fmaxf(((float)st->width - 24.0f) / (6.0f * scale), 20.0f);
        n += snprintf(text + n, sizeof text - (size_t)n, "\n%s", st->message_is_error ? "\x02" : "\x04");
        size_t len = strlen(st->message);
        for (size_t i = 0; i < len && (size_t)n + 4 < sizeof text; i += cols) {
            if (i) text[n++] = '\n';
            size_t k = len - i < cols ? len - i : cols;
            if ((size_t)n + k + 2 >= sizeof text) break;
            memcpy(text + n, st->message + i, k);
            n += (int)k;
        }
        text[n] = '\0';
    }
    view_hud_text(a->hud, text, 8.0f, 8.0f, scale, st->width, st->height);
    if (st->tool != VIEW_TOOL_ORBIT && st->mx > 0.0f && st->my > 0.0f)
        view_hud_ring(a->hud, st->mx, st->my, view_brush_pixels(st), st->width, st->height);
    if (st->help)
        view_hud_text(a->hud, view_help_text(), 8.0f, 8.0f + scale * 12.0f * 9.0f, scale, st->width,
                      st->height);
}

static double seconds_now(void) { return view_window_time(); }

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* Splits argv into render's flags (for cli_parse) and the viewer's. */
static int take_view_flags(view_app *a, int argc, char **argv)
{
    a->argv = calloc((size_t)argc + 1, sizeof *a->argv);
    if (!a->argv) return 1;
    for (int i = 0; i < argc; i++) {
        const char *f = argv[i];
        if (!strcmp(f, "--no-hud")) {
            a->st.hud = false; /* read back after init */
            continue;
        }
        if (!strcmp(f, "--script") || !strcmp(f, "--screenshot-at")) {
            if (i + 1 >= argc) {
                cli_error("view", "%s needs a value (%s)", f, !strcmp(f, "--script") ? "FILE" : "T:FILE");
                return 2;
            }
            const char *v = argv[++i];
            if (!strcmp(f, "--script")) {
                char err[1024];
                view_script_free(a->script);
                if (!view_script_load(v, 1.0f / 30.0f, &a->script, err, sizeof err)) {
                    cli_error("view", "%s", err);
                    return 2;
                }
            } else {
                char *end;
                errno = 0;
                float t = strtof(v, &end);
                if (end == v || *end != ':' || !end[1] || errno || !(t >= 0.0f) || !isfinite(t)) {
                    cli_error("view", "--screenshot-at '%s': expected T:FILE, seconds >= 0 and a "
                              "PNG path, like 2.5:shot.png", v);
                    return 2;
                }
                if (a->shot_count == MAX_SHOTS) {
                    cli_error("view", "--screenshot-at: at most %d", MAX_SHOTS);
                    return 2;
                }
                a->shots[a->shot_count++] = (shot){t, end + 1, false};
            }
            a->scripted = true;
            continue;
        }
        if (!strcmp(f, "--frames")) a->has_frames = true, a->scripted = true;
        if (!strcmp(f, "-o") || !strcmp(f, "--output")) a->has_output = true;
        a->argv[a->argc++] = argv[i];
    }
    return 0;
}

static void close_app(view_app *a)
{
    view_hud_destroy(a->hud);
    pelt_renderer_destroy(a->renderer);
    pelt_scene_instance_destroy(a->inst);
    view_window_close(a->win);
    view_script_free(a->script);
    cli_options_free(&a->o);
    free(a->argv);
    free(a->pixels);
    free(a->frame_ms);
    free(a);
}

/* One frame: input, requests, the draw, the step. False when the run ends
 * (the window closed, an exit key or event, --frames done). */
static bool view_frame(void *arg)
{
    view_app *a = arg;
    view_window_poll(a->win);
    if (view_window_should_close(a->win)) return false;
    unsigned fw, fh;
    view_window_framebuffer_size(a->win, &fw, &fh);
    if (fw && fh && (fw != a->st.width || fh != a->st.height)) {
        a->st.width = fw, a->st.height = fh;
        pelt_scene_instance_set_camera(a->inst, &a->st.camera, fw, fh);
    }
    /* Input: the window's, or in a scripted run the script's alone. */
    view_event e;
    int script_shot_count = 0;
    while (view_window_next_event(a->win, &e))
        if (!a->scripted) view_input_event(&a->st, a->inst, &e);
    while (a->script && view_script_next(a->script, a->t, &e)) {
        if (e.type == VIEW_EV_SCREENSHOT) {
            if (script_shot_count < 16)
                snprintf(a->script_shots[script_shot_count++], VIEW_PATH_MAX, "%s", e.path);
            continue;
        }
        view_input_event(&a->st, a->inst, &e);
        handle_requests(a); /* a drop or reload before the next event sees the new scene */
    }
    handle_requests(a);
    /* After the script's last event and screenshot, the window is live. */
    if (a->scripted && !a->has_frames && (!a->script || view_script_done(a->script))) {
        bool pending = false;
        for (int i = 0; i < a->shot_count; i++) pending = pending || !a->shots[i].done;
        if (!pending && a->frame > 0) a->scripted = false;
    }

    /* Draw. */
    if (a->frame % 15 == 0) a->wet_share = wet_share(pelt_scene_instance_fur(a->inst));
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, (GLsizei)a->st.width, (GLsizei)a->st.height);
    const float *bg = a->o.scene.output.background;
    glClearColor(bg[0], bg[1], bg[2], bg[3]);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    pelt_view view = pelt_scene_instance_view(a->inst);
    pelt_draw_desc draw = a->o.scene.draw; /* the viewer's toggles over the scene's */
    draw.no_fins = !a->st.fins;
    draw.debug.no_inter_shadow = !a->st.shadows;
    draw.debug.no_shadows = !a->st.light_shadows;
    double t_draw = seconds_now();
    pelt_renderer_draw(a->renderer, &view, &draw);
    glFinish(); /* the draw's time apart from the swap's, for the summary */
    a->draw_ms = (seconds_now() - t_draw) * 1000.0;
    if (a->st.hud) draw_hud(a);
    for (int i = 0; i < a->shot_count; i++)
        if (!a->shots[i].done && a->shots[i].time <= a->t + 5e-4f) {
            a->shots[i].done = true;
            if (!write_screenshot(a, a->shots[i].path)) a->rc = 1;
        }
    for (int i = 0; i < script_shot_count; i++)
        if (!write_screenshot(a, a->script_shots[i])) a->rc = 1;
    if (a->st.requests & VIEW_REQ_SCREENSHOT) {
        char path[4096];
        unsigned k = a->screenshot_counter++;
        if (a->has_output) cli_frame_path(a->o.output, k, path, sizeof path);
        else snprintf(path, sizeof path, "pelt-view-%03u.png", k);
        if (write_screenshot(a, path)) view_message(&a->st, false, "screenshot %s", path);
        a->st.requests &= ~(unsigned)VIEW_REQ_SCREENSHOT;
    }
    double t_swap = seconds_now();
    view_window_swap(a->win);
    a->swap_ms = (seconds_now() - t_swap) * 1000.0;

    /* Time: the real frame time, clamped; fixed steps when scripted. */
    double now = seconds_now();
    double ms = (now - a->prev) * 1000.0;
    a->prev = now;
    if (a->frame > 0) {
        a->ms_smooth = a->ms_smooth > 0.0 ? 0.9 * a->ms_smooth + 0.1 * ms : ms;
        if (a->frame_ms && a->frame_ms_count < a->frame_ms_cap) {
            unsigned i = a->frame_ms_count++, cap = a->frame_ms_cap;
            a->frame_ms[i] = ms;
            a->frame_ms[cap + i] = a->draw_ms;
            a->frame_ms[2 * (size_t)cap + i] = a->swap_ms;
        }
    }
    a->frame++;
    if (a->st.requests & VIEW_REQ_EXIT) return false;
    if (a->max_frames && a->frame >= a->max_frames) return false;
    float dt = a->scripted ? VIEW_FIXED_DT : (float)fmin(fmax(ms / 1000.0, 1.0 / 240.0), 1.0 / 15.0);
    view_input_frame(&a->st, a->inst, dt);
    pelt_scene_instance_advance(a->inst, dt);
    a->t += dt;
    /* The scene file, once a second: reload when it changed. */
    if (a->scene_path && now - a->mtime_checked >= 1.0) {
        a->mtime_checked = now;
        struct timespec m;
        if (scene_mtime(a->scene_path, &m) &&
            (m.tv_sec != a->scene_mtime.tv_sec || m.tv_nsec != a->scene_mtime.tv_nsec)) {
            a->scene_mtime = m;
            reload(a);
        }
    }
    return true;
}

/* After the last frame: the summary, the mask, everything freed. */
static void view_finish(void *arg)
{
    view_app *a = arg;
    if (!a->o.quiet && a->frame_ms_count > 0) {
        double med[3];
        for (int p = 0; p < 3; p++) {
            double *v = a->frame_ms + (size_t)p * a->frame_ms_cap;
            qsort(v, a->frame_ms_count, sizeof *v, cmp_double);
            med[p] = v[a->frame_ms_count / 2];
        }
        fprintf(stderr,
                "pelt view: %u frames at %ux%u, median %.1f ms per frame (%.1f fps): fur drawn in "
                "%.1f ms, swap %.1f ms\n",
                a->frame, a->st.width, a->st.height, med[0], med[0] > 0.0 ? 1000.0 / med[0] : 0.0,
                med[1], med[2]);
    }
    if (a->rc == 0 && a->o.mask_out) {
        pelt_fur *fur = pelt_scene_instance_fur(a->inst);
        unsigned m = pelt_fur_mask_size(fur);
        uint8_t *mask = malloc((size_t)m * m * 4);
        if (mask) {
            pelt_fur_mask_picture(fur, mask);
            if (!cli_write_png("view", a->o.mask_out, mask, m, m)) a->rc = 1;
            free(mask);
        }
    }
    view_exit_code = a->rc;
    close_app(a);
}

int cmd_view(int argc, char **argv)
{
    /* On the heap: in the browser this function returns before the first
       frame, and the frames go on with the app (view_window_run). */
    view_app *a = calloc(1, sizeof *a);
    if (!a) {
        cli_error("view", "out of memory");
        return 1;
    }
    a->st.hud = true;
    int rc = take_view_flags(a, argc, argv);
    bool hud_flag = a->st.hud;
    if (rc == 0) rc = cli_parse("view", a->argc, a->argv, &a->o);
    else pelt_scene_defaults(&a->o.scene);
    if (rc) {
        close_app(a);
        return rc == 1 ? 0 : rc;
    }
    if (a->argc > 0 && a->argv[0][0] != '-') a->scene_path = a->argv[0];
    if (a->has_frames) a->max_frames = a->o.scene.animation.frames;
    a->scripted = a->scripted || a->script;

    char err[1024];
    char title[256];
    snprintf(title, sizeof title, "pelt view - %s", a->scene_path ? a->scene_path : "default scene");
    const pelt_scene *sc = &a->o.scene;
    if (!view_window_open(title, sc->output.width, sc->output.height, sc->output.msaa, &a->win, err,
                          sizeof err)) {
        cli_error("view", "%s", err);
        close_app(a);
        return 1;
    }
    if (!view_hud_create(&a->hud, err, sizeof err)) {
        cli_error("view", "%s", err);
        close_app(a);
        return 1;
    }
    pelt_error perr = {0};
    a->st.layers = view_scene_layers(sc);
    a->st.lod = sc->fur.lod.mode != PELT_LOD_OFF;
    a->st.preset = view_preset_of(sc->fur_preset);
    pelt_scene s = build_scene(a);
    if (!build(a, &s, false, &perr)) {
        cli_error("view", "%s", perr.message);
        close_app(a);
        return 1;
    }
    view_input_init(&a->st, a->inst, sc);
    a->st.hud = hud_flag;
    for (int i = 0; i < a->o.drop_count; i++) {
        const float *d = a->o.drops[i];
        if (!pelt_scene_instance_drop_at_pixel(a->inst, d[0], d[1], d[2], 1.0f))
            fprintf(stderr, "pelt view: warning: --drop-at %g,%g misses the mesh\n", (double)d[0],
                    (double)d[1]);
    }
    scene_mtime(a->scene_path, &a->scene_mtime);
    a->frame_ms_cap = 1u << 16;
    a->frame_ms = malloc(3 * (size_t)a->frame_ms_cap * sizeof *a->frame_ms);

    a->prev = seconds_now();
    a->mtime_checked = a->prev;
    a->rc = 0;
    view_window_run(a->win, view_frame, view_finish, a);
    return view_exit_code;
}
#endif
