/* pelt — fur dynamics: forces on the mass-spring strands (Silva et al.
 * §3.2.1) and stepping them in time. */
#ifndef PELT_DYNAMICS_H
#define PELT_DYNAMICS_H

#include "pelt/base.h"
#include "pelt/fur.h"

#ifdef __cplusplus
extern "C" {
#endif

/* External forces, in world units. Start from pelt_forces_default(). */
typedef struct pelt_forces {
    float gravity[3];      /* acceleration, default (0, -9.81, 0) */
    float wind[3];         /* wind direction * strength (acceleration), default 0 */
    float gust_strength;   /* 0..: fraction of |wind| added as seeded noise, default 0.5 */
    float gust_scale;      /* spatial size of a gust in world units, default 0.5 */
    float gust_frequency;  /* gust changes per second, default 1.5 */
    /* A local blow (a hair dryer): `blow` (an acceleration, world units)
       acts on the strands whose roots lie within blow_radius of
       blow_center (world), falling off as (1 - (d / r)^2)^2. Default 0:
       none. */
    float blow[3];
    float blow_center[3];
    float blow_radius;
} pelt_forces;

pelt_forces pelt_forces_default(void);

/* Where the mesh is now (column-major model matrix, mesh-local to world).
 * Roots move with the mesh at the next step; tips keep their world
 * position and lag behind (inertia). PELT_ERR_INVALID_ARGUMENT for a
 * non-finite or singular matrix (the previous one is kept). */
pelt_status pelt_fur_set_transform(pelt_fur *fur, const float model[16], pelt_error *err);

/* The mesh in a new pose (a skinned mesh's animation, pelt/animation.h:
 * pelt_mesh_pose writes these): positions and normals (3 floats per
 * vertex) and tangents (4, w the handedness) in the mesh's coordinates.
 * Like a new transform, it takes effect at the next step: the strands'
 * roots follow the surface and their tips lag by inertia; the renderer
 * draws skin, fins and shells on the posed mesh (one upload a frame,
 * shared by all layers). The first call allocates room for the pose;
 * later ones allocate nothing. PELT_ERR_INVALID_ARGUMENT for a NULL
 * array or a non-finite value. */
pelt_status pelt_fur_set_pose(pelt_fur *fur, const float *positions, const float *normals, const float *tangents,
                              pelt_error *err);

/* Advances the fur by dt seconds (any dt: the strands substep internally):
 * mass-spring strands under `forces` (NULL: pelt_forces_default()). The
 * renderer uploads the new tips at its next draw. No allocation, no I/O. */
void pelt_fur_step(pelt_fur *fur, float dt, const pelt_forces *forces);

/* Tips back to rest, clock back to 0. */
void pelt_fur_reset(pelt_fur *fur);

#ifdef __cplusplus
}
#endif
#endif
