/* Private layout of pelt_mesh, shared by core/ and gl/ (not installed). */
#ifndef PELT_MESH_INTERNAL_H
#define PELT_MESH_INTERNAL_H

#include "pelt/mesh.h"

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
    uint32_t *indices; /* 3 per triangle */
    float bounds_min[3], bounds_max[3];
    pelt_mesh_stats stats;
};

/* Allocates an empty mesh with room for the given counts (arrays zeroed).
 * Returns NULL when out of memory or when the counts overflow. */
pelt_mesh *pelt__mesh_alloc(size_t vertex_count, size_t triangle_count);

/* Fills normals (when compute_normals), tangents and bounds of a mesh whose
 * positions, uvs and indices are set. */
void pelt__mesh_finish(pelt_mesh *mesh, bool compute_normals);

#endif
