/* Skinned files through assimp: the nodes, bones and weights gathered
 * while core/mesh/mesh_import.c merges a scene's meshes, then the merged
 * mesh's skeleton and animations (skeleton.h). Internal to core/mesh. */
#ifndef PELT_SKELETON_IMPORT_H
#define PELT_SKELETON_IMPORT_H

#include "pelt/mesh.h"

#include <assimp/scene.h>

#include <stdbool.h>
#include <stdint.h>

/* Node trees deeper than this are treated as corrupt (and would risk the stack). */
#define PELT__MAX_NODE_DEPTH 256

typedef struct pelt__skeleton_import {
    const char *path; /* the file, at the start of every message */
    pelt_error *err;
    const struct aiNode **nodes; /* parents first; NULL: the file has no skeleton */
    int32_t *node_parent;
    int32_t *node_bone;          /* a node's rigid-part bone, -1 until needed */
    uint32_t node_count;
    uint32_t *bone_node;
    float *bone_offset;          /* 16 per bone */
    uint32_t bone_count, real_bones, bone_room;
    unsigned char *bone_real;    /* 1: a bone of the file, 0: a rigid part's node */
    uint16_t *vbones;            /* PELT__BONES_PER_VERTEX per merged vertex, */
    float *vweights;             /* heaviest first */
} pelt__skeleton_import;

/* out = a b for assimp's row-major matrices (out may alias either). */
void pelt__ai_mat_mul(struct aiMatrix4x4 *out, const struct aiMatrix4x4 *a, const struct aiMatrix4x4 *b);

/* Whether the scene has bones or animations, so a skeleton is made. */
bool pelt__skeleton_import_wanted(const struct aiScene *scene);

/* Room for the skeleton of `vertex_count` merged vertices and the scene's
 * node tree. On failure free what was made with pelt__skeleton_import_free. */
pelt_status pelt__skeleton_import_begin(pelt__skeleton_import *s, const struct aiScene *scene, size_t vertex_count);

/* A skinned mesh is placed by its skeleton, as a viewer of the format
 * places it: adds each weighed vertex's bone matrices (the bone's node in
 * the file's pose, times its offset from the mesh's bind space) times the
 * weight into `skin` (12 floats, the rows, a vertex) and the weight into
 * `weight`. Fails when a bone names no node or a vertex out of range. */
pelt_status pelt__skeleton_import_skin(const pelt__skeleton_import *s, const struct aiMesh *mesh, float *skin,
                                       float *weight);

/* The skeleton's part of one mesh instance under `node`, its vertices
 * merged from `base` on. Nothing when the file has no skeleton. */
pelt_status pelt__skeleton_import_weigh(pelt__skeleton_import *s, const struct aiMesh *mesh,
                                        const struct aiNode *node, size_t base);

/* Gives mesh m, made by pelt__mesh_create_remap from `merged` vertices,
 * its skeleton (vertices renumbered by remap), the scene's animations and
 * its bind pose. */
pelt_status pelt__skeleton_import_finish(pelt__skeleton_import *s, const struct aiScene *scene, pelt_mesh *m,
                                         const uint32_t *remap, size_t merged);

void pelt__skeleton_import_free(pelt__skeleton_import *s);

#endif
