/* On-disk cache of atlas results (Lengyel §2.1 atlases are slow to grow): a plain record <-> one file. */
#ifndef PELT_ATLAS_CACHE_H
#define PELT_ATLAS_CACHE_H

/* A lower module: it (de)serialises a pelt__atlas_record and knows nothing
 * of how an atlas is built; atlas.c calls it, never the other way. */

#include "pelt/atlas.h"

#define PELT__ATLAS_CACHE_VERSION 1u

/* FNV-1a, 64 bit: the cache's checksum, and what atlas.c hashes its key
 * with. */
typedef struct pelt__atlas_hash { uint64_t h; } pelt__atlas_hash;

static inline pelt__atlas_hash pelt__atlas_hash_begin(void)
{
    pelt__atlas_hash s = {0xcbf29ce484222325ULL};
    return s;
}

static inline void pelt__atlas_hash_bytes(pelt__atlas_hash *s, const void *data, size_t n)
{
    const unsigned char *p = data;
    uint64_t h = s->h;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 0x100000001b3ULL;
    }
    s->h = h;
}

/* What the cache keeps of one atlas: plain arrays, no handles. */
typedef struct pelt__atlas_record {
    size_t vertex_count, triangle_count; /* of the output mesh */
    const uint32_t *source_vertex;       /* per vertex: input vertex */
    const uint32_t *welded_vertex;       /* per vertex: welded input vertex */
    const float *directions;             /* 3 per vertex */
    const float *weights;                /* per vertex */
    const float *uvs, *fur_uvs;          /* 2 per vertex each */
    const uint32_t *triangle_patch;      /* per triangle */
    const uint32_t *indices;             /* 3 per triangle */
    /* Kept: mode_used, patch_count, mask_size, texel_density, fur_per_atlas,
     * fill, uv_warning. The rest is zero after a load (the caller measures
     * it again). */
    pelt_atlas_stats stats;
    void *owned; /* after a load: the block the arrays live in */
} pelt__atlas_record;

/* Reads the record cached under key. The file must hold exactly what a
 * store wrote for key (magic, version, key, length, checksum) and arrays
 * that fit an input mesh of in_vertices / in_triangles (indices in range,
 * finite values); anything else is ignored and false returned, with the
 * reason in why ("is truncated", "fails its checksum", ...). A missing file
 * is false with why empty. On success the arrays are owned by *out: free
 * with pelt__atlas_record_free. */
bool pelt__atlas_cache_load(const char *dir, uint64_t key, size_t in_vertices,
                            size_t in_triangles, pelt__atlas_record *out, char *why,
                            size_t why_size);
/* The same checks on a cache file's bytes. */
bool pelt__atlas_cache_load_memory(const void *data, size_t size, uint64_t key,
                                   size_t in_vertices, size_t in_triangles,
                                   pelt__atlas_record *out, char *why, size_t why_size);
/* Where the header keeps the key, then the input vertex and triangle counts
 * (three little-endian u64). */
#define PELT__ATLAS_CACHE_KEY_AT 16
/* Frees what a load allocated; the record is zeroed. */
void pelt__atlas_record_free(pelt__atlas_record *r);
/* Writes the record under key atomically (temporary file + rename), making
 * dir when needed; false on any failure. */
bool pelt__atlas_cache_store(const char *dir, uint64_t key, const pelt__atlas_record *r);
/* Path of the cache file for key. */
void pelt__atlas_cache_path(const char *dir, uint64_t key, char *buf, size_t size);

#endif
