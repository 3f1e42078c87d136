/* pelt — the OpenGL renderer. Every call here needs the caller's OpenGL
 * 3.3+ core context current on the calling thread. */
#ifndef PELT_RENDER_H
#define PELT_RENDER_H

#include "pelt/base.h"
#include "pelt/camera.h"
#include "pelt/fur.h"
#include "pelt/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pelt_renderer pelt_renderer;

typedef struct pelt_renderer_desc {
    bool no_skin;   /* skip the opaque skin pass */
    bool no_shells; /* skip the shells (for measuring) */
    /* Draw only shells first_layer .. first_layer + layer_count - 1
     * (layer_count 0 = through the outermost): for inspecting one height
     * of the fur, and for level of detail. Still one instanced draw. */
    unsigned first_layer, layer_count;
} pelt_renderer_desc;

/* Compiles the shaders and uploads mesh and fur. The mesh and fur must
 * outlive the renderer. Free with pelt_renderer_destroy (context current). */
pelt_status pelt_renderer_create(const pelt_mesh *mesh, pelt_fur *fur,
                                 const pelt_renderer_desc *desc,
                                 pelt_renderer **out, pelt_error *err);
void pelt_renderer_destroy(pelt_renderer *renderer);

/* Uploads what changed in the fur since the last upload (strand tips,
 * colour texture, the changed rectangle of the wetness mask). Draw calls it
 * too; call it first to time uploads apart from drawing. */
void pelt_renderer_upload(pelt_renderer *renderer);

/* Draws skin then all shells (one instanced draw call) into the currently
 * bound framebuffer. Does not clear. No allocation, no file I/O. */
void pelt_renderer_draw(pelt_renderer *renderer, const pelt_view *view);

/* Draw calls issued by the last pelt_renderer_draw for the shells. */
unsigned pelt_renderer_shell_draw_calls(const pelt_renderer *renderer);

#ifdef __cplusplus
}
#endif
#endif
