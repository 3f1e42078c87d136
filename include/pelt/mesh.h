/* pelt — triangle meshes: import, validation, procedural shapes. */
#ifndef PELT_MESH_H
#define PELT_MESH_H

#include "pelt/base.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pelt_mesh pelt_mesh;

/* Caller-owned arrays describing an indexed triangle mesh. normals and uvs
 * may be NULL (normals are then computed; uvs get a fallback mapping). */
typedef struct pelt_mesh_data {
    const float *positions; /* 3 * vertex_count */
    const float *normals;   /* 3 * vertex_count, or NULL */
    const float *uvs;       /* 2 * vertex_count, or NULL */
    size_t vertex_count;
    const uint32_t *indices; /* 3 * triangle_count */
    size_t triangle_count;
    /* 3 * vertex_count, or NULL: per-vertex hair directions for the atlas's
     * direction field (pelt_mesh_load fills them from a file's first vertex
     * colour set, read as a flow map: direction = 2 * rgb - 1). */
    const float *directions;
    /* 2 * vertex_count, or NULL: fur-texture coordinates in tiles (a
     * surface atlas's patch coordinates, pelt_atlas). NULL: the fur tiles
     * uvs scaled to world size (pelt_fur_look.tiling). */
    const float *fur_uvs;
    /* 3 * vertex_count, or NULL: the comb direction per vertex, a tangent
     * times a weight in [0,1] (0 stands the fur up), as pelt_atlas makes
     * it. NULL: the fur combs along the fur texture's u axis. */
    const float *comb;
    /* 4 * vertex_count, or NULL: the file's first vertex colour set as
     * RGBA in [0,1] (pelt_mesh_load fills it), e.g. a hair colour for
     * pelt_fur_groom_from_vertex_colors. */
    const float *colors;
    /* 3 floats, or NULL (+Y): the mesh's up axis as its file declares it
     * (FBX's UpAxis; pelt_mesh_load fills it), normalised by
     * pelt_mesh_create; pelt_mesh_up reads it back. */
    const float *up;
} pelt_mesh_data;

/* What validation did to the input. */
typedef struct pelt_mesh_stats {
    size_t vertex_count;       /* after validation */
    size_t triangle_count;     /* after validation */
    size_t dropped_degenerate; /* repeated index or zero area */
    bool computed_normals;     /* input had none (or unusable ones) */
    bool fallback_uvs;         /* input had no uvs: spherical fallback map */
} pelt_mesh_stats;

/* Validates and copies `data` into a new mesh: indices in range and finite
 * coordinates (else PELT_ERR_FORMAT), degenerate and zero-area triangles
 * dropped and counted, vertices numbered in the order the kept triangles
 * first use them (unused ones dropped), normals computed when absent and
 * normalised when not unit length (within 1e-6), tangent frames from
 * fur_uvs, else uvs. The caller frees *out with pelt_mesh_destroy. */
pelt_status pelt_mesh_create(const pelt_mesh_data *data, pelt_mesh **out,
                             pelt_error *err);

/* Imports a mesh file through assimp (OBJ, PLY, OFF, STL, glTF/GLB, FBX...)
 * and validates it as pelt_mesh_create does. All meshes in the file are
 * merged. Errors name the file. Free with pelt_mesh_destroy. */
pelt_status pelt_mesh_load(const char *path, pelt_mesh **out, pelt_error *err);

/* The same from memory. `name` starts every message and its extension
 * names the format ("bunny.ply"); a glTF's external buffers cannot be found
 * from memory (use GLB or data: URIs). */
pelt_status pelt_mesh_load_memory(const void *data, size_t size, const char *name, pelt_mesh **out,
                                  pelt_error *err);

/* Procedural shapes with uvs in [0,1]^2. */
pelt_status pelt_mesh_torus(float major_radius, float minor_radius,
                            unsigned major_segments, unsigned minor_segments,
                            pelt_mesh **out, pelt_error *err);
pelt_status pelt_mesh_sphere(float radius, unsigned slices, unsigned stacks,
                             pelt_mesh **out, pelt_error *err);
/* A square of side `size` in the XZ plane, normal +Y, centred on the origin. */
pelt_status pelt_mesh_square(float size, unsigned subdivisions,
                             pelt_mesh **out, pelt_error *err);

/* A coarser copy of `mesh` with about `target_triangles` triangles, made
 * with meshoptimizer's simplifier (borders and uv seams kept, so it may
 * stop above the target), validated as pelt_mesh_create does: the new mesh
 * keeps the vertices its triangles use, with their attributes. Free with
 * pelt_mesh_destroy. */
pelt_status pelt_mesh_simplify(const pelt_mesh *mesh, size_t target_triangles, pelt_mesh **out,
                               pelt_error *err);

void pelt_mesh_destroy(pelt_mesh *mesh);

pelt_mesh_stats pelt_mesh_get_stats(const pelt_mesh *mesh);
/* Per-vertex hair directions from the file (3 floats per vertex), or NULL
 * when it had none. Owned by the mesh. */
const float *pelt_mesh_directions(const pelt_mesh *mesh);

/* The file's vertex colours, RGBA in [0,1] (4 floats per vertex), or NULL
 * when it had none. Owned by the mesh. */
const float *pelt_mesh_colors(const pelt_mesh *mesh);

/* The validated mesh as arrays (owned by the mesh, valid until it is
 * destroyed): normals are always set (computed when the input had none),
 * uvs and up always (fallback map, +Y), directions, fur_uvs,
 * comb and colors when given.
 * pelt_mesh_create(&data) of the result makes an equal mesh; a skinned
 * mesh's skeleton and animations are not surface arrays and stay with it. */
pelt_mesh_data pelt_mesh_get_data(const pelt_mesh *mesh);

/* Unit tangent along +u of the fur-texture coordinates (fur_uvs, else uvs)
 * and its handedness: 4 floats per vertex, owned by the mesh. */
const float *pelt_mesh_tangents(const pelt_mesh *mesh);

/* Axis-aligned bounds of the positions. */
void pelt_mesh_bounds(const pelt_mesh *mesh, float min[3], float max[3]);
/* The mesh's up axis as its file declares it (FBX's UpAxis metadata), a
 * unit axis; +Y when the file says nothing (glTF, X, OBJ...). The scene
 * key mesh.up turns it to +Y or overrides it. */
void pelt_mesh_up(const pelt_mesh *mesh, float up[3]);

/* Length of the bounds' diagonal: the mesh's size, which the fur's default
 * length and tiling and the atlas's default density scale with. */
float pelt_mesh_diagonal(const pelt_mesh *mesh);

#ifdef __cplusplus
}
#endif
#endif
