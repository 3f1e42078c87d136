/* Headless OpenGL through EGL: Mesa's surfaceless platform (llvmpipe on a
 * machine without a GPU), else the EGL device platform, else the default
 * display. Renders into an offscreen framebuffer object. */
#include "pelt/headless.h"

#include "core/base/error.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct pelt_headless {
    EGLDisplay display;
    EGLContext context;
    GLuint fbo, color_rb, depth_rb;
    GLuint resolve_fbo, resolve_rb; /* single-sample copy when MSAA is on */
    pelt_headless_desc desc;
    char name[256];
};

/* Tries one platform; returns an initialised display or EGL_NO_DISPLAY. */
static EGLDisplay open_display(EGLenum platform, void *native)
{
    EGLDisplay d = eglGetPlatformDisplayEXT(platform, native, NULL);
    if (d == EGL_NO_DISPLAY) return EGL_NO_DISPLAY;
    EGLint major, minor;
    if (!eglInitialize(d, &major, &minor)) return EGL_NO_DISPLAY;
    return d;
}

static EGLDisplay open_any_display(char *tried, size_t tried_size)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    EGLDisplay d = EGL_NO_DISPLAY;
    tried[0] = '\0';
    if (client && strstr(client, "EGL_MESA_platform_surfaceless")) {
        d = open_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY);
        if (d != EGL_NO_DISPLAY) return d;
        strncat(tried, "Mesa surfaceless platform failed; ", tried_size - strlen(tried) - 1);
    } else {
        strncat(tried, "no EGL_MESA_platform_surfaceless; ", tried_size - strlen(tried) - 1);
    }
    if (client && strstr(client, "EGL_EXT_platform_device")) {
        EGLDeviceEXT devices[8];
        EGLint count = 0;
        if (eglQueryDevicesEXT(8, devices, &count)) {
            for (EGLint i = 0; i < count; i++) {
                d = open_display(EGL_PLATFORM_DEVICE_EXT, devices[i]);
                if (d != EGL_NO_DISPLAY) return d;
            }
        }
        strncat(tried, "no usable EGL device; ", tried_size - strlen(tried) - 1);
    } else {
        strncat(tried, "no EGL_EXT_platform_device; ", tried_size - strlen(tried) - 1);
    }
    d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (d != EGL_NO_DISPLAY && eglInitialize(d, NULL, NULL)) return d;
    strncat(tried, "no default EGL display", tried_size - strlen(tried) - 1);
    return EGL_NO_DISPLAY;
}

static bool make_framebuffer(pelt_headless *c, pelt_error *err)
{
    GLenum color_format = c->desc.float_target ? GL_RGBA32F : c->desc.half_float_target ? GL_RGBA16F : GL_RGBA8;
    GLsizei w = (GLsizei)c->desc.width, h = (GLsizei)c->desc.height;
    GLsizei samples = (GLsizei)c->desc.samples;
    GLint max_samples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    if (samples > max_samples) {
        pelt__fail(err, PELT_ERR_GL, "%u multisample samples asked for; this context has at most %d",
                   c->desc.samples, (int)max_samples);
        return false;
    }

    glGenFramebuffers(1, &c->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, c->fbo);
    glGenRenderbuffers(1, &c->color_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, c->color_rb);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, color_format, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, c->color_rb);
    glGenRenderbuffers(1, &c->depth_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, c->depth_rb);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, c->depth_rb);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        pelt__fail(err, PELT_ERR_GL, "offscreen framebuffer %ux%u (%u samples) is incomplete",
                   c->desc.width, c->desc.height, c->desc.samples);
        return false;
    }
    if (samples > 0) {
        glGenFramebuffers(1, &c->resolve_fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, c->resolve_fbo);
        glGenRenderbuffers(1, &c->resolve_rb);
        glBindRenderbuffer(GL_RENDERBUFFER, c->resolve_rb);
        glRenderbufferStorage(GL_RENDERBUFFER, color_format, w, h);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, c->resolve_rb);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            pelt__fail(err, PELT_ERR_GL, "resolve framebuffer is incomplete");
            return false;
        }
    }
    pelt_headless_bind(c);
    return true;
}

pelt_status pelt_headless_create(const pelt_headless_desc *desc, pelt_headless **out,
                                 pelt_error *err)
{
    *out = NULL;
    if (!desc || desc->width == 0 || desc->height == 0 || desc->width > 16384 ||
        desc->height > 16384)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "headless framebuffer size must be 1..16384 in each dimension");
    if (desc->samples > 16)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "at most 16 MSAA samples");

    pelt_headless *c = calloc(1, sizeof *c);
    if (!c) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory");
    c->desc = *desc;

    char tried[256];
    c->display = open_any_display(tried, sizeof tried);
    if (c->display == EGL_NO_DISPLAY) {
        free(c);
        return pelt__fail(err, PELT_ERR_NO_CONTEXT,
                          "no EGL display (%s); install Mesa's EGL driver "
                          "(Debian: libegl-mesa0 libgl1-mesa-dri) or a GPU driver", tried);
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        free(c);
        return pelt__fail(err, PELT_ERR_NO_CONTEXT, "EGL cannot bind the desktop OpenGL API");
    }
    const EGLint config_attrs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = NULL;
    EGLint n = 0;
    bool no_config = !eglChooseConfig(c->display, config_attrs, &config, 1, &n) || n == 0;
    const char *exts = eglQueryString(c->display, EGL_EXTENSIONS);
    if (no_config && !(exts && strstr(exts, "EGL_KHR_no_config_context"))) {
        free(c);
        return pelt__fail(err, PELT_ERR_NO_CONTEXT, "EGL has no OpenGL-capable config");
    }
    const EGLint ctx_attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    c->context = eglCreateContext(c->display, no_config ? EGL_NO_CONFIG_KHR : config,
                                  EGL_NO_CONTEXT, ctx_attrs);
    if (c->context == EGL_NO_CONTEXT) {
        free(c);
        return pelt__fail(err, PELT_ERR_NO_CONTEXT,
                          "EGL could not create an OpenGL 3.3 core context (EGL error 0x%x)",
                          (unsigned)eglGetError());
    }
    if (!eglMakeCurrent(c->display, EGL_NO_SURFACE, EGL_NO_SURFACE, c->context)) {
        eglDestroyContext(c->display, c->context);
        free(c);
        return pelt__fail(err, PELT_ERR_NO_CONTEXT,
                          "EGL could not make a surfaceless context current "
                          "(EGL_KHR_surfaceless_context missing?)");
    }
    snprintf(c->name, sizeof c->name, "OpenGL %s, %s", (const char *)glGetString(GL_VERSION),
             (const char *)glGetString(GL_RENDERER));
    if (epoxy_gl_version() < 33) {
        pelt_headless_destroy(c);
        return pelt__fail(err, PELT_ERR_NO_CONTEXT, "OpenGL 3.3 core needed, got %s",
                          (const char *)glGetString(GL_VERSION));
    }
    if (!make_framebuffer(c, err)) {
        pelt_headless_destroy(c);
        return err ? err->status : PELT_ERR_GL;
    }
    *out = c;
    return PELT_OK;
}

void pelt_headless_destroy(pelt_headless *c)
{
    if (!c) return;
    if (c->context != EGL_NO_CONTEXT) {
        GLuint fbos[2] = {c->fbo, c->resolve_fbo};
        GLuint rbs[3] = {c->color_rb, c->depth_rb, c->resolve_rb};
        glDeleteFramebuffers(2, fbos);
        glDeleteRenderbuffers(3, rbs);
        eglMakeCurrent(c->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(c->display, c->context);
    }
    /* The display is not terminated: an EGL display is one per process and
     * platform, shared with anyone else in the process who uses it (an
     * application's own context, another pelt_headless), and terminating it
     * would unload the driver under them. eglInitialize on it again is a
     * no-op, so creating another context later reuses it. */
    eglReleaseThread();
    free(c);
}

void pelt_headless_bind(pelt_headless *c)
{
    glBindFramebuffer(GL_FRAMEBUFFER, c->fbo);
    glViewport(0, 0, (GLsizei)c->desc.width, (GLsizei)c->desc.height);
}

/* Binds the framebuffer to read from, resolving MSAA first. */
static void bind_for_read(pelt_headless *c)
{
    GLint w = (GLint)c->desc.width, h = (GLint)c->desc.height;
    if (c->resolve_fbo) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, c->fbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, c->resolve_fbo);
        glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, c->resolve_fbo);
    } else {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, c->fbo);
    }
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
}

void pelt_headless_read_rgba8(pelt_headless *c, uint8_t *rgba)
{
    size_t w = c->desc.width, h = c->desc.height, row = w * 4;
    bind_for_read(c);
    glReadPixels(0, 0, (GLsizei)w, (GLsizei)h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    pelt_headless_bind(c);
    /* GL rows run bottom-up; image files top-down: swap rows in place. */
    for (size_t y = 0; y < h / 2; y++) {
        uint8_t *a = rgba + y * row, *b = rgba + (h - 1 - y) * row;
        for (size_t i = 0; i < row; i++) {
            uint8_t t = a[i];
            a[i] = b[i];
            b[i] = t;
        }
    }
}

void pelt_headless_read_rgba32f(pelt_headless *c, float *rgba)
{
    bind_for_read(c);
    glReadPixels(0, 0, (GLsizei)c->desc.width, (GLsizei)c->desc.height, GL_RGBA, GL_FLOAT, rgba);
    pelt_headless_bind(c);
}

const char *pelt_headless_renderer_name(const pelt_headless *c) { return c->name; }
