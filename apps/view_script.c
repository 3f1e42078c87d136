/* pelt view --script FILE: timed input events, one a line (docs/viewer.md):
 *
 *   # seconds  event        arguments
 *   0.5        move         X Y
 *   0.5        down|up      [left|right|middle] [shift] [ctrl]
 *   1.0        click        X Y [left|right|middle] [shift] [ctrl]
 *   1.0        drag         X0 Y0 X1 Y1 SECONDS [left|right|middle] [shift] [ctrl]
 *   1.0        hold         X Y SECONDS [left|right|middle] [shift] [ctrl]
 *   2.0        key          NAME      (press and release; shift+NAME, ctrl+NAME)
 *   2.0        keydown|keyup NAME
 *   2.0        scroll       CLICKS
 *   3.0        drop         FILE
 *   3.0        screenshot   FILE
 *   4.0        exit
 *
 * A click releases one frame after it presses; a drag moves once a frame.
 * Events of the same time keep the file's order. */
#include "apps/view.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

typedef struct timed {
    float time;
    size_t order;
    view_event e;
} timed;

struct view_script {
    timed *events;
    size_t count, cap, next;
};

static bool add(view_script *s, float time, const view_event *e)
{
    if (s->count == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 64;
        timed *t = realloc(s->events, cap * sizeof *t);
        if (!t) return false;
        s->events = t;
        s->cap = cap;
    }
    s->events[s->count] = (timed){time, s->count, *e};
    s->count++;
    return true;
}

static int by_time(const void *a, const void *b)
{
    const timed *x = a, *y = b;
    if (x->time != y->time) return x->time < y->time ? -1 : 1;
    return (x->order > y->order) - (x->order < y->order);
}

static const struct { const char *name; int key; } key_names[] = {
    {"space", GLFW_KEY_SPACE}, {"escape", GLFW_KEY_ESCAPE}, {"esc", GLFW_KEY_ESCAPE},
    {"tab", GLFW_KEY_TAB}, {"backspace", GLFW_KEY_BACKSPACE}, {"enter", GLFW_KEY_ENTER},
    {"up", GLFW_KEY_UP}, {"down", GLFW_KEY_DOWN}, {"left", GLFW_KEY_LEFT},
    {"right", GLFW_KEY_RIGHT}, {"pageup", GLFW_KEY_PAGE_UP}, {"pagedown", GLFW_KEY_PAGE_DOWN},
    {"home", GLFW_KEY_HOME}, {"shift", GLFW_KEY_LEFT_SHIFT}, {"ctrl", GLFW_KEY_LEFT_CONTROL},
    {"f1", GLFW_KEY_F1}, {"f2", GLFW_KEY_F2}, {"f3", GLFW_KEY_F3}, {"f4", GLFW_KEY_F4},
    {"f5", GLFW_KEY_F5}, {"f6", GLFW_KEY_F6}, {"f7", GLFW_KEY_F7}, {"f8", GLFW_KEY_F8},
    {"f9", GLFW_KEY_F9}, {"f10", GLFW_KEY_F10}, {"f11", GLFW_KEY_F11}, {"f12", GLFW_KEY_F12},
    {"[", GLFW_KEY_LEFT_BRACKET}, {"]", GLFW_KEY_RIGHT_BRACKET}, {"-", GLFW_KEY_MINUS},
    {"=", GLFW_KEY_EQUAL}, {",", GLFW_KEY_COMMA}, {".", GLFW_KEY_PERIOD}, {"/", GLFW_KEY_SLASH},
};

/* "shift+ctrl+s" -> key and mods; false for an unknown name. */
static bool parse_key(const char *word, int *key, int *mods)
{
    *mods = 0;
    char buf[64];
    snprintf(buf, sizeof buf, "%s", word);
    char *name = buf;
    for (;;) {
        char *plus = strchr(name, '+');
        if (!plus || plus == name) break;
        *plus = '\0';
        if (!strcasecmp(name, "shift")) *mods |= GLFW_MOD_SHIFT;
        else if (!strcasecmp(name, "ctrl")) *mods |= GLFW_MOD_CONTROL;
        else return false;
        name = plus + 1;
    }
    if (strlen(name) == 1 && isalnum((unsigned char)name[0])) {
        *key = isdigit((unsigned char)name[0]) ? GLFW_KEY_0 + (name[0] - '0')
                                               : GLFW_KEY_A + (toupper((unsigned char)name[0]) - 'A');
        return true;
    }
    for (size_t i = 0; i < sizeof key_names / sizeof key_names[0]; i++)
        if (!strcasecmp(name, key_names[i].name)) {
            *key = key_names[i].key;
            return true;
        }
    return false;
}

static bool parse_float(const char *w, float *out)
{
    if (!w) return false;
    char *end;
    errno = 0;
    float v = strtof(w, &end);
    if (end == w || *end || errno || !isfinite(v)) return false;
    *out = v;
    return true;
}

/* Trailing words of a mouse event: button name and modifiers. */
static bool parse_mouse_words(char **words, int n, int *button, int *mods)
{
    *button = 0;
    *mods = 0;
    for (int i = 0; i < n; i++) {
        if (!strcmp(words[i], "left")) *button = 0;
        else if (!strcmp(words[i], "right")) *button = 1;
        else if (!strcmp(words[i], "middle")) *button = 2;
        else if (!strcmp(words[i], "shift")) *mods |= GLFW_MOD_SHIFT;
        else if (!strcmp(words[i], "ctrl")) *mods |= GLFW_MOD_CONTROL;
        else return false;
    }
    return true;
}

static const char *usage_of(const char *ev)
{
    static const char *const u[][2] = {
        {"move", "move X Y"}, {"down", "down [left|right|middle] [shift] [ctrl]"},
        {"up", "up [left|right|middle]"}, {"click", "click X Y [button] [shift] [ctrl]"},
        {"drag", "drag X0 Y0 X1 Y1 SECONDS [button] [shift] [ctrl]"},
        {"hold", "hold X Y SECONDS [button] [shift] [ctrl]"}, {"key", "key NAME"},
        {"keydown", "keydown NAME"}, {"keyup", "keyup NAME"}, {"scroll", "scroll CLICKS"},
        {"drop", "drop FILE"}, {"screenshot", "screenshot FILE"}, {"exit", "exit"}};
    for (size_t i = 0; i < sizeof u / sizeof u[0]; i++)
        if (!strcmp(ev, u[i][0])) return u[i][1];
    return NULL;
}

/* One line's events; false with the reason in err. */
static bool parse_line(view_script *s, char *line, float dt, char *err, size_t err_size)
{
    char *words[16];
    int n = 0;
    for (char *w = strtok(line, " \t\r\n"); w && n < 16; w = strtok(NULL, " \t\r\n")) words[n++] = w;
    if (n == 0) return true;
    float t;
    if (!parse_float(words[0], &t) || t < 0.0f) {
        snprintf(err, err_size, "'%s' is not a time in seconds (>= 0)", words[0]);
        return false;
    }
    if (n < 2) {
        snprintf(err, err_size, "a time without an event");
        return false;
    }
    const char *ev = words[1];
    const char *usage = usage_of(ev);
    if (!usage) {
        snprintf(err, err_size,
                 "unknown event '%s' (move, down, up, click, drag, hold, key, keydown, keyup, "
                 "scroll, drop, screenshot, exit)", ev);
        return false;
    }
    char **a = words + 2;
    int na = n - 2;
    view_event e = {0};
    bool ok = true;
    float x0 = 0.0f, y0 = 0.0f, x1 = 0.0f, y1 = 0.0f, secs = 0.0f; /* read only when parsed */
    int button = 0, mods = 0;
    if (!strcmp(ev, "move")) {
        ok = na == 2 && parse_float(a[0], &e.x) && parse_float(a[1], &e.y);
        e.type = VIEW_EV_MOVE;
        ok = ok && add(s, t, &e);
    } else if (!strcmp(ev, "down") || !strcmp(ev, "up")) {
        ok = parse_mouse_words(a, na, &button, &mods);
        e = (view_event){.type = VIEW_EV_BUTTON, .x = NAN, .button = button, .mods = mods,
                         .press = !strcmp(ev, "down")};
        ok = ok && add(s, t, &e);
    } else if (!strcmp(ev, "click")) {
        ok = na >= 2 && parse_float(a[0], &x0) && parse_float(a[1], &y0) &&
             parse_mouse_words(a + 2, na - 2, &button, &mods);
        view_event m = {.type = VIEW_EV_MOVE, .x = x0, .y = y0};
        view_event p = {.type = VIEW_EV_BUTTON, .x = x0, .y = y0, .button = button, .mods = mods,
                        .press = true};
        view_event r = p;
        r.press = false;
        ok = ok && add(s, t, &m) && add(s, t, &p) && add(s, t + dt, &r);
    } else if (!strcmp(ev, "drag") || !strcmp(ev, "hold")) {
        bool drag = !strcmp(ev, "drag");
        int fixed = drag ? 5 : 3;
        ok = na >= fixed && parse_float(a[0], &x0) && parse_float(a[1], &y0) &&
             parse_float(a[fixed - 1], &secs) && secs > 0.0f &&
             parse_mouse_words(a + fixed, na - fixed, &button, &mods);
        x1 = x0, y1 = y0;
        if (ok && drag) ok = parse_float(a[2], &x1) && parse_float(a[3], &y1);
        if (ok) {
            view_event m = {.type = VIEW_EV_MOVE, .x = x0, .y = y0};
            view_event p = {.type = VIEW_EV_BUTTON, .x = x0, .y = y0, .button = button,
                            .mods = mods, .press = true};
            ok = add(s, t, &m) && add(s, t, &p);
            int steps = (int)ceilf(secs / dt - 1e-4f);
            if (steps < 1) steps = 1;
            for (int i = 1; ok && drag && i <= steps; i++) {
                float f = (float)i / (float)steps;
                view_event mv = {.type = VIEW_EV_MOVE, .x = x0 + f * (x1 - x0),
                                 .y = y0 + f * (y1 - y0)};
                ok = add(s, t + (float)i * dt, &mv);
            }
            view_event r = p;
            r.x = x1, r.y = y1, r.press = false;
            ok = ok && add(s, t + (float)steps * dt + (drag ? dt : 0.0f), &r);
        }
    } else if (!strcmp(ev, "key") || !strcmp(ev, "keydown") || !strcmp(ev, "keyup")) {
        ok = na == 1 && parse_key(a[0], &e.key, &e.mods);
        e.type = VIEW_EV_KEY;
        e.press = strcmp(ev, "keyup") != 0;
        ok = ok && add(s, t, &e);
        if (ok && !strcmp(ev, "key")) {
            e.press = false;
            ok = add(s, t + dt, &e);
        }
    } else if (!strcmp(ev, "scroll")) {
        ok = na == 1 && parse_float(a[0], &e.y);
        e.type = VIEW_EV_SCROLL;
        ok = ok && add(s, t, &e);
    } else if (!strcmp(ev, "drop") || !strcmp(ev, "screenshot")) {
        ok = na == 1 && strlen(a[0]) < VIEW_PATH_MAX;
        e.type = !strcmp(ev, "drop") ? VIEW_EV_DROP : VIEW_EV_SCREENSHOT;
        if (ok) snprintf(e.path, sizeof e.path, "%s", a[0]);
        ok = ok && add(s, t, &e);
    } else { /* exit */
        ok = na == 0;
        e.type = VIEW_EV_EXIT;
        ok = ok && add(s, t, &e);
    }
    if (!ok) snprintf(err, err_size, "expected: TIME %s", usage);
    return ok;
}

bool view_script_load(const char *path, float frame_dt, view_script **out, char *err,
                      size_t err_size)
{
    *out = NULL;
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, err_size, "--script '%s': %s", path, strerror(errno));
        return false;
    }
    view_script *s = calloc(1, sizeof *s);
    if (!s) {
        fclose(f);
        snprintf(err, err_size, "out of memory");
        return false;
    }
    char line[2048], why[512];
    unsigned lineno = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        char *hash = strchr(line, '#');
        if (hash) *hash = '\0';
        if (!parse_line(s, line, frame_dt, why, sizeof why)) {
            snprintf(err, err_size, "--script '%s' line %u: %s", path, lineno, why);
            fclose(f);
            view_script_free(s);
            return false;
        }
    }
    fclose(f);
    if (s->count) qsort(s->events, s->count, sizeof *s->events, by_time);
    *out = s;
    return true;
}

void view_script_free(view_script *s)
{
    if (!s) return;
    free(s->events);
    free(s);
}

bool view_script_next(view_script *s, float t, view_event *out)
{
    /* Half a millisecond of slack: frame times are sums of float steps. */
    if (s->next >= s->count || s->events[s->next].time > t + 5e-4f) return false;
    *out = s->events[s->next++].e;
    return true;
}

bool view_script_done(const view_script *s) { return s->next >= s->count; }
