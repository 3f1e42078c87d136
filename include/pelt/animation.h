/* pelt — skinned meshes and their animations (docs/animation.md): the
 * skeleton, skin weights and animations a mesh file brings (glTF, FBX, X,
 * Collada... through assimp), sampled at any time into a pose. No OpenGL.
 *
 * A skinned mesh's pelt_mesh positions are its pose in the file's node
 * tree (what a viewer shows before it plays anything). A pose at time t
 * is linear-blend skinning of the bind-space vertices by the bones'
 * transforms at t: each vertex has up to 4 bones, weights renormalised to
 * sum to 1; keys are interpolated as assimp delivers them (positions and
 * scales linearly, rotations by slerp). Vertices without bones keep their
 * place. */
#ifndef PELT_ANIMATION_H
#define PELT_ANIMATION_H

#include "pelt/base.h"
#include "pelt/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PELT_ANIMATION_NAME_MAX 64u /* bytes of a stored name, with the NUL */
#define PELT_MAX_BONES 1024u        /* a file with more bones is refused */

typedef struct pelt_animation_info {
    char name[PELT_ANIMATION_NAME_MAX]; /* as in the file ("" when unnamed) */
    float duration;                     /* seconds, > 0 */
    unsigned channels;                  /* animated nodes */
} pelt_animation_info;

typedef struct pelt_skin_info {
    size_t bones;            /* bones that weigh vertices */
    size_t nodes;            /* nodes of the skeleton's tree */
    size_t skinned_vertices; /* vertices with at least one bone */
    size_t animations;
} pelt_skin_info;

/* What the mesh brings; all zero for a mesh without bones or animations. */
pelt_skin_info pelt_mesh_skin_info(const pelt_mesh *mesh);

/* Animation i (0 .. animations - 1); false when out of range. */
bool pelt_mesh_animation(const pelt_mesh *mesh, size_t i, pelt_animation_info *out);

/* Looks an animation up by name, or by index when `name_or_index` is a
 * decimal number. PELT_ERR_INVALID_ARGUMENT with a message that lists what
 * the mesh has when there is no such animation. */
pelt_status pelt_mesh_find_animation(const pelt_mesh *mesh, const char *name_or_index, size_t *index,
                                     pelt_error *err);

/* The pose of animation `animation` at `seconds` (looping: taken modulo the
 * duration; negative times count back from the end): positions and
 * normals (3 floats per vertex each, vertex_count of them) and tangents
 * (4 per vertex, w the handedness, or NULL) in the mesh's coordinates.
 * No allocation. PELT_ERR_INVALID_ARGUMENT for a bad index, a mesh
 * without a skeleton or a non-finite time. */
pelt_status pelt_mesh_pose(const pelt_mesh *mesh, size_t animation, float seconds, float *positions,
                           float *normals, float *tangents, pelt_error *err);

#ifdef __cplusplus
}
#endif
#endif
