/* Private layout of pelt_mesh: only core/mesh/ includes this (the layering
 * check enforces it); everyone else reads a mesh through pelt/mesh.h. */
#ifndef PELT_MESH_INTERNAL_H
#define PELT_MESH_INTERNAL_H

#include "pelt/mesh.h"

#include "core/base/vec.h"

struct pelt_mesh {
    size_t vertex_count;
    size_t triangle_count;
    float *positions; /* 3 per vertex */
    float *normals;   /* 3 per vertex, unit length */
    float *uvs;       /* 2 per vertex: surface (atlas) coordinates in [0,1],
                         they address the wetness mask and colour texture */
    float *fur_uvs;   /* 2 per vertex or NULL: fur-texture coordinates in
                         tiles (patch-local, from the atlas); NULL means
                         uvs * tiling */
    float *tangents;  /* 4 per vertex: unit tangent along +u, w = handedness */
    float *directions; /* 3 per vertex or NULL: hair directions from the file */
    float *comb;      /* 3 per vertex or NULL (then the tangent): the comb
                         direction, the direction field times its weight;
                         0 where the field vanishes, so the fur stands up */
    float *colors;    /* 4 per vertex or NULL: RGBA vertex colours from the file */
    uint32_t *indices; /* 3 per triangle */
    float bounds_min[3], bounds_max[3];
    pelt_mesh_stats stats;
    struct pelt__skeleton *skeleton; /* NULL, or the bones and animations (skeleton.h) */
    float up[3];      /* the file's up axis (FBX metadata), else +Y */
};

/* pelt_mesh_create that also hands over where each input vertex went:
 * remap[i] - 1 is its index in the mesh, 0 when it was dropped (free it). */
pelt_status pelt__mesh_create_remap(const pelt_mesh_data *data, pelt_mesh **out, uint32_t **remap_out,
                                    pelt_error *err);

/* Allocates an empty mesh with room for the given counts (arrays zeroed).
 * Returns NULL when out of memory or when the counts overflow. */
pelt_mesh *pelt__mesh_alloc(size_t vertex_count, size_t triangle_count);

/* Fills normals (when compute_normals), tangents and bounds of a mesh whose
 * positions, uvs and indices are set. */
void pelt__mesh_finish(pelt_mesh *mesh, bool compute_normals);

/* mesh_check.c: pelt's checks of a mesh file before assimp reads it. buf
 * holds the first len bytes of the `size` bytes named `name` (all of them
 * when pelt__mesh_check_reads_whole says so for the first bytes). */
pelt_status pelt__mesh_check(const char *name, const char *buf, size_t len, long long size,
                             pelt_error *err);
bool pelt__mesh_check_reads_whole(const char *name, const char *head, size_t len);

#endif
