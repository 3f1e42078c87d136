/* Private layout of pelt_atlas and the helpers shared by core/atlas*.c. */
#ifndef PELT_ATLAS_INTERNAL_H
#define PELT_ATLAS_INTERNAL_H

#include "pelt/atlas.h"

#include <stdio.h>

#define PELT__ATLAS_GUTTER 1 /* free texels on each side of a patch: >= 2 between two */

struct pelt_atlas {
    pelt_mesh *mesh;          /* output, NULL once taken */
    size_t vertex_count, triangle_count;
    uint32_t *source_vertex;  /* per output vertex */
    uint32_t *welded_vertex;  /* per output vertex */
    uint32_t *triangle_patch; /* per triangle */
    float *directions;        /* 3 per output vertex */
    float *weights;           /* per output vertex */
    pelt_atlas_stats stats;
};

/* Allocates an atlas with arrays for the counts (mesh left NULL). */
pelt_atlas *pelt__atlas_alloc(size_t vertex_count, size_t triangle_count);

/* Copies positions and the original normals from `in` through
 * source_vertex, finishes the output mesh (tangents along fur_uvs) and
 * fills the count, stretch and flip statistics. */
void pelt__atlas_finish_mesh(pelt_atlas *a, const pelt_mesh *in);

/* Counts texels of a res x res grid whose centre lies inside two or more of
 * the triangles (uvs 2 per vertex, in [0,1] grid units; outside parts are
 * clipped). claims is res*res bytes of scratch (zeroed here).
 * Top-left fill rule on exact fixed-point edge functions. When covered is
 * not NULL it receives the number of texels claimed at least once. */
size_t pelt__raster_overlaps(const float *uvs, const uint32_t *indices, size_t triangle_count,
                             unsigned res, uint8_t *claims, size_t *covered);

/* 64-bit key of everything the atlas depends on. */
uint64_t pelt__atlas_key(const pelt_mesh *in, const pelt_atlas_desc *d, unsigned mask_size,
                         float density);
/* Reads the cached atlas for key into *out (mesh rebuilt from `in`);
 * false when absent, stale or corrupt (never trusted blindly). */
bool pelt__atlas_cache_load(const char *dir, uint64_t key, const pelt_mesh *in,
                            pelt_atlas **out);
/* Writes atomically (temporary file + rename); false on any failure. */
bool pelt__atlas_cache_store(const char *dir, uint64_t key, const pelt_atlas *a);
/* Path of the cache file for key. */
void pelt__atlas_cache_path(const char *dir, uint64_t key, char *buf, size_t size);

#endif
