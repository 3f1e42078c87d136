/* Private to core/atlas: the pelt_atlas layout, the patch builder's state and the build steps (Lengyel et al. 2001 §2.1, §3). */
#ifndef PELT_ATLAS_INTERNAL_H
#define PELT_ATLAS_INTERNAL_H

#include "pelt/atlas.h"

#include "core/base/error.h"
#include "core/base/vec.h"

#include <stdio.h>

/* Who calls whom inside core/atlas (no circle):
 *   atlas.c   -> atlas_grow.c -> atlas_flatten.c -> atlas_check.c
 *   atlas.c   -> atlas_pack.c, atlas_stats.c, atlas_cache.c, atlas_check.c,
 *                direction_field.c, core/base/weld.c
 *   atlas_cache.c: a plain record to and from a file (atlas_cache.h).
 *   atlas_draw.c: only the public mesh API. */

#define PELT__ATLAS_GUTTER 1 /* free texels on each side of a patch: >= 2 between two */
#define PELT__ATLAS_NONE UINT32_MAX

struct pelt_atlas {
    pelt_allocator alloc;     /* desc.hooks's: the arrays below come from it */
    pelt_mesh *mesh;          /* output, NULL once taken */
    size_t vertex_count, triangle_count;
    uint32_t *source_vertex;  /* per output vertex */
    uint32_t *welded_vertex;  /* per output vertex */
    uint32_t *triangle_patch; /* per triangle */
    float *directions;        /* 3 per output vertex */
    float *weights;           /* per output vertex */
    pelt_atlas_stats stats;
};

/* Allocates an atlas with arrays for the counts (mesh left NULL) through
 * `alloc` (NULL: malloc), which it keeps. Free with pelt_atlas_destroy. */
pelt_atlas *pelt__atlas_alloc(const pelt_allocator *alloc, size_t vertex_count,
                              size_t triangle_count);

static inline pelt_status pelt__atlas_fail_oom(pelt_error *err, const char *what)
{
    return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "pelt_atlas_create: out of memory (%s)", what);
}

/* 8-byte keys ascending, for qsort. */
static inline int pelt__atlas_compare_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

/* ---- atlas_check.c ------------------------------------------------------ */

/* Counts texels of a res x res grid whose centre lies inside two or more of
 * the triangles (uvs 2 per vertex, in [0,1] grid units; outside parts are
 * clipped). claims is res*res bytes of scratch (zeroed here).
 * Top-left fill rule on exact fixed-point edge functions. When covered is
 * not NULL it receives the number of texels claimed at least once. */
size_t pelt__raster_overlaps(const float *uvs, const uint32_t *indices, size_t triangle_count,
                             unsigned res, uint8_t *claims, size_t *covered);

/* ---- the patch builder (atlas.c owns it) -------------------------------- */

typedef struct pelt__atlas_heap_item { float d; uint32_t f; } pelt__atlas_heap_item;

typedef struct pelt__atlas_builder {
    pelt_allocator alloc;      /* every array of the builder comes from it */
    pelt_mesh_data in;
    size_t vc, tc;
    unsigned cap;
    float max_stretch;
    uint32_t *canon, *adj, *face_patch;
    float *dir, *weight;       /* per input vertex */
    float *fnormal, *fcent;    /* 3 per face */
    /* growth */
    uint32_t *order, *face_stamp, *face_done, gen;
    float *dist;
    pelt__atlas_heap_item *heap;
    size_t heap_n;
    /* flattening, sized for cap faces */
    uint32_t *local_of, *local_stamp, *lverts, *tri_local, lgen;
    double *coef, *frame, *X, *r, *q, *s, *p, *t, *colscale;
    uint8_t *claims;
    unsigned claims_res;
    /* output */
    uint32_t *out_source, *out_patch, *out_index, *vert_stamp, *vert_out;
    float *out_local;
    size_t out_count;
    float *patch_box; /* 4 per patch: min x, min y, max x, max y (world units) */
    size_t patch_count;
} pelt__atlas_builder;

static inline pelt_vec3 pelt__atlas_vpos(const pelt__atlas_builder *b, uint32_t v)
{
    return v3_load(b->in.positions + 3 * v);
}

/* Unit field direction of face f in 3D scaled by its mean weight. */
static inline pelt_vec3 pelt__atlas_face_field(const pelt__atlas_builder *b, uint32_t f)
{
    pelt_vec3 s = v3(0, 0, 0);
    for (int k = 0; k < 3; k++) {
        uint32_t v = b->in.indices[3 * f + k];
        s = v3_mad(s, v3_load(b->dir + 3 * v), b->weight[v] / 3.0f);
    }
    return s;
}

/* ---- atlas_grow.c -------------------------------------------------------- */

/* Covers every face with patches (b->canon, dir and weight set): seeds in a
 * random order from `seed`, each grown, flattened, checked, shrunk until it
 * passes, oriented and accepted, splitting its vertices into b->out_*.
 * Fails only when out of memory. */
pelt_status pelt__atlas_grow_patches(pelt__atlas_builder *b, uint32_t seed, pelt_error *err);

/* ---- atlas_flatten.c ----------------------------------------------------- */

/* Flattens the first n faces of b->order into b->X (per local vertex);
 * returns the local vertex count. */
size_t pelt__atlas_flatten(pelt__atlas_builder *b, size_t n);
/* Checks the flattened patch: no flipped triangle, area ratio and
 * anisotropy within max_stretch, no overlap. Returns the number of faces to
 * keep on failure (a prefix), or n when it passes; *scale_out gets the
 * factor to world units. */
size_t pelt__atlas_check_patch(pelt__atlas_builder *b, size_t n, size_t nl, double *scale_out);
/* Rotates the patch so the field runs along +u and scales it by `scale`. */
void pelt__atlas_orient_patch(pelt__atlas_builder *b, size_t n, size_t nl, double scale);
/* Jacobian of the map from face i's local frame to the flattened coords. */
void pelt__atlas_jacobian(const pelt__atlas_builder *b, size_t i, double J[4]);

/* ---- atlas_pack.c -------------------------------------------------------- */

/* Packs the patches' boxes into a mask x mask atlas at one scale for all
 * (the largest that fits, by bisection) and writes the atlas uvs of every
 * output vertex (2 per vertex, b->out_count). *scale gets texels per world
 * unit and *used the texels inside packed rectangles. Fails when mask is
 * too small for the patches or when out of memory. */
pelt_status pelt__atlas_pack(const pelt__atlas_builder *b, unsigned mask, float *uvs,
                             double *scale, double *used, pelt_error *err);

/* ---- atlas_stats.c ------------------------------------------------------- */

/* Twice the total unsigned uv area and twice the total world area of the
 * triangles, and how many have positive / negative uv orientation (either
 * pointer may be NULL). */
void pelt__atlas_area_totals(const float *positions, const float *uvs, const uint32_t *indices,
                             size_t triangle_count, double *uv_total, double *world_total,
                             size_t *positive, size_t *negative);
/* Fills st->flipped and the stretch statistics of a uv set against the
 * world areas of the triangles. */
void pelt__atlas_uv_stats(const float *positions, const float *uvs, const uint32_t *indices,
                          size_t triangle_count, pelt_atlas_stats *st);

/* ---- atlas.c ------------------------------------------------------------- */

/* 64-bit key of everything the atlas depends on: the mesh, the stats that
 * steer the mode, and every desc field after defaults (the cache's file
 * name; see atlas_cache.h). */
uint64_t pelt__atlas_key(const pelt_mesh *in, const pelt_atlas_desc *d, unsigned mask_size,
                         float density);

#endif
