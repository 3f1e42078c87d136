/* pelt view: input -> camera, tools and switches. Events come from the
 * window or from a script alike (apps/view.h), so a scripted run takes
 * the same paths as a hand on the mouse. */
#include "apps/view.h"

#include "pelt/params.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

const char *view_preset_name(int i) { return i <= 0 ? "" : pelt_curl_preset_names[i - 1]; }

int view_preset_of(const char *name)
{
    int i = pelt_curl_preset_index(name);
    return i < 0 ? 0 : i + 1;
}

static int preset_count(void)
{
    int n = 0;
    while (pelt_curl_preset_names[n]) n++;
    return n + 1; /* and the scene's own curl */
}

unsigned view_scene_layers(const pelt_scene *sc)
{
    return sc->fur.layers ? sc->fur.layers : (unsigned)pelt_fur_param("layers")->def[0];
}

static const char *const tool_names[VIEW_TOOL_COUNT] = {"orbit", "water", "hair dryer", "comb",
                                                        "length"};

const char *view_tool_name(view_tool t) { return t < VIEW_TOOL_COUNT ? tool_names[t] : "?"; }

const char *view_help_text(void)
{
    return "\x04mouse\x01\n"
           "  left drag     the tool on the fur; on the background: orbit\n"
           "  right drag    orbit        middle drag   pan\n"
           "  wheel         zoom         drop a file   load it as the mesh\n"
           "\x04tools\x01\n"
           "  0  orbit       left drag orbits everywhere\n"
           "  1  water       click: a droplet; hold: rain under the cursor\n"
           "  2  hair dryer  hold: dries and blows along the view, under the cursor\n"
           "  3  comb        drag: the hair under the brush leans along the drag\n"
           "  4  length      drag: longer; with shift: shorter\n"
           "  [ ]  brush radius\n"
           "\x04keys\x01\n"
           "  W  wind on/off      - =  wind strength\n"
           "  G  gravity on/off   R  rain on/off   T  towel (dry all)\n"
           "  C  curl preset      Up/Down  layers x2 / /2\n"
           "  F  fins on/off      S  inter-fur shadows on/off\n"
           "  O  shadows from the light on/off (on a ground when ground.enabled)\n"
           "  L  level of detail on/off (docs/lod.md)\n"
           "  Backspace  reset    P  screenshot   Ctrl+S  save the groom\n"
           "  F5  reload the scene (also when its file changes)\n"
           "  Tab  HUD on/off     H  this help    Esc  quit";
}

void view_message(view_state *st, bool error, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(st->message, sizeof st->message, fmt, ap);
    va_end(ap);
    st->message_is_error = error;
    st->message_seconds = error ? 30.0f : 4.0f;
    fprintf(stderr, "pelt view: %s%s\n", error ? "" : "", st->message);
}

static float len3(const float v[3]) { return sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

static float mesh_diagonal(pelt_scene_instance *inst)
{
    float lo[3], hi[3];
    pelt_mesh_bounds(pelt_scene_instance_mesh(inst), lo, hi);
    float d[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    pelt_view v = pelt_scene_instance_view(inst);
    float s = sqrtf(v.model[0] * v.model[0] + v.model[1] * v.model[1] + v.model[2] * v.model[2]);
    float diag = len3(d) * (s > 0.0f ? s : 1.0f);
    return diag > 0.0f ? diag : 1.0f;
}

void view_input_init(view_state *st, pelt_scene_instance *inst, const pelt_scene *scene)
{
    memset(st, 0, sizeof *st);
    pelt_view v = pelt_scene_instance_view(inst);
    st->camera = pelt_scene_instance_camera(inst);
    st->width = v.width;
    st->height = v.height;
    st->tool = VIEW_TOOL_ORBIT;
    st->diagonal = mesh_diagonal(inst);
    st->radius = 0.05f * st->diagonal;
    st->rng = 0x9e3779b9u;
    st->scene_forces = pelt_scene_instance_forces(inst);
    float w = len3(st->scene_forces.wind);
    st->wind_on = w > 0.0f;
    st->wind_strength = w > 0.0f ? w : 20.0f;
    for (int k = 0; k < 3; k++) st->wind_dir[k] = w > 0.0f ? st->scene_forces.wind[k] / w : k == 0;
    st->gravity_on = len3(st->scene_forces.gravity) > 0.0f;
    st->rain_rate = scene->wetness.rain.rate > 0.0f ? scene->wetness.rain.rate : 60.0f;
    st->rain_on = scene->wetness.rain.rate > 0.0f;
    st->preset = view_preset_of(scene->fur_preset);
    st->layers = view_scene_layers(scene);
    st->fins = !scene->draw.no_fins;
    st->shadows = scene->fur.look.inter_shadow;
    st->light_shadows = scene->shadows.enabled;
    st->lod = scene->fur.lod.mode != PELT_LOD_OFF;
    st->hud = true;
}

/* xorshift32: the held water tool's drops, the same for every run. */
static float rnd(view_state *st)
{
    uint32_t x = st->rng;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    st->rng = x;
    return (float)(x >> 8) / 16777216.0f;
}

/* World units per pixel at the camera's target distance. */
static float world_per_pixel(const view_state *st)
{
    float h = st->height ? (float)st->height : 1.0f;
    return 2.0f * st->camera.distance * tanf(st->camera.fov_y * 0.5f * 3.14159265f / 180.0f) / h;
}

float view_brush_pixels(const view_state *st) { return st->radius / world_per_pixel(st); }

static void apply_camera(view_state *st, pelt_scene_instance *inst)
{
    pelt_scene_instance_set_camera(inst, &st->camera, st->width, st->height);
}

/* Does the ray through the cursor see the mesh? */
static bool sees_mesh(pelt_scene_instance *inst, float x, float y)
{
    pelt_view v = pelt_scene_instance_view(inst);
    float o[3], d[3], hit[3];
    return pelt_view_pixel_ray(&v, x, y, o, d) &&
           pelt_fur_pick(pelt_scene_instance_fur(inst), o, d, hit);
}

/* The comb and length tools along one move of the cursor. */
static void stroke(view_state *st, pelt_scene_instance *inst, float dx, float dy)
{
    if (dx == 0.0f && dy == 0.0f) return;
    pelt_brush b = {.radius = st->radius, .strength = 1.0f};
    if (st->tool == VIEW_TOOL_COMB) {
        b.tool = PELT_BRUSH_COMB;
        float drag[2] = {dx, dy};
        pelt_scene_instance_brush_at_pixel(inst, st->last_x, st->last_y, &b, drag);
    } else {
        b.tool = PELT_BRUSH_LENGTH;
        b.amount = 0.004f * sqrtf(dx * dx + dy * dy) * (st->shift ? -1.0f : 1.0f);
        pelt_scene_instance_brush_at_pixel(inst, st->mx, st->my, &b, NULL);
    }
}

static void key(view_state *st, pelt_scene_instance *inst, int k, int mods)
{
    bool ctrl = mods & GLFW_MOD_CONTROL;
    switch (k) {
    case GLFW_KEY_0: case GLFW_KEY_1: case GLFW_KEY_2: case GLFW_KEY_3: case GLFW_KEY_4:
        st->tool = (view_tool)(k - GLFW_KEY_0);
        view_message(st, false, "tool: %s", view_tool_name(st->tool));
        break;
    case GLFW_KEY_LEFT_BRACKET:
        st->radius = fmaxf(st->radius / 1.25f, 0.002f * st->diagonal);
        break;
    case GLFW_KEY_RIGHT_BRACKET:
        st->radius = fminf(st->radius * 1.25f, 0.5f * st->diagonal);
        break;
    case GLFW_KEY_W:
        st->wind_on = !st->wind_on;
        st->forces_touched = true;
        break;
    case GLFW_KEY_MINUS:
        st->wind_strength = fmaxf(st->wind_strength / 1.25f, 1.0f);
        st->forces_touched = true;
        break;
    case GLFW_KEY_EQUAL:
        st->wind_strength = fminf(st->wind_strength * 1.25f, 500.0f);
        st->forces_touched = true;
        break;
    case GLFW_KEY_G:
        st->gravity_on = !st->gravity_on;
        st->forces_touched = true;
        break;
    case GLFW_KEY_R:
        st->rain_on = !st->rain_on;
        pelt_scene_instance_set_rain_rate(inst, st->rain_on ? st->rain_rate : 0.0f);
        break;
    case GLFW_KEY_T:
        pelt_fur_clear_wetness(pelt_scene_instance_fur(inst));
        view_message(st, false, "towel: all dry");
        break;
    case GLFW_KEY_C:
        st->preset = (st->preset + 1) % preset_count();
        st->requests |= VIEW_REQ_REBUILD;
        break;
    case GLFW_KEY_UP:
    case GLFW_KEY_PAGE_UP:
        if (st->layers < 256) st->layers = st->layers * 2 > 256 ? 256 : st->layers * 2;
        st->requests |= VIEW_REQ_REBUILD;
        break;
    case GLFW_KEY_DOWN:
    case GLFW_KEY_PAGE_DOWN:
        if (st->layers > 2) st->layers /= 2;
        st->requests |= VIEW_REQ_REBUILD;
        break;
    case GLFW_KEY_L:
        /* The levels are the fur's (fur.lod): made again, groom kept. */
        st->lod = !st->lod;
        st->requests |= VIEW_REQ_REBUILD;
        view_message(st, false, "level of detail %s", st->lod ? "on" : "off");
        break;
    case GLFW_KEY_F:
        st->fins = !st->fins;
        view_message(st, false, "fins %s", st->fins ? "on" : "off");
        break;
    case GLFW_KEY_S:
        if (ctrl) {
            st->requests |= VIEW_REQ_SAVE_GROOM;
            break;
        }
        st->shadows = !st->shadows;
        /* A fur made without them needs making again (groom kept). */
        if (st->shadows && !pelt_fur_get_desc(pelt_scene_instance_fur(inst)).look.inter_shadow)
            st->requests |= VIEW_REQ_REBUILD;
        view_message(st, false, "inter-fur shadows %s", st->shadows ? "on" : "off");
        break;
    case GLFW_KEY_O:
        st->light_shadows = !st->light_shadows;
        view_message(st, false, "shadows from the light %s", st->light_shadows ? "on" : "off");
        break;
    case GLFW_KEY_BACKSPACE: st->requests |= VIEW_REQ_RESET; break;
    case GLFW_KEY_P: st->requests |= VIEW_REQ_SCREENSHOT; break;
    case GLFW_KEY_F5: st->requests |= VIEW_REQ_RELOAD; break;
    case GLFW_KEY_H: st->help = !st->help; break;
    case GLFW_KEY_TAB: st->hud = !st->hud; break;
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q: st->requests |= VIEW_REQ_EXIT; break;
    default: break;
    }
}

void view_input_event(view_state *st, pelt_scene_instance *inst, const view_event *e)
{
    switch (e->type) {
    case VIEW_EV_MOVE: {
        float dx = e->x - st->mx, dy = e->y - st->my;
        st->last_x = st->mx, st->last_y = st->my;
        st->mx = e->x, st->my = e->y;
        if (st->orbiting) {
            st->camera.yaw -= 0.3f * dx;
            st->camera.pitch = fminf(fmaxf(st->camera.pitch + 0.3f * dy, -89.0f), 89.0f);
            apply_camera(st, inst);
        } else if (st->button[2]) {
            pelt_view v = pelt_scene_instance_view(inst);
            float s = world_per_pixel(st);
            for (int k = 0; k < 3; k++) /* view rows 0 and 1: right and up in world */
                st->camera.target[k] += s * (-dx * v.view[4 * k] + dy * v.view[4 * k + 1]);
            apply_camera(st, inst);
        } else if (st->button[0] && (st->tool == VIEW_TOOL_COMB || st->tool == VIEW_TOOL_LENGTH)) {
            stroke(st, inst, dx, dy);
        }
        break;
    }
    case VIEW_EV_BUTTON: {
        if (e->button < 0 || e->button > 2) break;
        if (!isnan(e->x)) st->mx = e->x, st->my = e->y;
        st->last_x = st->mx, st->last_y = st->my;
        st->button[e->button] = e->press;
        if (e->press) st->shift = e->mods & GLFW_MOD_SHIFT;
        if (!e->press) {
            if (e->button == 0 || e->button == 1) st->orbiting = false;
            if (e->button == 0) st->hold_seconds = 0.0f;
            break;
        }
        if (e->button == 1) st->orbiting = true;
        if (e->button != 0) break;
        if (st->tool == VIEW_TOOL_ORBIT || !sees_mesh(inst, st->mx, st->my)) {
            st->orbiting = true; /* on the background every tool orbits */
            break;
        }
        st->hold_seconds = 0.0f;
        if (st->tool == VIEW_TOOL_WATER)
            pelt_scene_instance_drop_at_pixel(inst, st->mx, st->my, st->radius, 1.0f);
        break;
    }
    case VIEW_EV_SCROLL:
        st->camera.distance *= powf(0.9f, e->y);
        st->camera.distance = fminf(fmaxf(st->camera.distance, 0.05f * st->diagonal),
                                    20.0f * st->diagonal);
        apply_camera(st, inst);
        break;
    case VIEW_EV_KEY:
        if (e->key == GLFW_KEY_LEFT_SHIFT || e->key == GLFW_KEY_RIGHT_SHIFT) st->shift = e->press;
        if (e->press) key(st, inst, e->key, e->mods);
        break;
    case VIEW_EV_DROP:
        snprintf(st->drop_path, sizeof st->drop_path, "%s", e->path);
        st->requests |= VIEW_REQ_LOAD_MESH;
        break;
    case VIEW_EV_EXIT:
        st->requests |= VIEW_REQ_EXIT;
        break;
    case VIEW_EV_SCREENSHOT: /* the frame loop's */
        break;
    }
}

/* The switches and the dryer's air as the instance's forces. */
static void apply_forces(view_state *st, pelt_scene_instance *inst, bool blowing)
{
    pelt_forces f = st->scene_forces;
    for (int k = 0; k < 3; k++) {
        if (st->forces_touched) {
            f.wind[k] = st->wind_on ? st->wind_dir[k] * st->wind_strength : 0.0f;
            if (!st->gravity_on) f.gravity[k] = 0.0f;
        }
        if (blowing) { /* the dryer's air, around the point under the cursor */
            f.blow[k] = st->blow_dir[k] * 60.0f * fminf(st->blow_seconds / 0.3f, 1.0f);
            f.blow_center[k] = st->blow_center[k];
        }
    }
    f.blow_radius = blowing ? 1.5f * st->radius : 0.0f;
    pelt_scene_instance_set_forces(inst, &f);
}

void view_input_apply(view_state *st, pelt_scene_instance *inst)
{
    apply_camera(st, inst);
    if (st->forces_touched) apply_forces(st, inst, false);
    if (st->rain_on) pelt_scene_instance_set_rain_rate(inst, st->rain_rate);
}

void view_input_frame(view_state *st, pelt_scene_instance *inst, float dt)
{
    bool held = st->button[0] && !st->orbiting;
    if (held) st->hold_seconds += dt;
    if (st->message_seconds > 0.0f) st->message_seconds -= dt;
    if (held && st->tool == VIEW_TOOL_WATER && st->hold_seconds > 0.25f) {
        /* Rain under the cursor: 30 drops a second within the brush. */
        st->rain_carry += 30.0f * dt;
        float px = st->radius / world_per_pixel(st);
        for (; st->rain_carry >= 1.0f; st->rain_carry -= 1.0f) {
            float a = 6.2831853f * rnd(st), r = px * sqrtf(rnd(st));
            pelt_scene_instance_drop_at_pixel(inst, st->mx + r * cosf(a), st->my + r * sinf(a),
                                              st->radius * 0.4f, 0.8f);
        }
    }
    if (held && st->tool == VIEW_TOOL_DRYER && dt > 0.0f) {
        /* Dry 2.5 wetness a second over a little more than the brush, and
         * blow along the ray through the cursor for a moment. */
        pelt_scene_instance_drop_at_pixel(inst, st->mx, st->my, st->radius * 1.25f,
                                          -fminf(2.5f * dt, 1.0f));
        pelt_view v = pelt_scene_instance_view(inst);
        float o[3], d[3], hit[3];
        if (pelt_view_pixel_ray(&v, st->mx, st->my, o, d) &&
            pelt_fur_pick(pelt_scene_instance_fur(inst), o, d, hit)) {
            const float *m = v.model; /* the hit in world units */
            for (int k = 0; k < 3; k++)
                st->blow_center[k] = m[k] * hit[0] + m[4 + k] * hit[1] + m[8 + k] * hit[2] + m[12 + k];
            static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
            memcpy(v.model, identity, sizeof identity); /* the ray in world units */
            if (pelt_view_pixel_ray(&v, st->mx, st->my, o, d)) {
                memcpy(st->blow_dir, d, sizeof d);
                st->blow_seconds = 0.6f;
            }
        }
    }
    bool blowing = st->blow_seconds > 0.0f;
    if (st->forces_touched || blowing || st->was_blowing) apply_forces(st, inst, blowing);
    st->was_blowing = blowing;
    if (blowing) st->blow_seconds -= dt;
}
