/* pelt view: the GLFW window and its OpenGL 3.3 core context. Input
 * callbacks queue view_events; the frame loop takes them in order.
 *
 * GLFW is loaded when a window is opened (dlopen of libglfw.so.3), not
 * linked: linked, it brings libX11 and libxcb into every pelt command at
 * start, which headless commands have no use for, and with them loaded
 * LeakSanitizer's tracer crashed at the exit of `pelt render` on larger
 * meshes (the docs_images test).
 *
 * In the browser (Emscripten, docs/web.md) the same file drives the canvas
 * through Emscripten's GLFW, linked, with a WebGL2 context; the frame loop
 * is the browser's (view_window_run). */
#include "apps/view.h"

#include "gl/gl_api.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__EMSCRIPTEN__)
#include <emscripten.h>
#include <emscripten/html5.h>

static bool load_glfw(char *err, size_t err_size)
{
    (void)err, (void)err_size;
    return true; /* linked */
}
#else
#include <dlfcn.h>

/* Every GLFW function used here, called through a pointer of its own type. */
#define GLFW_FUNCTIONS(X)                                                                      \
    X(glfwSetErrorCallback) X(glfwInit) X(glfwTerminate) X(glfwWindowHint)                      \
    X(glfwCreateWindow) X(glfwDestroyWindow) X(glfwSetWindowUserPointer)                        \
    X(glfwGetWindowUserPointer) X(glfwMakeContextCurrent) X(glfwSwapInterval)                   \
    X(glfwSetCursorPosCallback) X(glfwSetMouseButtonCallback) X(glfwSetScrollCallback)          \
    X(glfwSetKeyCallback) X(glfwSetDropCallback) X(glfwGetCursorPos) X(glfwPollEvents)          \
    X(glfwWindowShouldClose) X(glfwGetFramebufferSize) X(glfwSwapBuffers)                       \
    X(glfwSetWindowTitle) X(glfwGetTime)
#define DECLARE(f) static __typeof__(f) *pf_##f;
GLFW_FUNCTIONS(DECLARE)
#undef DECLARE

/* Loads libglfw.so.3 once; false with a message in err. */
static bool load_glfw(char *err, size_t err_size)
{
    static void *lib;
    if (lib) return true;
    void *h = dlopen("libglfw.so.3", RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        snprintf(err, err_size, "cannot load GLFW (libglfw.so.3, Debian package libglfw3): %s",
                 dlerror());
        return false;
    }
#define LOAD(f)                                                                                \
    *(void **)&pf_##f = dlsym(h, #f);                                                          \
    if (!pf_##f) {                                                                             \
        snprintf(err, err_size, "libglfw.so.3 has no %s (GLFW 3.3 or later needed)", #f);     \
        dlclose(h);                                                                            \
        return false;                                                                          \
    }
    GLFW_FUNCTIONS(LOAD)
#undef LOAD
    lib = h; /* never closed: the GL driver it loads stays for the process */
    return true;
}

#define glfwSetErrorCallback pf_glfwSetErrorCallback
#define glfwInit pf_glfwInit
#define glfwTerminate pf_glfwTerminate
#define glfwWindowHint pf_glfwWindowHint
#define glfwCreateWindow pf_glfwCreateWindow
#define glfwDestroyWindow pf_glfwDestroyWindow
#define glfwSetWindowUserPointer pf_glfwSetWindowUserPointer
#define glfwGetWindowUserPointer pf_glfwGetWindowUserPointer
#define glfwMakeContextCurrent pf_glfwMakeContextCurrent
#define glfwSwapInterval pf_glfwSwapInterval
#define glfwSetCursorPosCallback pf_glfwSetCursorPosCallback
#define glfwSetMouseButtonCallback pf_glfwSetMouseButtonCallback
#define glfwSetScrollCallback pf_glfwSetScrollCallback
#define glfwSetKeyCallback pf_glfwSetKeyCallback
#define glfwSetDropCallback pf_glfwSetDropCallback
#define glfwGetCursorPos pf_glfwGetCursorPos
#define glfwPollEvents pf_glfwPollEvents
#define glfwWindowShouldClose pf_glfwWindowShouldClose
#define glfwGetFramebufferSize pf_glfwGetFramebufferSize
#define glfwSwapBuffers pf_glfwSwapBuffers
#define glfwSetWindowTitle pf_glfwSetWindowTitle
#define glfwGetTime pf_glfwGetTime
#endif

#define QUEUE_MAX 1024

struct view_window {
    GLFWwindow *glfw;
    view_event queue[QUEUE_MAX];
    size_t head, count;
};

static char glfw_message[512];
#if defined(__EMSCRIPTEN__)
static view_window *page_window; /* the page's one canvas, for pelt_web_key */
#endif

static void on_error(int code, const char *description)
{
    snprintf(glfw_message, sizeof glfw_message, "%s (GLFW error 0x%x)", description, code);
}

static void push(view_window *w, const view_event *e)
{
    if (w->count == QUEUE_MAX) return; /* a flood of input: drop the newest */
    w->queue[(w->head + w->count) % QUEUE_MAX] = *e;
    w->count++;
}

static view_window *self(GLFWwindow *g) { return glfwGetWindowUserPointer(g); }

static void on_cursor(GLFWwindow *g, double x, double y)
{
    view_event e = {.type = VIEW_EV_MOVE, .x = (float)x, .y = (float)y};
    push(self(g), &e);
}

static void on_button(GLFWwindow *g, int button, int action, int mods)
{
    int b = button == GLFW_MOUSE_BUTTON_LEFT ? 0 : button == GLFW_MOUSE_BUTTON_RIGHT ? 1
          : button == GLFW_MOUSE_BUTTON_MIDDLE ? 2 : -1;
    if (b < 0) return;
    double x, y;
    glfwGetCursorPos(g, &x, &y);
    view_event e = {.type = VIEW_EV_BUTTON, .x = (float)x, .y = (float)y, .button = b,
                    .mods = mods, .press = action == GLFW_PRESS};
    push(self(g), &e);
}

static void on_scroll(GLFWwindow *g, double dx, double dy)
{
    (void)dx;
    view_event e = {.type = VIEW_EV_SCROLL, .y = (float)dy};
    push(self(g), &e);
}

static void on_key(GLFWwindow *g, int key, int scancode, int action, int mods)
{
    (void)scancode;
    if (action == GLFW_REPEAT && key != GLFW_KEY_LEFT_BRACKET && key != GLFW_KEY_RIGHT_BRACKET &&
        key != GLFW_KEY_MINUS && key != GLFW_KEY_EQUAL)
        return;
    view_event e = {.type = VIEW_EV_KEY, .key = key, .mods = mods, .press = action != GLFW_RELEASE};
    push(self(g), &e);
}

static void on_drop(GLFWwindow *g, int count, const char **paths)
{
    for (int i = 0; i < count; i++) {
        view_event e = {.type = VIEW_EV_DROP};
        snprintf(e.path, sizeof e.path, "%s", paths[i]);
        push(self(g), &e);
    }
}

bool view_window_open(const char *title, unsigned w, unsigned h, unsigned samples, view_window **out,
                      char *err, size_t err_size)
{
    *out = NULL;
#if defined(__EMSCRIPTEN__)
    const char *display = "the page's canvas";
#else
    const char *display = getenv("DISPLAY"), *wayland = getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland)) {
        snprintf(err, err_size,
                 "no display: DISPLAY is not set (run it in a desktop session, or under Xvfb: "
                 "xvfb-run -a pelt view ...; pelt render draws without one)");
        return false;
    }
#endif
    if (!load_glfw(err, err_size)) return false;
    glfwSetErrorCallback(on_error);
    if (!glfwInit()) {
        snprintf(err, err_size, "cannot open the display '%s': %s", display ? display : "",
                 glfw_message[0] ? glfw_message : "glfwInit failed");
        return false;
    }
    view_window *win = calloc(1, sizeof *win);
    if (!win) {
        glfwTerminate();
        snprintf(err, err_size, "out of memory");
        return false;
    }
#if defined(__EMSCRIPTEN__)
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API); /* WebGL2 */
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
#else
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
#endif
    glfwWindowHint(GLFW_DEPTH_BITS, 24);
    glfwWindowHint(GLFW_SAMPLES, (int)samples); /* output.msaa, as render draws it */
    glfwWindowHint(GLFW_SRGB_CAPABLE, GLFW_FALSE);
    win->glfw = glfwCreateWindow((int)w, (int)h, title, NULL, NULL);
    if (!win->glfw) {
        snprintf(err, err_size, "cannot create a %ux%u window with an OpenGL 3.3 core context: %s",
                 w, h, glfw_message[0] ? glfw_message : "unknown reason");
        free(win);
        glfwTerminate();
        return false;
    }
    glfwSetWindowUserPointer(win->glfw, win);
    glfwMakeContextCurrent(win->glfw);
    glfwSwapInterval(0); /* llvmpipe: no vsync to wait for; keep input latency one frame */
    glfwSetCursorPosCallback(win->glfw, on_cursor);
    glfwSetMouseButtonCallback(win->glfw, on_button);
    glfwSetScrollCallback(win->glfw, on_scroll);
    glfwSetKeyCallback(win->glfw, on_key);
    glfwSetDropCallback(win->glfw, on_drop);
#if !defined(__EMSCRIPTEN__)
    if (epoxy_gl_version() < 33) {
        snprintf(err, err_size, "OpenGL 3.3 core needed, got %s",
                 (const char *)glGetString(GL_VERSION));
        view_window_close(win);
        return false;
    }
#endif
#if defined(__EMSCRIPTEN__)
    page_window = win;
#endif
    *out = win;
    return true;
}

void view_window_close(view_window *w)
{
    if (!w) return;
#if defined(__EMSCRIPTEN__)
    page_window = NULL;
#endif
    glfwDestroyWindow(w->glfw);
    free(w);
    /* No glfwTerminate: it unloads the GL driver (libGL, Mesa's GLX), and
     * what the driver still holds then shows as leaks of an unknown
     * module that no LeakSanitizer suppression can name. The window is
     * gone; the process ends right after. */
}

void view_window_poll(view_window *w)
{
    (void)w;
    glfwPollEvents();
}

bool view_window_next_event(view_window *w, view_event *out)
{
    if (!w->count) return false;
    *out = w->queue[w->head];
    w->head = (w->head + 1) % QUEUE_MAX;
    w->count--;
    return true;
}

bool view_window_should_close(const view_window *w) { return glfwWindowShouldClose(w->glfw); }

void view_window_framebuffer_size(const view_window *w, unsigned *width, unsigned *height)
{
    int fw, fh;
#if defined(__EMSCRIPTEN__)
    (void)w; /* the page sizes the canvas (web/page.js): follow it */
    emscripten_get_canvas_element_size("#canvas", &fw, &fh);
#else
    glfwGetFramebufferSize(w->glfw, &fw, &fh);
#endif
    *width = fw > 0 ? (unsigned)fw : 0;
    *height = fh > 0 ? (unsigned)fh : 0;
}

void view_window_swap(view_window *w) { glfwSwapBuffers(w->glfw); }

void view_window_set_title(view_window *w, const char *title) { glfwSetWindowTitle(w->glfw, title); }

void view_window_read_rgba8(view_window *w, uint8_t *rgba, unsigned width, unsigned height)
{
    (void)w;
    size_t row = (size_t)width * 4;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, (GLsizei)width, (GLsizei)height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    for (size_t y = 0; y < height / 2; y++) { /* GL rows run bottom-up */
        uint8_t *a = rgba + y * row, *b = rgba + (height - 1 - y) * row;
        for (size_t i = 0; i < row; i++) {
            uint8_t t = a[i];
            a[i] = b[i];
            b[i] = t;
        }
    }
}

#if defined(__EMSCRIPTEN__)
double view_window_time(void) { return emscripten_get_now() / 1000.0; }

/* The page's panel (web/page.js) presses the viewer's keys through this:
 * a press and a release of GLFW key `key`, queued like the keyboard's. */
EMSCRIPTEN_KEEPALIVE void pelt_web_key(int key, int mods)
{
    if (!page_window) return;
    view_event e = {.type = VIEW_EV_KEY, .key = key, .mods = mods, .press = true};
    push(page_window, &e);
    e.press = false;
    push(page_window, &e);
}

/* The wheel and the pinch, in the desktop's clicks (positive: away from the
 * user): the page measures them (Emscripten 3.1.6's GLFW hands on the
 * browser's raw pixels with the sign flipped). */
EMSCRIPTEN_KEEPALIVE void pelt_web_scroll(float clicks)
{
    if (!page_window) return;
    view_event e = {.type = VIEW_EV_SCROLL, .y = clicks};
    push(page_window, &e);
}

typedef struct run_state {
    bool (*frame)(void *);
    void (*finish)(void *);
    void *user;
} run_state;

static void run_one(void *arg)
{
    run_state *r = arg;
    if (r->frame(r->user)) return;
    emscripten_cancel_main_loop();
    r->finish(r->user);
}

void view_window_run(view_window *w, bool (*frame)(void *), void (*finish)(void *), void *user)
{
    (void)w;
    static run_state r;
    r = (run_state){frame, finish, user};
    /* The browser calls run_one once an animation frame; this never returns. */
    emscripten_set_main_loop_arg(run_one, &r, 0, 1);
}
#else
double view_window_time(void) { return pf_glfwGetTime ? glfwGetTime() : 0.0; }

void view_window_run(view_window *w, bool (*frame)(void *), void (*finish)(void *), void *user)
{
    (void)w;
    while (frame(user)) {
    }
    finish(user);
}
#endif
