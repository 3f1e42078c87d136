/* Groom files: a binary little-endian PLY of the validated mesh with the
 * groom as vertex properties (docs/grooming.md says why). Written and read
 * here by hand, strictly: only the layout pelt writes is accepted, every
 * count is checked against the bytes there are, and vertices are matched
 * to the mesh by position, so the file survives a different vertex order. */
#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/fur/fur_internal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GROOM_MAGIC "pelt groom 1"
#define VERTEX_BYTES 32u /* 7 floats + 4 bytes */
#define FACE_BYTES 13u   /* a uchar count of 3 + 3 uints */
#define MAX_HEADER 4096u

static const char *const vertex_properties[] = {
    "float x",       "float y",       "float z",      "float length", "float density",
    "float lean_u",  "float lean_v",  "uchar red",    "uchar green",  "uchar blue",
    "uchar alpha"};
enum { VERTEX_PROPERTIES = sizeof vertex_properties / sizeof vertex_properties[0] };

/* ---- writing -------------------------------------------------------------- */

static void put_u32(uint8_t *p, uint32_t x)
{
    p[0] = (uint8_t)x, p[1] = (uint8_t)(x >> 8), p[2] = (uint8_t)(x >> 16), p[3] = (uint8_t)(x >> 24);
}

static void put_f32(uint8_t *p, float f)
{
    uint32_t x;
    memcpy(&x, &f, 4);
    put_u32(p, x);
}

pelt_status pelt_fur_save_groom(const pelt_fur *f, const char *path, pelt_error *err)
{
    if (!f || !path) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "save groom: fur or path is NULL");
    const pelt_mesh_data md = pelt_mesh_get_data(f->mesh), *m = &md;
    if (m->vertex_count > UINT32_MAX || m->triangle_count > UINT32_MAX)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s: mesh too large for a groom file", path);
    /* Write to a temporary name, then rename: a crash never leaves half a file. */
    char tmp[4096];
    if (snprintf(tmp, sizeof tmp, "%s.tmp", path) >= (int)sizeof tmp)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s: path too long", path);
    FILE *out = fopen(tmp, "wb");
    if (!out) return pelt__fail(err, PELT_ERR_IO, "%s: cannot write (through %s): %s", path, tmp, strerror(errno));
    fprintf(out, "ply\nformat binary_little_endian 1.0\ncomment " GROOM_MAGIC "\n"
                 "comment per vertex: length (x fur length), density, lean (tangent frame), "
                 "hair colour (alpha = its weight)\n"
                 "element vertex %zu\n", m->vertex_count);
    for (int k = 0; k < VERTEX_PROPERTIES; k++) fprintf(out, "property %s\n", vertex_properties[k]);
    fprintf(out, "element face %zu\nproperty list uchar uint vertex_indices\nend_header\n",
            m->triangle_count);
    bool ok = true;
    for (size_t i = 0; i < m->vertex_count && ok; i++) {
        const pelt__groom_vertex *g = &f->groom.v[i];
        uint8_t rec[VERTEX_BYTES];
        for (int k = 0; k < 3; k++) put_f32(rec + 4 * k, m->positions[3 * i + (size_t)k]);
        put_f32(rec + 12, g->length);
        put_f32(rec + 16, g->density);
        put_f32(rec + 20, g->lean[0]);
        put_f32(rec + 24, g->lean[1]);
        memcpy(rec + 28, g->color, 4);
        ok = fwrite(rec, sizeof rec, 1, out) == 1;
    }
    for (size_t t = 0; t < m->triangle_count && ok; t++) {
        uint8_t rec[FACE_BYTES];
        rec[0] = 3;
        for (int k = 0; k < 3; k++) put_u32(rec + 1 + 4 * k, m->indices[3 * t + (size_t)k]);
        ok = fwrite(rec, sizeof rec, 1, out) == 1;
    }
    if (fclose(out) != 0) ok = false;
    if (!ok || rename(tmp, path) != 0) {
        int e = errno;
        remove(tmp);
        return pelt__fail(err, PELT_ERR_IO, "%s: cannot write: %s", path, strerror(e));
    }
    return PELT_OK;
}

/* ---- reading -------------------------------------------------------------- */

static uint32_t get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static float get_f32(const uint8_t *p)
{
    uint32_t x = get_u32(p);
    float f;
    memcpy(&f, &x, 4);
    return f;
}

/* The next header line into line[] (without the newline); false at the end
 * of the header area or on an over-long line. */
static bool next_line(const char *text, size_t size, size_t *at, char *line, size_t cap)
{
    size_t i = *at, n = 0;
    while (i < size && text[i] != '\n') {
        if (n + 1 >= cap) return false;
        line[n++] = text[i++];
    }
    if (i >= size) return false;
    if (n && line[n - 1] == '\r') n--;
    line[n] = '\0';
    *at = i + 1;
    return true;
}

/* Parses "element NAME COUNT" for the expected name. */
static bool element_line(const char *line, const char *name, size_t *count)
{
    char fmt[64];
    snprintf(fmt, sizeof fmt, "element %s %%20s", name);
    char num[24] = {0};
    if (sscanf(line, fmt, num) != 1) return false;
    char *end;
    errno = 0;
    unsigned long long c = strtoull(num, &end, 10);
    if (*end || errno || num[0] == '-' || c > UINT32_MAX) return false;
    *count = (size_t)c;
    return true;
}

typedef struct header {
    size_t vertices, faces, data_at;
} header;

static pelt_status read_header(const uint8_t *data, size_t size, const char *name, header *h,
                               pelt_error *err)
{
    const char *text = (const char *)data;
    size_t limit = size < MAX_HEADER ? size : MAX_HEADER, at = 0;
    char line[256];
#define NEXT(what)                                                                              \
    do {                                                                                        \
        if (!next_line(text, limit, &at, line, sizeof line))                                    \
            return pelt__fail(err, PELT_ERR_FORMAT, "%s: not a pelt groom file: the header "     \
                              "ends before %s", name, what);                                    \
    } while (0)
    NEXT("'ply'");
    if (strcmp(line, "ply") != 0)
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: not a PLY file (a groom file starts with 'ply')", name);
    NEXT("the format");
    if (strcmp(line, "format binary_little_endian 1.0") != 0)
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: groom files are binary_little_endian 1.0, got '%.60s'",
                          name, line);
    bool magic = false;
    for (;;) {
        NEXT("'element vertex'");
        if (strncmp(line, "comment ", 8) != 0) break;
        if (strcmp(line + 8, GROOM_MAGIC) == 0) magic = true;
    }
    if (!magic)
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: a PLY file but not a pelt groom (no '" GROOM_MAGIC
                          "' comment): save one with pelt_fur_save_groom", name);
    if (!element_line(line, "vertex", &h->vertices))
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: expected 'element vertex COUNT', got '%.60s'", name, line);
    for (int k = 0; k < VERTEX_PROPERTIES; k++) {
        NEXT("the vertex properties");
        if (strncmp(line, "property ", 9) != 0 || strcmp(line + 9, vertex_properties[k]) != 0)
            return pelt__fail(err, PELT_ERR_FORMAT, "%s: vertex property %d: expected 'property %s', "
                              "got '%.60s'", name, k + 1, vertex_properties[k], line);
    }
    NEXT("'element face'");
    if (!element_line(line, "face", &h->faces))
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: expected 'element face COUNT', got '%.60s'", name, line);
    NEXT("the face property");
    if (strcmp(line, "property list uchar uint vertex_indices") != 0)
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: expected 'property list uchar uint "
                          "vertex_indices', got '%.60s'", name, line);
    NEXT("'end_header'");
    if (strcmp(line, "end_header") != 0)
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: expected 'end_header', got '%.60s'", name, line);
#undef NEXT
    h->data_at = at;
    /* Both counts are below 2^32, so these products fit in 64 bits. */
    size_t need = (size_t)h->vertices * VERTEX_BYTES + (size_t)h->faces * FACE_BYTES;
    size_t have = size - at;
    if (have < need)
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: truncated: the header declares %zu vertices and "
                          "%zu faces (%zu bytes), the file holds %zu", name, h->vertices, h->faces,
                          need, have);
    if (have > need)
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: %zu bytes after the %zu vertices and %zu faces",
                          name, have - need, h->vertices, h->faces);
    return PELT_OK;
}

/* ---- matching file vertices to mesh vertices by position ------------------ */

typedef struct grid {
    size_t mask;        /* table size - 1 (a power of two) */
    uint32_t *slot;     /* file vertex + 1, 0 = empty */
    float inv_cell;
} grid;

static uint64_t cell_hash(int64_t x, int64_t y, int64_t z)
{
    uint64_t h = (uint64_t)x * 0x9e3779b97f4a7c15ULL ^ (uint64_t)y * 0xc2b2ae3d27d4eb4fULL ^
                 (uint64_t)z * 0x165667b19e3779f9ULL;
    return h ^ (h >> 29);
}

static void cell_of(const grid *g, const float p[3], int64_t c[3])
{
    /* Clamped so that a far-away file position still converts safely. */
    for (int k = 0; k < 3; k++) c[k] = (int64_t)floorf(fmaxf(fminf(p[k] * g->inv_cell, 1e15f), -1e15f));
}

static const float *file_position(const uint8_t *verts, uint32_t i, float out[3])
{
    for (int k = 0; k < 3; k++) out[k] = get_f32(verts + (size_t)i * VERTEX_BYTES + 4 * (size_t)k);
    return out;
}

/* The file vertex within tol of p, or UINT32_MAX. */
static uint32_t grid_find(const grid *g, const uint8_t *verts, const float p[3], float tol)
{
    int64_t c[3];
    cell_of(g, p, c);
    for (int dz = -1; dz <= 1; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                uint64_t key = cell_hash(c[0] + dx, c[1] + dy, c[2] + dz);
                for (size_t s = key & g->mask; g->slot[s]; s = (s + 1) & g->mask) {
                    float q[3];
                    file_position(verts, g->slot[s] - 1, q);
                    if (fabsf(q[0] - p[0]) <= tol && fabsf(q[1] - p[1]) <= tol &&
                        fabsf(q[2] - p[2]) <= tol)
                        return g->slot[s] - 1;
                }
            }
    return UINT32_MAX;
}

/* The file vertex of every mesh vertex: in order when the file is this
 * mesh's, else through a hash grid of the file's positions. */
static pelt_status match_vertices(const pelt_mesh_data *m, float diagonal, const uint8_t *verts, size_t nfile,
                                  const char *name, uint32_t *of, pelt_error *err)
{
    float tol = 1e-5f * diagonal;
    if (!(tol > 0.0f)) tol = 1e-12f;
    bool in_order = nfile == m->vertex_count;
    for (size_t i = 0; i < m->vertex_count && in_order; i++) {
        float q[3];
        file_position(verts, (uint32_t)i, q);
        for (int k = 0; k < 3; k++)
            if (!(fabsf(q[k] - m->positions[3 * i + (size_t)k]) <= tol)) in_order = false;
        of[i] = (uint32_t)i;
    }
    if (in_order) return PELT_OK;

    grid g = {0, NULL, 1.0f / (2.0f * tol)};
    size_t size = 16;
    while (size < 2 * nfile) size *= 2;
    g.mask = size - 1;
    g.slot = pelt__calloc(size, sizeof *g.slot);
    if (!g.slot) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", name);
    for (uint32_t i = 0; i < nfile; i++) {
        float p[3];
        int64_t c[3];
        cell_of(&g, file_position(verts, i, p), c);
        size_t s = cell_hash(c[0], c[1], c[2]) & g.mask;
        while (g.slot[s]) s = (s + 1) & g.mask;
        g.slot[s] = i + 1;
    }
    size_t missing = 0, first_missing = 0;
    for (size_t i = 0; i < m->vertex_count; i++) {
        of[i] = grid_find(&g, verts, m->positions + 3 * i, tol);
        if (of[i] == UINT32_MAX && missing++ == 0) first_missing = i;
    }
    free(g.slot);
    if (missing)
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: groom does not match the mesh: %zu of its %zu "
                          "vertices (first: vertex %zu at %g %g %g) have no groom vertex within %g "
                          "(the file has %zu vertices; was it saved for another mesh?)",
                          name, missing, m->vertex_count, first_missing,
                          (double)m->positions[3 * first_missing],
                          (double)m->positions[3 * first_missing + 1],
                          (double)m->positions[3 * first_missing + 2], (double)tol, nfile);
    return PELT_OK;
}

pelt_status pelt_fur_load_groom_memory(pelt_fur *f, const void *data, size_t size, const char *name,
                                       pelt_error *err)
{
    if (!name) name = "groom";
    if (!f || (!data && size)) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s: fur or data is NULL", name);
    header h;
    pelt_status st = read_header(data, size, name, &h, err);
    if (st != PELT_OK) return st;
    const uint8_t *verts = (const uint8_t *)data + h.data_at;
    const uint8_t *faces = verts + h.vertices * VERTEX_BYTES;
    for (size_t t = 0; t < h.faces; t++) {
        const uint8_t *r = faces + t * FACE_BYTES;
        if (r[0] != 3)
            return pelt__fail(err, PELT_ERR_FORMAT, "%s: face %zu has %u vertices, groom files hold "
                              "triangles", name, t, (unsigned)r[0]);
        for (int k = 0; k < 3; k++)
            if (get_u32(r + 1 + 4 * k) >= h.vertices)
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: face %zu: vertex index %u out of range "
                                  "(%zu vertices)", name, t, get_u32(r + 1 + 4 * k), h.vertices);
    }
    for (size_t i = 0; i < h.vertices; i++)
        for (int k = 0; k < 7; k++)
            if (!isfinite(get_f32(verts + i * VERTEX_BYTES + 4 * (size_t)k)))
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: vertex %zu: %s is not finite", name, i,
                                  vertex_properties[k] + 6 /* past "float " */);
    const pelt_mesh_data md = pelt_mesh_get_data(f->mesh), *m = &md;
    uint32_t *of = pelt__calloc(m->vertex_count ? m->vertex_count : 1, sizeof *of);
    if (!of) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", name);
    st = match_vertices(m, pelt_mesh_diagonal(f->mesh), verts, h.vertices, name, of, err);
    if (st == PELT_OK) {
        for (size_t i = 0; i < m->vertex_count; i++) {
            const uint8_t *r = verts + (size_t)of[i] * VERTEX_BYTES;
            pelt_groom_value v;
            v.length = get_f32(r + 12);
            v.density = get_f32(r + 16);
            v.lean[0] = get_f32(r + 20);
            v.lean[1] = get_f32(r + 24);
            for (int k = 0; k < 4; k++) v.color[k] = r[28 + k] / 255.0f;
            pelt__groom_pack(&v, &f->groom.v[i]);
        }
        pelt__groom_changed(&f->groom, 0, m->vertex_count);
    }
    free(of);
    return st;
}

pelt_status pelt_fur_load_groom(pelt_fur *f, const char *path, pelt_error *err)
{
    if (!path) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "load groom: path is NULL");
    FILE *in = fopen(path, "rb");
    if (!in) return pelt__fail(err, PELT_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    uint8_t *data = NULL;
    size_t size = 0;
    pelt_status st = PELT_OK;
    if (fseek(in, 0, SEEK_END) != 0) st = PELT_ERR_IO;
    long end = st == PELT_OK ? ftell(in) : -1;
    if (end < 0 || fseek(in, 0, SEEK_SET) != 0) st = PELT_ERR_IO;
    if (st == PELT_OK) {
        size = (size_t)end;
        data = malloc(size ? size : 1);
        if (!data) st = PELT_ERR_OUT_OF_MEMORY;
        else if (size && fread(data, 1, size, in) != size) st = PELT_ERR_IO;
    }
    fclose(in);
    if (st == PELT_OK) st = pelt_fur_load_groom_memory(f, data, size, path, err);
    else pelt__fail(err, st, "%s: cannot read", path);
    free(data);
    return st;
}
