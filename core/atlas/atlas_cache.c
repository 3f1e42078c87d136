/* On-disk cache of atlas results: one small binary file per (mesh, desc)
 * key with a header, a version and a checksum; anything that does not
 * match exactly is ignored and rebuilt. */
#define _POSIX_C_SOURCE 200809L
#include "core/atlas/atlas.h"

#include "core/base/error.h"
#include "core/mesh/mesh_internal.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#define CACHE_MAGIC "PELTATL\0"
#define CACHE_VERSION 1u

typedef struct hasher { uint64_t h; } hasher;

/* FNV-1a, 64 bit. */
static void hash_bytes(hasher *s, const void *data, size_t n)
{
    const unsigned char *p = data;
    uint64_t h = s->h;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 0x100000001b3ULL;
    }
    s->h = h;
}

static void hash_u64(hasher *s, uint64_t v) { hash_bytes(s, &v, sizeof v); }
static void hash_f32(hasher *s, float v) { hash_bytes(s, &v, sizeof v); }

uint64_t pelt__atlas_key(const pelt_mesh *in, const pelt_atlas_desc *d, unsigned mask_size,
                         float density)
{
    hasher s = {0xcbf29ce484222325ULL};
    hash_u64(&s, CACHE_VERSION);
    hash_u64(&s, in->vertex_count);
    hash_u64(&s, in->triangle_count);
    hash_bytes(&s, in->positions, in->vertex_count * 3 * sizeof(float));
    hash_bytes(&s, in->normals, in->vertex_count * 3 * sizeof(float));
    hash_bytes(&s, in->uvs, in->vertex_count * 2 * sizeof(float));
    hash_bytes(&s, in->indices, in->triangle_count * 3 * sizeof(uint32_t));
    hash_u64(&s, in->stats.fallback_uvs);
    hash_u64(&s, mask_size);
    hash_f32(&s, density);
    for (int k = 0; k < 3; k++) hash_f32(&s, d->direction[k]);
    hash_u64(&s, d->vertex_directions != NULL);
    if (d->vertex_directions) hash_bytes(&s, d->vertex_directions, in->vertex_count * 3 * sizeof(float));
    hash_u64(&s, d->seed);
    hash_f32(&s, d->max_stretch);
    hash_u64(&s, (uint64_t)(int64_t)d->mode);
    hash_u64(&s, d->max_patch_faces);
    hash_u64(&s, d->smoothing_iterations);
    return s.h;
}

void pelt__atlas_cache_path(const char *dir, uint64_t key, char *buf, size_t size)
{
    snprintf(buf, size, "%s/atlas-%016llx.bin", dir, (unsigned long long)key);
}

bool pelt_atlas_default_cache_dir(char *buf, size_t size)
{
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    int n;
    if (xdg && xdg[0] == '/') n = snprintf(buf, size, "%s/pelt", xdg);
    else if (home && home[0]) n = snprintf(buf, size, "%s/.cache/pelt", home);
    else return false;
    return n > 0 && (size_t)n < size;
}

/* The fixed part of a cache file; arrays follow, then the checksum. */
typedef struct cache_header {
    char magic[8];
    uint32_t version, mode_used;
    uint64_t key;
    uint64_t in_vertices, in_triangles, vertices, triangles, patch_count;
    uint32_t mask_size, reserved;
    float texel_density, fur_per_atlas, fill, reserved2;
    char uv_warning[256];
} cache_header;

static size_t payload_size(uint64_t vc, uint64_t tc)
{
    /* source, welded (u32), directions (3 f32), weights, uvs, fur_uvs (2 f32)
     * per vertex; patch and 3 indices (u32) per triangle. */
    return (size_t)vc * (4 + 4 + 12 + 4 + 8 + 8) + (size_t)tc * (4 + 12);
}

static bool mkdir_p(const char *dir)
{
    char path[4096];
    size_t n = strlen(dir);
    if (n == 0 || n >= sizeof path) return false;
    memcpy(path, dir, n + 1);
    for (size_t i = 1; i <= n; i++) {
        if (path[i] == '/' || path[i] == '\0') {
            char c = path[i];
            path[i] = '\0';
            if (mkdir(path, 0755) != 0 && errno != EEXIST) return false;
            path[i] = c;
        }
    }
    return true;
}

static bool write_all(FILE *f, const void *p, size_t n, hasher *s)
{
    hash_bytes(s, p, n);
    return fwrite(p, 1, n, f) == n;
}

bool pelt__atlas_cache_store(const char *dir, uint64_t key, const pelt_atlas *a)
{
    if (!a->mesh || !mkdir_p(dir)) return false;
    char path[4200], tmp[4300];
    pelt__atlas_cache_path(dir, key, path, sizeof path);
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    snprintf(tmp, sizeof tmp, "%s.tmp%09ld", path, (long)ts.tv_nsec);
    FILE *f = fopen(tmp, "wb");
    if (!f) return false;
    cache_header h;
    memset(&h, 0, sizeof h);
    memcpy(h.magic, CACHE_MAGIC, 8);
    h.version = CACHE_VERSION;
    h.mode_used = (uint32_t)a->stats.mode_used;
    h.key = key;
    h.vertices = a->vertex_count;
    h.triangles = a->triangle_count;
    h.patch_count = a->stats.patch_count;
    h.mask_size = a->stats.mask_size;
    h.texel_density = a->stats.texel_density;
    h.fur_per_atlas = a->stats.fur_per_atlas;
    h.fill = a->stats.fill;
    memcpy(h.uv_warning, a->stats.uv_warning, sizeof h.uv_warning);
    /* in_* are filled from the source indices' range by the loader check. */
    h.in_vertices = 0;
    for (size_t o = 0; o < a->vertex_count; o++)
        if (a->source_vertex[o] + 1u > h.in_vertices) h.in_vertices = a->source_vertex[o] + 1u;
    h.in_triangles = a->triangle_count;
    hasher s = {0xcbf29ce484222325ULL};
    size_t vc = a->vertex_count, tc = a->triangle_count;
    bool ok = write_all(f, &h, sizeof h, &s) &&
              write_all(f, a->source_vertex, vc * 4, &s) &&
              write_all(f, a->welded_vertex, vc * 4, &s) &&
              write_all(f, a->directions, vc * 12, &s) &&
              write_all(f, a->weights, vc * 4, &s) &&
              write_all(f, a->mesh->uvs, vc * 8, &s) &&
              write_all(f, a->mesh->fur_uvs, vc * 8, &s) &&
              write_all(f, a->triangle_patch, tc * 4, &s) &&
              write_all(f, a->mesh->indices, tc * 12, &s);
    uint64_t sum = s.h;
    ok = ok && fwrite(&sum, sizeof sum, 1, f) == 1;
    ok = (fclose(f) == 0) && ok;
    if (ok) ok = rename(tmp, path) == 0;
    if (!ok) remove(tmp);
    return ok;
}

static bool all_finite(const float *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i])) return false;
    return true;
}

bool pelt__atlas_cache_load(const char *dir, uint64_t key, const pelt_mesh *in, pelt_atlas **out)
{
    char path[4200];
    pelt__atlas_cache_path(dir, key, path, sizeof path);
    FILE *f = fopen(path, "rb");
    if (!f) return false;
    cache_header h;
    bool ok = fread(&h, sizeof h, 1, f) == 1 && memcmp(h.magic, CACHE_MAGIC, 8) == 0 &&
              h.version == CACHE_VERSION && h.key == key && h.triangles == in->triangle_count &&
              h.in_triangles == in->triangle_count && h.in_vertices <= in->vertex_count &&
              h.vertices > 0 && h.vertices <= 3 * h.triangles && h.mask_size > 0 &&
              h.mask_size <= 16384 && h.patch_count >= 1 && h.patch_count <= h.triangles &&
              (h.mode_used == PELT_ATLAS_MESH_UVS || h.mode_used == PELT_ATLAS_PATCHES) &&
              memchr(h.uv_warning, '\0', sizeof h.uv_warning) != NULL;
    pelt_atlas *a = NULL;
    unsigned char *buf = NULL;
    if (ok) {
        size_t n = payload_size(h.vertices, h.triangles);
        buf = pelt__calloc(n + sizeof(uint64_t) + 1, 1);
        /* Exactly the expected length: one byte more means a stale layout. */
        ok = buf && fread(buf, 1, n + sizeof(uint64_t) + 1, f) == n + sizeof(uint64_t);
        if (ok) {
            hasher s = {0xcbf29ce484222325ULL};
            hash_bytes(&s, &h, sizeof h);
            hash_bytes(&s, buf, n);
            uint64_t sum;
            memcpy(&sum, buf + n, sizeof sum);
            ok = sum == s.h;
        }
        if (ok) {
            a = pelt__atlas_alloc(h.vertices, h.triangles);
            if (a) a->mesh = pelt__mesh_alloc(h.vertices, h.triangles);
            if (a && a->mesh) a->mesh->fur_uvs = pelt__calloc(h.vertices, 2 * sizeof(float));
            ok = a && a->mesh && a->mesh->fur_uvs;
        }
        if (ok) {
            size_t vc = h.vertices, tc = h.triangles;
            const unsigned char *p = buf;
            memcpy(a->source_vertex, p, vc * 4), p += vc * 4;
            memcpy(a->welded_vertex, p, vc * 4), p += vc * 4;
            memcpy(a->directions, p, vc * 12), p += vc * 12;
            memcpy(a->weights, p, vc * 4), p += vc * 4;
            memcpy(a->mesh->uvs, p, vc * 8), p += vc * 8;
            memcpy(a->mesh->fur_uvs, p, vc * 8), p += vc * 8;
            memcpy(a->triangle_patch, p, tc * 4), p += tc * 4;
            memcpy(a->mesh->indices, p, tc * 12);
            /* The checksum guards against damage, these against a file that
             * was made for something else. */
            for (size_t o = 0; o < vc && ok; o++)
                ok = a->source_vertex[o] < in->vertex_count && a->welded_vertex[o] < in->vertex_count;
            for (size_t i = 0; i < 3 * tc && ok; i++) ok = a->mesh->indices[i] < vc;
            for (size_t t = 0; t < tc && ok; t++) ok = a->triangle_patch[t] < h.patch_count;
            ok = ok && all_finite(a->directions, 3 * vc) && all_finite(a->weights, vc) &&
                 all_finite(a->mesh->uvs, 2 * vc) && all_finite(a->mesh->fur_uvs, 2 * vc);
        }
    }
    fclose(f);
    free(buf);
    if (!ok) {
        pelt_atlas_destroy(a);
        return false;
    }
    a->stats.mode_used = (int)h.mode_used;
    a->stats.patch_count = h.patch_count;
    a->stats.mask_size = h.mask_size;
    a->stats.texel_density = h.texel_density;
    a->stats.fur_per_atlas = h.fur_per_atlas;
    a->stats.fill = h.fill;
    memcpy(a->stats.uv_warning, h.uv_warning, sizeof h.uv_warning);
    pelt__atlas_finish_mesh(a, in);
    *out = a;
    return true;
}
