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

/* Frames a set of points (a mesh and its fur) for an orbit camera, the
 * view `pelt render` takes of a mesh file when the scene gives no camera:
 * - target: the centre of the points' bounding sphere, each point grown by
 *   its reach (a sphere of that radius: the fur around a vertex);
 * - yaw: a three-quarter view about the up axis (+Y), 45 degrees off the
 *   long axis of the points' footprint on the XZ plane, on the side nearest
 *   camera->yaw; camera->yaw is kept when the footprint has no clear long
 *   axis (principal extents within 15% of each other);
 * - distance: the smallest at which every grown point lies inside both
 *   fields of view (fov_y, and the horizontal one that `aspect` = width /
 *   height gives) and beyond the near plane of pelt_camera_to_view, times
 *   1 + margin.
 * pitch and fov_y are kept. positions holds count xyz triples; reach holds
 * count radii >= 0, or is NULL (all 0). Returns false, leaving *camera
 * untouched, when count is 0, aspect is not positive or a value is not
 * finite. O(count); no allocation. */
bool pelt_camera_frame(pelt_camera *camera, const float *positions, const float *reach, size_t count,
                       float aspect, float margin);

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
