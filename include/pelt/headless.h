/* pelt — a headless OpenGL 3.3+ core context through EGL (Mesa surfaceless,
 * or the EGL device platform on a GPU) with an offscreen framebuffer. */
#ifndef PELT_HEADLESS_H
#define PELT_HEADLESS_H

#include "pelt/base.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pelt_headless pelt_headless;

typedef struct pelt_headless_desc {
    unsigned width, height; /* framebuffer size, required */
    unsigned samples;       /* MSAA samples, 0 = none */
    bool float_target;      /* RGBA32F colour target (for shader tests) */
    bool half_float_target; /* RGBA16F colour target: many blended layers
                               without an 8-bit target's rounding at each */
} pelt_headless_desc;

/* Creates the context, makes it current and binds the framebuffer. When no
 * context can be made the error names what is missing. Free with
 * pelt_headless_destroy. */
pelt_status pelt_headless_create(const pelt_headless_desc *desc,
                                 pelt_headless **out, pelt_error *err);
void pelt_headless_destroy(pelt_headless *ctx);

/* Binds the offscreen framebuffer and sets the viewport. */
void pelt_headless_bind(pelt_headless *ctx);

/* Reads the framebuffer into rgba (width * height * 4 bytes), top row
 * first, as image files store it. */
void pelt_headless_read_rgba8(pelt_headless *ctx, uint8_t *rgba);
/* Reads a float target (width * height * 4 floats), bottom row first. */
void pelt_headless_read_rgba32f(pelt_headless *ctx, float *rgba);

/* "OpenGL 4.5 (Core Profile) Mesa ... llvmpipe": renderer and version. */
const char *pelt_headless_renderer_name(const pelt_headless *ctx);

#ifdef __cplusplus
}
#endif
#endif
