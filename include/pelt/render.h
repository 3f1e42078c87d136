/* pelt — the OpenGL renderer. Every call here needs the caller's OpenGL
 * 3.3+ core context current on the calling thread. */
#ifndef PELT_RENDER_H
#define PELT_RENDER_H

#include "pelt/base.h"
#include "pelt/fur.h"
#include "pelt/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pelt_renderer pelt_renderer;

/* An orbit camera around `target`. Angles in degrees. */
typedef struct pelt_camera {
    float yaw, pitch;   /* around +Y, then up from the XZ plane */
    float distance;
    float fov_y;        /* vertical field of view */
    float target[3];
} pelt_camera;

/* One directional light. */
typedef struct pelt_light {
    float direction[3]; /* towards the light, need not be unit */
    float color[3];
    float ambient;      /* ambient fraction of the hair colour */
} pelt_light;

typedef struct pelt_view {
    float view[16], proj[16]; /* column-major */
    float eye[3];
    float model[16];          /* mesh placement, column-major */
    pelt_light light;
    unsigned width, height;   /* viewport in pixels */
} pelt_view;

/* Fills view/proj/eye of `view` from an orbit camera and an aspect ratio;
 * model becomes the identity. */
void pelt_camera_to_view(const pelt_camera *camera, float aspect, pelt_view *view);

/* The ray through the centre of pixel (px, py) (column from the left, row
 * from the top) in MESH coordinates (view, projection and model undone),
 * for pelt_fur_add_droplet_ray under the mouse. `view` needs width and
 * height. False when the matrices are singular. */
bool pelt_view_pixel_ray(const pelt_view *view, float px, float py, float origin[3],
                         float direction[3]);

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
