/* On-disk atlas cache: one versioned, checksummed file per key holding a plain record (Lengyel §2.1 results). */
#define _POSIX_C_SOURCE 200809L
#include "core/atlas/atlas_cache.h"

#include "core/base/error.h"
#include "core/base/hooks.h"

#include <errno.h>
#include <stddef.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* The file: a header, the arrays (see payload_size), the checksum. Anything
 * that does not match exactly is ignored, and the atlas is rebuilt. */
#define CACHE_MAGIC "PELTATL\0"

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

/* The fuzz target reads the key and input counts at these offsets. */
_Static_assert(offsetof(cache_header, key) == PELT__ATLAS_CACHE_KEY_AT &&
                   offsetof(cache_header, in_vertices) == PELT__ATLAS_CACHE_KEY_AT + 8 &&
                   offsetof(cache_header, in_triangles) == PELT__ATLAS_CACHE_KEY_AT + 16,
               "cache header layout");

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

static bool write_all(FILE *f, const void *p, size_t n, pelt__atlas_hash *s)
{
    pelt__atlas_hash_bytes(s, p, n);
    return fwrite(p, 1, n, f) == n;
}

bool pelt__atlas_cache_store(const char *dir, uint64_t key, const pelt__atlas_record *r)
{
    if (!r->source_vertex || !r->welded_vertex || !r->directions || !r->weights || !r->uvs ||
        !r->fur_uvs || !r->triangle_patch || !r->indices || !mkdir_p(dir))
        return false;
    char path[4200], tmp[4300];
    pelt__atlas_cache_path(dir, key, path, sizeof path);
    /* A name of this process alone: two builders of the same atlas each
     * write their own file and rename it over the other's, whole. */
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    snprintf(tmp, sizeof tmp, "%s.tmp%ld.%09ld", path, (long)getpid(), (long)ts.tv_nsec);
    FILE *f = fopen(tmp, "wbx");
    if (!f) return false;
    cache_header h;
    memset(&h, 0, sizeof h);
    memcpy(h.magic, CACHE_MAGIC, 8);
    h.version = PELT__ATLAS_CACHE_VERSION;
    h.mode_used = (uint32_t)r->stats.mode_used;
    h.key = key;
    h.vertices = r->vertex_count;
    h.triangles = r->triangle_count;
    h.patch_count = r->stats.patch_count;
    h.mask_size = r->stats.mask_size;
    h.texel_density = r->stats.texel_density;
    h.fur_per_atlas = r->stats.fur_per_atlas;
    h.fill = r->stats.fill;
    memcpy(h.uv_warning, r->stats.uv_warning, sizeof h.uv_warning);
    /* in_* are filled from the source indices' range by the loader check. */
    h.in_vertices = 0;
    for (size_t o = 0; o < r->vertex_count; o++)
        if (r->source_vertex[o] + 1u > h.in_vertices) h.in_vertices = r->source_vertex[o] + 1u;
    h.in_triangles = r->triangle_count;
    pelt__atlas_hash s = pelt__atlas_hash_begin();
    size_t vc = r->vertex_count, tc = r->triangle_count;
    bool ok = write_all(f, &h, sizeof h, &s) &&
              write_all(f, r->source_vertex, vc * 4, &s) &&
              write_all(f, r->welded_vertex, vc * 4, &s) &&
              write_all(f, r->directions, vc * 12, &s) &&
              write_all(f, r->weights, vc * 4, &s) &&
              write_all(f, r->uvs, vc * 8, &s) &&
              write_all(f, r->fur_uvs, vc * 8, &s) &&
              write_all(f, r->triangle_patch, tc * 4, &s) &&
              write_all(f, r->indices, tc * 12, &s);
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

void pelt__atlas_record_free(pelt__atlas_record *r)
{
    if (!r) return;
    free(r->owned);
    memset(r, 0, sizeof *r);
}

/* Fails a load with its reason (for the warning). */
static bool reject(char *why, size_t why_size, const char *reason)
{
    if (why && why_size) snprintf(why, why_size, "%s", reason);
    return false;
}

bool pelt__atlas_cache_load_memory(const void *data, size_t size, uint64_t key,
                                   size_t in_vertices, size_t in_triangles,
                                   pelt__atlas_record *out, char *why, size_t why_size)
{
    memset(out, 0, sizeof *out);
    cache_header h;
    if (size < sizeof h + sizeof(uint64_t)) return reject(why, why_size, "is truncated");
    memcpy(&h, data, sizeof h);
    if (memcmp(h.magic, CACHE_MAGIC, 8) != 0) return reject(why, why_size, "is not a pelt atlas cache");
    if (h.version != PELT__ATLAS_CACHE_VERSION)
        return reject(why, why_size, "was written by another version of pelt");
    if (h.key != key) return reject(why, why_size, "was made for another mesh or settings");
    if (h.vertices == 0 || h.vertices > 3 * (uint64_t)in_triangles || h.triangles != in_triangles)
        return reject(why, why_size, "does not fit this mesh");
    /* Exactly the expected length: a byte more or less is a stale layout or a cut file. */
    size_t n = payload_size(h.vertices, h.triangles);
    if (size != sizeof h + n + sizeof(uint64_t))
        return reject(why, why_size, size < sizeof h + n + sizeof(uint64_t) ? "is truncated"
                                                                               : "is longer than its header says");
    pelt__atlas_hash s = pelt__atlas_hash_begin();
    pelt__atlas_hash_bytes(&s, data, sizeof h + n);
    uint64_t sum;
    memcpy(&sum, (const unsigned char *)data + sizeof h + n, sizeof sum);
    if (sum != s.h) return reject(why, why_size, "fails its checksum");
    /* The checksum guards against damage, these against a file that was made
     * for something else. */
    if (h.in_triangles != in_triangles || h.in_vertices > in_vertices || h.mask_size == 0 ||
        h.mask_size > 16384 || h.patch_count < 1 || h.patch_count > h.triangles ||
        (h.mode_used != PELT_ATLAS_MESH_UVS && h.mode_used != PELT_ATLAS_PATCHES) ||
        !memchr(h.uv_warning, '\0', sizeof h.uv_warning))
        return reject(why, why_size, "has a header that does not fit this mesh");
    /* The arrays get their own block: every one starts at a multiple of 4. */
    unsigned char *buf = pelt__calloc(n ? n : 1, 1);
    if (!buf) return reject(why, why_size, "cannot be read: out of memory");
    memcpy(buf, (const unsigned char *)data + sizeof h, n);
    size_t vc = h.vertices, tc = h.triangles;
    const unsigned char *p = buf;
    pelt__atlas_record r = {.vertex_count = vc, .triangle_count = tc, .owned = buf};
    r.source_vertex = (const uint32_t *)p, p += vc * 4;
    r.welded_vertex = (const uint32_t *)p, p += vc * 4;
    r.directions = (const float *)p, p += vc * 12;
    r.weights = (const float *)p, p += vc * 4;
    r.uvs = (const float *)p, p += vc * 8;
    r.fur_uvs = (const float *)p, p += vc * 8;
    r.triangle_patch = (const uint32_t *)p, p += tc * 4;
    r.indices = (const uint32_t *)p;
    bool ok = true;
    for (size_t o = 0; o < vc && ok; o++)
        ok = r.source_vertex[o] < in_vertices && r.welded_vertex[o] < in_vertices;
    for (size_t i = 0; i < 3 * tc && ok; i++) ok = r.indices[i] < vc;
    for (size_t t = 0; t < tc && ok; t++) ok = r.triangle_patch[t] < h.patch_count;
    ok = ok && all_finite(r.directions, 3 * vc) && all_finite(r.weights, vc) &&
         all_finite(r.uvs, 2 * vc) && all_finite(r.fur_uvs, 2 * vc);
    if (!ok) {
        free(buf);
        return reject(why, why_size, "holds an index out of range or a non-finite value");
    }
    r.stats.mode_used = (int)h.mode_used;
    r.stats.patch_count = h.patch_count;
    r.stats.mask_size = h.mask_size;
    r.stats.texel_density = h.texel_density;
    r.stats.fur_per_atlas = h.fur_per_atlas;
    r.stats.fill = h.fill;
    memcpy(r.stats.uv_warning, h.uv_warning, sizeof h.uv_warning);
    *out = r;
    return true;
}

bool pelt__atlas_cache_load(const char *dir, uint64_t key, size_t in_vertices,
                            size_t in_triangles, pelt__atlas_record *out, char *why, size_t why_size)
{
    memset(out, 0, sizeof *out);
    if (why && why_size) why[0] = '\0';
    char path[4200];
    pelt__atlas_cache_path(dir, key, path, sizeof path);
    FILE *f = fopen(path, "rb");
    if (!f) return false; /* no file: a plain miss, no reason */
    /* At most what the largest record that fits the mesh takes. */
    size_t cap = sizeof(cache_header) + payload_size(3 * (uint64_t)in_triangles, in_triangles) +
                 sizeof(uint64_t) + 1;
    unsigned char *data = pelt__calloc(cap, 1);
    if (!data) {
        fclose(f);
        return reject(why, why_size, "cannot be read: out of memory");
    }
    size_t size = fread(data, 1, cap, f);
    bool failed = ferror(f);
    fclose(f);
    bool ok = failed ? reject(why, why_size, "cannot be read")
                     : pelt__atlas_cache_load_memory(data, size, key, in_vertices, in_triangles, out,
                                                     why, why_size);
    free(data);
    return ok;
}
