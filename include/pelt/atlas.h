/* pelt — surface atlas: direction field, patches and packing (Lengyel et al.
 * §2.1 lapped textures without overlap, §3 hair direction), validation of a
 * uv set, and a drawing of the result for inspection. GL-free. */
#ifndef PELT_ATLAS_H
#define PELT_ATLAS_H

#include "pelt/base.h"
#include "pelt/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pelt_atlas_mode {
    PELT_ATLAS_AUTO = 0,  /* the mesh's uvs when they are a valid atlas, else patches */
    PELT_ATLAS_MESH_UVS,  /* the mesh's uvs even when invalid (the reason is still reported) */
    PELT_ATLAS_PATCHES    /* always grow patches */
} pelt_atlas_mode;

/* Zero means the documented default for every field. */
typedef struct pelt_atlas_desc {
    unsigned mask_size;   /* atlas (wetness mask) side in texels; 0 = smallest power of
                             two >= max(256, sqrt(triangle count)), at most 4096 */
    float texel_density;  /* fur-texture tiles per world unit; 0 = 8 / bbox diagonal */
    float direction[3];   /* global hair direction, projected on each tangent plane;
                             all zero = (0, -1, 0) (combed down) */
    const float *vertex_directions; /* optional, 3 per input vertex: overrides
                             `direction`; a length below 1 lowers the slant weight,
                             zero stands the fur up */
    uint32_t seed;        /* patch seeds and colours */
    float max_stretch;    /* bound on per-triangle area ratio (either way) and on
                             singular-value ratio inside a patch; 0 = 2.0, min 1.1 */
    int mode;             /* pelt_atlas_mode */
    const char *cache_dir; /* NULL or "" = no cache; see pelt_atlas_default_cache_dir */
    unsigned max_patch_faces;     /* size cap of one patch; 0 = 1500 */
    unsigned smoothing_iterations; /* direction-field smoothing; 0 = 4 */
    pelt_hooks hooks;     /* allocator (the atlas, its arrays and the builder's
                             scratch; kept, pelt_atlas_destroy frees through it)
                             and logger (why the mesh's uvs were not used) */
} pelt_atlas_desc;

typedef struct pelt_atlas_stats {
    int mode_used;           /* PELT_ATLAS_MESH_UVS or PELT_ATLAS_PATCHES */
    size_t patch_count;
    size_t vertex_count;     /* of the output mesh (after splitting) */
    size_t triangle_count;
    unsigned mask_size;      /* atlas side in texels actually used */
    float texel_density;     /* fur tiles per world unit actually used */
    float fur_per_atlas;     /* fur-uv difference per atlas-uv difference (patch mode) */
    float stretch_min, stretch_mean, stretch_max; /* per-triangle uv area / world area,
                                                     normalised by the mesh total */
    size_t flipped;          /* triangles with uv orientation against the majority */
    float fill;              /* fraction of the atlas inside packed patch rectangles */
    double build_seconds;
    bool from_cache;
    char uv_warning[256];    /* why the mesh's own uvs were not used, or "" */
} pelt_atlas_stats;

typedef struct pelt_atlas pelt_atlas;

/* Builds the atlas of `in`: an output mesh whose vertices are split on patch
 * borders, uvs = atlas coordinates in [0,1] (address the mask), fur_uvs =
 * patch coordinates in fur tiles, comb = direction times weight (below),
 * normals copied from `in`, tangents along +u of fur_uvs; plus
 * per-output-vertex arrays below, in the mesh's vertex order. The mesh is
 * made by pelt_mesh_create, so its pelt_mesh_get_data makes an equal mesh
 * (an embedder's own atlas feeds the renderer the same way); its stats are
 * that validation's (nothing dropped). Looks in / writes to
 * desc->cache_dir. desc may be NULL (defaults). Free with pelt_atlas_destroy. */
pelt_status pelt_atlas_create(const pelt_mesh *in, const pelt_atlas_desc *desc,
                              pelt_atlas **out, pelt_error *err);
void pelt_atlas_destroy(pelt_atlas *atlas);

/* The output mesh (owned by the atlas), or NULL after pelt_atlas_take_mesh. */
const pelt_mesh *pelt_atlas_mesh(const pelt_atlas *atlas);
/* Hands the output mesh to the caller (free with pelt_mesh_destroy). */
pelt_mesh *pelt_atlas_take_mesh(pelt_atlas *atlas);
const pelt_atlas_stats *pelt_atlas_get_stats(const pelt_atlas *atlas);
size_t pelt_atlas_vertex_count(const pelt_atlas *atlas);
/* Per output vertex: index of the input vertex it was split from. */
const uint32_t *pelt_atlas_source_vertices(const pelt_atlas *atlas);
/* Per output vertex: the smallest input index at the same position, so one
 * strand per original position is keyed by this value. */
const uint32_t *pelt_atlas_welded_vertices(const pelt_atlas *atlas);
/* Per output triangle (same order as the input): its patch. */
const uint32_t *pelt_atlas_triangle_patches(const pelt_atlas *atlas);
/* Per output vertex: unit hair direction in the tangent plane (3 floats) and
 * its slant weight in [0,1] (0 where the field vanishes: fur stands up;
 * the renderer scales the tangential slant by it). */
const float *pelt_atlas_directions(const pelt_atlas *atlas);
const float *pelt_atlas_direction_weights(const pelt_atlas *atlas);

/* The one-call form: builds, hands over the mesh, copies the stats
 * (stats may be NULL) and frees everything else. */
pelt_status pelt_atlas_build(const pelt_mesh *in, const pelt_atlas_desc *desc,
                             pelt_mesh **out_mesh, pelt_atlas_stats *stats,
                             pelt_error *err);

/* Result of rasterizing a uv set. */
typedef struct pelt_atlas_check {
    size_t triangle_count;
    size_t flipped;        /* signed uv area against the majority orientation */
    size_t degenerate;     /* zero uv area */
    size_t outside;        /* triangles with a uv outside [0,1] */
    size_t overlap_texels; /* texels whose centre lies in two or more triangles */
    size_t covered_texels;
    int orientation;       /* majority: +1 counter-clockwise, -1 clockwise */
} pelt_atlas_check;

/* Rasterizes every triangle's uv footprint into resolution^2 texels (centre
 * sampling, top-left fill rule so a shared edge is counted once) and counts
 * texels claimed twice and flipped triangles. Allocates scratch only. */
pelt_status pelt_atlas_check_uvs(const pelt_mesh *mesh, unsigned resolution,
                                 pelt_atlas_check *result, pelt_error *err);

/* Draws the patches (a random colour each, borders darker) and the direction
 * field (short lines in atlas space) into rgba (width*height*4 bytes, row 0 =
 * v = 0). Needs the mesh still in the atlas. */
pelt_status pelt_atlas_draw(const pelt_atlas *atlas, uint8_t *rgba, unsigned width,
                            unsigned height, uint32_t seed, pelt_error *err);

/* Writes $XDG_CACHE_HOME/pelt or $HOME/.cache/pelt into buf; returns false
 * when neither variable is set or buf is too small. */
bool pelt_atlas_default_cache_dir(char *buf, size_t size);

#ifdef __cplusplus
}
#endif
#endif
