/* A mesh's skeleton and animations (pelt/animation.h), built by
 * mesh_import.c from what assimp reads; GL-free and assimp-free, so the
 * pose is testable on a skeleton made by hand. Matrices are column-major
 * 4x4 floats, as pelt_view's. */
#ifndef PELT_SKELETON_H
#define PELT_SKELETON_H

#include "pelt/animation.h"

#include <stdint.h>

#define PELT__MAX_SKELETON_NODES 4096u
#define PELT__BONES_PER_VERTEX 4

typedef struct pelt__vec_key {
    float time; /* seconds */
    float v[3];
} pelt__vec_key;

typedef struct pelt__quat_key {
    float time; /* seconds */
    float q[4]; /* x, y, z, w; unit */
} pelt__quat_key;

/* One animated node: its local transform is T(pos) R(rot) S(scale) at any
 * time, each track held at its first and last key outside them; an empty
 * track keeps the node's rest value of that part. */
typedef struct pelt__channel {
    uint32_t node;
    pelt__vec_key *pos;
    pelt__quat_key *rot;
    pelt__vec_key *scale;
    uint32_t pos_count, rot_count, scale_count;
} pelt__channel;

typedef struct pelt__animation {
    char name[PELT_ANIMATION_NAME_MAX];
    float duration; /* seconds, > 0 */
    pelt__channel *channels;
    uint32_t channel_count;
} pelt__animation;

/* Nodes come parents first (parent[i] < i, -1 for a root). A bone is a
 * node and the offset from the mesh's bind space to that node's space;
 * a vertex placed by its node alone (a rigid part) has that node as a
 * bone with the identity offset. Every vertex has 1..4 bones, weights
 * summing to 1. */
typedef struct pelt__skeleton {
    uint32_t node_count;
    int32_t *parent;
    float *rest;         /* 16 per node: its local transform in the file */
    float *rest_trs;     /* 10 per node: the same as t (3), r (4: x y z w), s (3) */
    uint32_t bone_count;
    uint32_t *bone_node;
    float *bone_offset;  /* 16 per bone */
    uint32_t real_bones; /* bones from the file; the rest are rigid parts' nodes */
    pelt__animation *animations;
    uint32_t animation_count;
    size_t vertex_count;
    uint16_t *bones;     /* PELT__BONES_PER_VERTEX per vertex */
    float *weights;      /* PELT__BONES_PER_VERTEX per vertex, summing to 1 */
    float *bind;         /* 10 per vertex: bind-space position, normal, tangent */
    size_t skinned;      /* vertices weighed by a real bone */
    /* Scratch of pelt_mesh_pose, made with the skeleton so that posing
       allocates nothing (one pose at a time per mesh). */
    float *scratch_globals; /* 16 per node */
    float *scratch_skin;    /* 16 per bone */
} pelt__skeleton;

void pelt__skeleton_free(pelt__skeleton *s);

/* The nodes' global transforms (16 per node into `globals`) of animation
 * `a` (NULL: the rest pose) at `seconds`, already wrapped into
 * [0, duration]. */
void pelt__skeleton_globals(const pelt__skeleton *s, const pelt__animation *a, float seconds, float *globals);

/* One track sampled at t: linear between keys for vectors, normalised
 * linear-then-slerp for rotations (the shorter way round). */
void pelt__sample_vec(const pelt__vec_key *k, uint32_t n, float t, const float rest[3], float out[3]);
void pelt__sample_quat(const pelt__quat_key *k, uint32_t n, float t, const float rest[4], float out[4]);

/* T R S as a column-major matrix. */
void pelt__trs_matrix(const float t[3], const float q[4], const float s[3], float out[16]);
/* A rigid-plus-scale matrix split into t, r (unit quaternion), s; false
 * for a matrix with a zero scale. */
bool pelt__matrix_trs(const float m[16], float t[3], float q[4], float s[3]);

/* Blends each vertex's bone matrices (`skin`: 16 per bone, bone transform
 * times offset) and moves its bind-space attributes: positions, normals,
 * tangents (NULL: not written). */
void pelt__skeleton_skin(const pelt__skeleton *s, const float *skin, float *positions, float *normals,
                         float *tangents);

/* Sets each vertex's bind-space attributes from its rest ones (the mesh as
 * imported, placed by the rest pose): the inverse of its blended rest
 * matrix applied. False when a vertex's blended matrix is singular. */
bool pelt__skeleton_bind(pelt__skeleton *s, const float *positions, const float *normals, const float *tangents);

/* The mesh's skeleton, or NULL when it has none (a static mesh). */
const pelt__skeleton *pelt__mesh_skeleton(const pelt_mesh *mesh);

/* Gives `dst`, made from `src` by splitting its vertices (dst vertex o
 * comes from src vertex source_vertex[o], as the atlas does), a copy of
 * src's skeleton and animations; nothing when src has none. On failure
 * dst holds what was made (pelt_mesh_destroy frees it). */
pelt_status pelt__mesh_copy_skeleton(pelt_mesh *dst, const pelt_mesh *src, const uint32_t *source_vertex,
                                     pelt_error *err);

#endif
