/* pelt — cameras, lights and views: the matrices a draw needs and the ray
 * through a pixel. Plain maths, no OpenGL. */
#ifndef PELT_CAMERA_H
#define PELT_CAMERA_H

#include "pelt/base.h"

#ifdef __cplusplus
extern "C" {
#endif

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
    unsigned width, height;   /* viewport in pixels; level of detail needs the
                                 height (0: the finest levels, docs/lod.md) */
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

#ifdef __cplusplus
}
#endif
#endif
