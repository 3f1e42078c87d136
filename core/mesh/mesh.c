/* Mesh validation and per-vertex frames: the base surface the fur shells
 * are offset from (Lengyel et al. 2001, §2: shells over a triangle mesh). */
#include "core/mesh/mesh_internal.h"
#include "core/mesh/skeleton.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/vec.h"
#include "core/base/weld.h"

#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PELT__PI 3.14159265358979323846

/* Larger coordinates are corrupt data, not geometry: bbox extents and
 * products of them must stay finite. */
#define PELT__MAX_COORD 1e30f

/* A triangle is "zero area" below this fraction of the bbox diagonal squared:
 * small enough to keep genuine slivers of a million-triangle scan. */
#define PELT__MIN_AREA_FRACTION 1e-12

/* A normal whose length is within this of 1 counts as unit: a few float
 * roundings of a normalised vector (which are up to ~3e-7). */
#define PELT__UNIT_TOLERANCE 1e-6

pelt_mesh *pelt__mesh_alloc(size_t vertex_count, size_t triangle_count)
{
    if (vertex_count > (size_t)UINT32_MAX) return NULL; /* indices are 32-bit */
    pelt_mesh *m = pelt__calloc(1, sizeof *m);
    if (!m) return NULL;
    m->vertex_count = vertex_count;
    m->triangle_count = triangle_count;
    m->up[1] = 1.0f;
    m->positions = pelt__calloc(vertex_count, 3 * sizeof(float));
    m->normals = pelt__calloc(vertex_count, 3 * sizeof(float));
    m->uvs = pelt__calloc(vertex_count, 2 * sizeof(float));
    m->tangents = pelt__calloc(vertex_count, 4 * sizeof(float));
    m->indices = pelt__calloc(triangle_count, 3 * sizeof(uint32_t));
    if (!m->positions || !m->normals || !m->uvs || !m->tangents || !m->indices) {
        pelt_mesh_destroy(m);
        return NULL;
    }
    m->stats.vertex_count = vertex_count;
    m->stats.triangle_count = triangle_count;
    return m;
}

void pelt_mesh_destroy(pelt_mesh *mesh)
{
    if (!mesh) return;
    free(mesh->positions);
    free(mesh->normals);
    free(mesh->uvs);
    free(mesh->fur_uvs);
    free(mesh->tangents);
    free(mesh->comb);
    free(mesh->directions);
    free(mesh->colors);
    free(mesh->indices);
    pelt__skeleton_free(mesh->skeleton);
    free(mesh);
}

const float *pelt_mesh_directions(const pelt_mesh *mesh) { return mesh ? mesh->directions : NULL; }

const float *pelt_mesh_colors(const pelt_mesh *mesh) { return mesh ? mesh->colors : NULL; }

pelt_mesh_data pelt_mesh_get_data(const pelt_mesh *m)
{
    pelt_mesh_data d = {m->positions, m->normals, m->uvs, m->vertex_count, m->indices,
                        m->triangle_count, m->directions, m->fur_uvs, m->comb, m->colors, m->up};
    return d;
}

const float *pelt_mesh_tangents(const pelt_mesh *m) { return m->tangents; }

pelt_mesh_stats pelt_mesh_get_stats(const pelt_mesh *mesh)
{
    pelt_mesh_stats none = {0};
    return mesh ? mesh->stats : none;
}

void pelt_mesh_up(const pelt_mesh *mesh, float up[3])
{
    for (int k = 0; k < 3; k++) up[k] = mesh ? mesh->up[k] : (k == 1 ? 1.0f : 0.0f);
}

void pelt_mesh_bounds(const pelt_mesh *mesh, float min[3], float max[3])
{
    for (int k = 0; k < 3; k++) {
        min[k] = mesh ? mesh->bounds_min[k] : 0.0f;
        max[k] = mesh ? mesh->bounds_max[k] : 0.0f;
    }
}

float pelt_mesh_diagonal(const pelt_mesh *mesh)
{
    float lo[3], hi[3];
    pelt_mesh_bounds(mesh, lo, hi);
    return v3_len(v3_sub(v3_load(hi), v3_load(lo)));
}

/* ---- normals ----------------------------------------------------------- */

/* 1 / the largest bbox extent: frames are computed on the mesh scaled to
 * unit size, so float cross products neither underflow on a microscopic
 * mesh nor overflow on a huge one (directions do not change). */
static double frame_scale(const pelt_mesh *m)
{
    double ext = 0.0;
    for (int k = 0; k < 3; k++) {
        double e = (double)m->bounds_max[k] - (double)m->bounds_min[k];
        if (e > ext) ext = e;
    }
    return ext > 0.0 && isfinite(ext) ? 1.0 / ext : 1.0;
}

/* Edges p1 - p0 and p2 - p0 of triangle t, scaled by s. */
static void tri_edges(const pelt_mesh *m, size_t t, double s, pelt_vec3 *e1, pelt_vec3 *e2)
{
    const uint32_t *tri = m->indices + 3 * t;
    const float *a = m->positions + 3 * tri[0], *b = m->positions + 3 * tri[1],
                *c = m->positions + 3 * tri[2];
    *e1 = v3((float)(((double)b[0] - a[0]) * s), (float)(((double)b[1] - a[1]) * s),
             (float)(((double)b[2] - a[2]) * s));
    *e2 = v3((float)(((double)c[0] - a[0]) * s), (float)(((double)c[1] - a[1]) * s),
             (float)(((double)c[2] - a[2]) * s));
}

static pelt_vec3 tri_cross(const pelt_mesh *m, size_t t, double s)
{
    pelt_vec3 e1, e2;
    tri_edges(m, t, s, &e1, &e2);
    return v3_cross(e1, e2);
}

/* Area-weighted vertex normals, summed over all vertices that share a
 * position: a uv seam duplicates vertices, and different normals on its two
 * sides would open a crack between the offset shells. */
static void compute_normals(pelt_mesh *m, const uint32_t *canon)
{
    const double s = frame_scale(m);
    float *n = m->normals;
    memset(n, 0, m->vertex_count * 3 * sizeof(float));
    for (size_t t = 0; t < m->triangle_count; t++) {
        pelt_vec3 c = tri_cross(m, t, s); /* length = 2 * area (scaled) */
        for (int k = 0; k < 3; k++) {
            float *p = n + 3 * m->indices[3 * t + k];
            v3_store(p, v3_add(v3_load(p), c));
        }
    }
    if (canon) {
        /* Each group's sum, in ascending vertex order, lands on its smallest
         * vertex (canon[i] <= i), then is copied to the others. */
        for (size_t i = 0; i < m->vertex_count; i++) {
            float *sum = n + 3 * canon[i];
            if (canon[i] == i) v3_store(sum, v3_add(v3(0, 0, 0), v3_load(sum)));
            else v3_store(sum, v3_add(v3_load(sum), v3_load(n + 3 * i)));
        }
        for (size_t i = 0; i < m->vertex_count; i++)
            if (canon[i] != i) memcpy(n + 3 * i, n + 3 * canon[i], 3 * sizeof(float));
    }
    /* Where faces cancel (a fold), any incident face normal beats none. */
    const pelt_vec3 zero = v3(0, 0, 0);
    for (size_t t = 0; t < m->triangle_count; t++) {
        pelt_vec3 face = v3_norm_or(tri_cross(m, t, s), zero);
        for (int k = 0; k < 3; k++) {
            float *p = n + 3 * m->indices[3 * t + k];
            if (v3_len(v3_load(p)) <= 1e-30f) v3_store(p, face);
        }
    }
    for (size_t i = 0; i < m->vertex_count; i++)
        v3_store(n + 3 * i, v3_norm_or(v3_load(n + 3 * i), v3(0, 1, 0)));
}

/* ---- tangents ---------------------------------------------------------- */

/* A unit vector perpendicular to unit n: the shared basis (core/base/vec.h). */
static pelt_vec3 perpendicular(pelt_vec3 n) { return v3_perpendicular(n); }

/* Accumulates area-weighted unit +u and +v directions per vertex into
 * tan (3 per vertex) and bit (3 per vertex). */
static void accumulate_uv_frames(const pelt_mesh *m, const float *uv, float *tan, float *bit)
{
    const pelt_vec3 zero = v3(0, 0, 0);
    const double s = frame_scale(m);
    for (size_t t = 0; t < m->triangle_count; t++) {
        const uint32_t *tri = m->indices + 3 * t;
        pelt_vec3 e1, e2;
        tri_edges(m, t, s, &e1, &e2);
        float du1 = uv[2 * tri[1]] - uv[2 * tri[0]], dv1 = uv[2 * tri[1] + 1] - uv[2 * tri[0] + 1];
        float du2 = uv[2 * tri[2]] - uv[2 * tri[0]], dv2 = uv[2 * tri[2] + 1] - uv[2 * tri[0] + 1];
        float r = du1 * dv2 - du2 * dv1;
        if (!(fabsf(r) > 1e-20f)) continue; /* degenerate uvs: no direction here */
        /* dP/du and dP/dv of the triangle's affine map (times r). */
        pelt_vec3 tu = v3_sub(v3_scale(e1, dv2), v3_scale(e2, dv1));
        pelt_vec3 tv = v3_sub(v3_scale(e2, du1), v3_scale(e1, du2));
        if (r < 0) {
            tu = v3_scale(tu, -1.0f);
            tv = v3_scale(tv, -1.0f);
        }
        float area = 0.5f * v3_len(v3_cross(e1, e2));
        tu = v3_scale(v3_norm_or(tu, zero), area);
        tv = v3_scale(v3_norm_or(tv, zero), area);
        for (int k = 0; k < 3; k++) {
            float *pt = tan + 3 * tri[k], *pb = bit + 3 * tri[k];
            v3_store(pt, v3_add(v3_load(pt), tu));
            v3_store(pb, v3_add(v3_load(pb), tv));
        }
    }
}

/* Vertices with the same position and normal share their frame when all of
 * them point roughly the same way (a seam of a continuous map); a mirrored
 * seam or a pole fan keeps its own per-vertex frames. */
static void weld_tangents(const pelt_mesh *m, const uint32_t *canon, const uint32_t *next,
                          float *tan, float *bit)
{
    const uint32_t none = PELT__WELD_NONE;
    for (size_t c = 0; c < m->vertex_count; c++) {
        if (canon[c] != c || next[c] == none) continue; /* not a group's head, or alone */
        pelt_vec3 st = v3(0, 0, 0), sb = v3(0, 0, 0);
        for (uint32_t i = (uint32_t)c; i != none; i = next[i]) {
            st = v3_add(st, v3_load(tan + 3 * i));
            sb = v3_add(sb, v3_load(bit + 3 * i));
        }
        pelt_vec3 ut = v3_norm_or(st, v3(0, 0, 0)), ub = v3_norm_or(sb, v3(0, 0, 0));
        int agree = v3_len(ut) > 0.5f;
        for (uint32_t i = (uint32_t)c; i != none && agree; i = next[i]) {
            pelt_vec3 ti = v3_norm_or(v3_load(tan + 3 * i), v3(0, 0, 0));
            pelt_vec3 bi = v3_norm_or(v3_load(bit + 3 * i), v3(0, 0, 0));
            agree = v3_dot(ti, ut) > 0.7f && v3_dot(bi, ub) > 0.0f;
        }
        if (agree) {
            for (uint32_t i = (uint32_t)c; i != none; i = next[i]) {
                v3_store(tan + 3 * i, st);
                v3_store(bit + 3 * i, sb);
            }
        }
    }
}

/* Unit tangent along +u orthogonalised against the normal (Gram-Schmidt),
 * w = +1 when (n x t) points along +v, else -1. */
static void compute_tangents(pelt_mesh *m, const uint32_t *canon, const uint32_t *next,
                             float *scratch)
{
    const float *uv = m->fur_uvs ? m->fur_uvs : m->uvs;
    float *tan = scratch, *bit = scratch + 3 * m->vertex_count;
    memset(scratch, 0, m->vertex_count * 6 * sizeof(float));
    accumulate_uv_frames(m, uv, tan, bit);
    if (canon) weld_tangents(m, canon, next, tan, bit);
    for (size_t i = 0; i < m->vertex_count; i++) {
        pelt_vec3 n = v3_load(m->normals + 3 * i);
        pelt_vec3 raw = v3_load(tan + 3 * i);
        pelt_vec3 t = v3_sub(raw, v3_scale(n, v3_dot(n, raw)));
        float w = 1.0f;
        /* +u nearly along the normal is as useless as no +u at all. */
        if (v3_len(raw) > 0.0f && v3_len(t) > 1e-3f * v3_len(raw)) {
            t = v3_norm_or(t, perpendicular(n));
            if (v3_dot(v3_cross(n, t), v3_load(bit + 3 * i)) < 0.0f) w = -1.0f;
        } else {
            t = perpendicular(n);
        }
        float *o = m->tangents + 4 * i;
        v3_store(o, t);
        o[3] = w;
    }
}

/* ---- finish ------------------------------------------------------------ */

static void compute_bounds(pelt_mesh *m)
{
    for (int k = 0; k < 3; k++) {
        m->bounds_min[k] = m->vertex_count ? INFINITY : 0.0f;
        m->bounds_max[k] = m->vertex_count ? -INFINITY : 0.0f;
    }
    for (size_t i = 0; i < m->vertex_count; i++) {
        for (int k = 0; k < 3; k++) {
            float x = m->positions[3 * i + k];
            if (x < m->bounds_min[k]) m->bounds_min[k] = x;
            if (x > m->bounds_max[k]) m->bounds_max[k] = x;
        }
    }
}

void pelt__mesh_finish(pelt_mesh *mesh, bool compute_normals_flag)
{
    pelt_mesh *m = mesh;
    compute_bounds(m);
    /* Welding is a quality step: without memory for it the frames are still
     * valid, just not shared across seams. Normals are summed over a
     * position, tangent frames over a position and normal. */
    uint32_t *canon = pelt__calloc(m->vertex_count, sizeof *canon);
    uint32_t *next = pelt__calloc(m->vertex_count, sizeof *next);
    if (compute_normals_flag) {
        bool by_position = canon && pelt__weld(m->positions, NULL, m->vertex_count, canon);
        compute_normals(m, by_position ? canon : NULL);
        m->stats.computed_normals = true;
    }
    bool by_frame = canon && next && pelt__weld(m->positions, m->normals, m->vertex_count, canon);
    if (by_frame) pelt__weld_chain(canon, m->vertex_count, next);
    float *scratch = pelt__calloc(m->vertex_count, 6 * sizeof(float));
    if (scratch) {
        compute_tangents(m, by_frame ? canon : NULL, next, scratch);
    } else {
        for (size_t i = 0; i < m->vertex_count; i++) {
            v3_store(m->tangents + 4 * i, perpendicular(v3_load(m->normals + 3 * i)));
            m->tangents[4 * i + 3] = 1.0f;
        }
    }
    free(scratch);
    free(canon);
    free(next);
    m->stats.vertex_count = m->vertex_count;
    m->stats.triangle_count = m->triangle_count;
}

/* ---- pelt_mesh_create -------------------------------------------------- */

static int all_finite(const float *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i])) return 0;
    return 1;
}

static int all_bounded(const float *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!(fabsf(v[i]) <= PELT__MAX_COORD)) return 0;
    return 1;
}

/* Spherical map around the bbox centre, for meshes without uvs: enough for
 * a visible, continuous-almost-everywhere wetness mask until an atlas. */
static void fallback_uvs(pelt_mesh *m)
{
    pelt_vec3 c = v3_scale(v3_add(v3_load(m->bounds_min), v3_load(m->bounds_max)), 0.5f);
    for (size_t i = 0; i < m->vertex_count; i++) {
        pelt_vec3 d = v3_sub(v3_load(m->positions + 3 * i), c);
        float len = v3_len(d);
        float u = 0.5f, v = 0.5f;
        if (len > 0.0f) {
            u = (float)(0.5 + atan2((double)d.z, (double)d.x) / (2.0 * PELT__PI));
            v = (float)(0.5 + asin(clampf(d.y / len, -1.0f, 1.0f)) / PELT__PI);
        }
        m->uvs[2 * i] = clampf(u, 0.0f, 1.0f);
        m->uvs[2 * i + 1] = clampf(v, 0.0f, 1.0f);
    }
}

pelt_status pelt_mesh_create(const pelt_mesh_data *data, pelt_mesh **out, pelt_error *err)
{
    return pelt__mesh_create_remap(data, out, NULL, err);
}

pelt_status pelt__mesh_create_remap(const pelt_mesh_data *data, pelt_mesh **out, uint32_t **remap_out,
                                    pelt_error *err)
{
    if (remap_out) *remap_out = NULL;
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_mesh_create: out is NULL");
    *out = NULL;
    if (!data) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_mesh_create: data is NULL");
    if (!data->positions || !data->indices)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "pelt_mesh_create: %s is NULL", data->positions ? "indices" : "positions");
    if (data->vertex_count == 0 || data->triangle_count == 0)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "pelt_mesh_create: %s is 0",
                          data->vertex_count == 0 ? "vertex_count" : "triangle_count");
    const size_t nv = data->vertex_count, nt = data->triangle_count;
    if (nv > (size_t)UINT32_MAX || nv > (size_t)-1 / (6 * sizeof(float)) ||
        nt > (size_t)-1 / (3 * sizeof(uint32_t)))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "pelt_mesh_create: %zu vertices / %zu triangles is too many", nv, nt);

    for (size_t i = 0; i < nv; i++)
        if (!all_finite(data->positions + 3 * i, 3))
            return pelt__fail(err, PELT_ERR_FORMAT, "vertex %zu has a non-finite coordinate", i);
    for (size_t i = 0; i < nv; i++)
        if (!all_bounded(data->positions + 3 * i, 3))
            return pelt__fail(err, PELT_ERR_FORMAT, "vertex %zu has a coordinate beyond +-%g", i,
                              (double)PELT__MAX_COORD);
    if (data->uvs) {
        for (size_t i = 0; i < nv; i++)
            if (!all_finite(data->uvs + 2 * i, 2))
                return pelt__fail(err, PELT_ERR_FORMAT, "vertex %zu has a non-finite uv", i);
        for (size_t i = 0; i < nv; i++)
            if (!all_bounded(data->uvs + 2 * i, 2))
                return pelt__fail(err, PELT_ERR_FORMAT, "vertex %zu has a uv beyond +-%g", i,
                                  (double)PELT__MAX_COORD);
    }
    if (data->up && !(all_finite(data->up, 3) && v3_len(v3_load(data->up)) > 1e-6f))
        return pelt__fail(err, PELT_ERR_FORMAT, "the up axis is zero or not finite");
    for (size_t t = 0; t < nt; t++) {
        for (int k = 0; k < 3; k++) {
            uint32_t v = data->indices[3 * t + k];
            if (v >= nv)
                return pelt__fail(err, PELT_ERR_FORMAT,
                                  "triangle %zu refers to vertex %" PRIu32 " but there are %zu vertices",
                                  t, v, nv);
        }
    }

    /* Bounds of the referenced vertices set the zero-area threshold. */
    pelt_vec3 lo = v3(INFINITY, INFINITY, INFINITY), hi = v3(-INFINITY, -INFINITY, -INFINITY);
    for (size_t j = 0; j < 3 * nt; j++) {
        pelt_vec3 p = v3_load(data->positions + 3 * (size_t)data->indices[j]);
        lo = v3(fminf(lo.x, p.x), fminf(lo.y, p.y), fminf(lo.z, p.z));
        hi = v3(fmaxf(hi.x, p.x), fmaxf(hi.y, p.y), fmaxf(hi.z, p.z));
    }
    pelt_vec3 ext = v3_sub(hi, lo);
    double diag2 = (double)ext.x * ext.x + (double)ext.y * ext.y + (double)ext.z * ext.z;
    double min_area = PELT__MIN_AREA_FRACTION * diag2;

    /* Pass 1: keep non-degenerate triangles, mark and renumber used vertices. */
    unsigned char *keep = pelt__calloc(nt, 1);
    uint32_t *remap = pelt__calloc(nv, sizeof *remap);
    if (!keep || !remap) {
        free(keep);
        free(remap);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "pelt_mesh_create: no memory for %zu vertices", nv);
    }
    size_t kept = 0, dropped = 0, used = 0;
    for (size_t t = 0; t < nt; t++) {
        const uint32_t *tri = data->indices + 3 * t;
        int ok = tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2];
        if (ok) {
            /* Double precision: float cross products of large coordinates overflow. */
            const float *a = data->positions + 3 * (size_t)tri[0];
            const float *b = data->positions + 3 * (size_t)tri[1];
            const float *c = data->positions + 3 * (size_t)tri[2];
            double e1[3], e2[3];
            for (int k = 0; k < 3; k++) {
                e1[k] = (double)b[k] - a[k];
                e2[k] = (double)c[k] - a[k];
            }
            double cx = e1[1] * e2[2] - e1[2] * e2[1];
            double cy = e1[2] * e2[0] - e1[0] * e2[2];
            double cz = e1[0] * e2[1] - e1[1] * e2[0];
            double area = 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
            ok = area > min_area;
        }
        if (!ok) {
            dropped++;
            continue;
        }
        keep[t] = 1;
        kept++;
        for (int k = 0; k < 3; k++)
            if (remap[tri[k]] == 0) remap[tri[k]] = (uint32_t)++used; /* 0 = unused */
    }
    if (kept == 0) {
        free(keep);
        free(remap);
        return pelt__fail(err, PELT_ERR_FORMAT,
                          "mesh has no usable triangles: all %zu are degenerate or of zero area", nt);
    }

    pelt_mesh *m = pelt__mesh_alloc(used, kept);
    if (!m) {
        free(keep);
        free(remap);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY,
                          "pelt_mesh_create: no memory for %zu vertices and %zu triangles", used, kept);
    }
    for (size_t t = 0, o = 0; t < nt; t++) {
        if (!keep[t]) continue;
        for (int k = 0; k < 3; k++) m->indices[3 * o + k] = remap[data->indices[3 * t + k]] - 1;
        o++;
    }

    int normals_ok = data->normals != NULL;
    for (size_t i = 0; i < nv && normals_ok; i++) {
        if (!remap[i]) continue;
        const float *n = data->normals + 3 * i;
        normals_ok = all_finite(n, 3) && (n[0] != 0.0f || n[1] != 0.0f || n[2] != 0.0f);
    }
    if (data->fur_uvs)
        for (size_t i = 0; i < nv; i++)
            if (remap[i] && (!all_finite(data->fur_uvs + 2 * i, 2) ||
                             !all_bounded(data->fur_uvs + 2 * i, 2))) {
                free(keep);
                free(remap);
                pelt_mesh_destroy(m);
                return pelt__fail(err, PELT_ERR_FORMAT, "vertex %zu has a non-finite or huge fur uv", i);
            }
    /* Optional per-vertex arrays travel with their vertices. */
    if (data->directions) m->directions = pelt__calloc(m->vertex_count, 3 * sizeof(float));
    if (data->fur_uvs) m->fur_uvs = pelt__calloc(m->vertex_count, 2 * sizeof(float));
    if (data->comb) m->comb = pelt__calloc(m->vertex_count, 3 * sizeof(float));
    if (data->colors) m->colors = pelt__calloc(m->vertex_count, 4 * sizeof(float));
    if ((data->directions && !m->directions) || (data->fur_uvs && !m->fur_uvs) ||
        (data->comb && !m->comb) || (data->colors && !m->colors)) {
        free(keep);
        free(remap);
        pelt_mesh_destroy(m);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for per-vertex arrays");
    }
    for (size_t i = 0; i < nv; i++) {
        if (!remap[i]) continue;
        size_t o = remap[i] - 1;
        memcpy(m->positions + 3 * o, data->positions + 3 * i, 3 * sizeof(float));
        if (data->uvs) memcpy(m->uvs + 2 * o, data->uvs + 2 * i, 2 * sizeof(float));
        if (m->directions) {
            /* Non-finite hints count as none: the fur stands up there. */
            const float *d = data->directions + 3 * i;
            for (int k = 0; k < 3; k++) m->directions[3 * o + k] = isfinite(d[k]) ? d[k] : 0.0f;
        }
        if (m->fur_uvs) memcpy(m->fur_uvs + 2 * o, data->fur_uvs + 2 * i, 2 * sizeof(float));
        if (m->comb) {
            const float *c = data->comb + 3 * i;
            for (int k = 0; k < 3; k++) m->comb[3 * o + k] = isfinite(c[k]) ? c[k] : 0.0f;
        }
        if (m->colors) {
            /* Colours are clamped to [0,1]; non-finite ones become 0. */
            const float *c = data->colors + 4 * i;
            for (int k = 0; k < 4; k++)
                m->colors[4 * o + k] = isfinite(c[k]) ? fminf(fmaxf(c[k], 0.0f), 1.0f) : 0.0f;
        }
        if (normals_ok) {
            /* Normalised in double: tiny or huge input normals stay finite.
             * A normal already unit to float precision is kept as given, so
             * creating a mesh from pelt_mesh_get_data changes nothing. */
            const float *n = data->normals + 3 * i;
            double l = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
            for (int k = 0; k < 3; k++)
                m->normals[3 * o + k] = fabs(l - 1.0) <= PELT__UNIT_TOLERANCE ? n[k] : (float)(n[k] / l);
        }
    }
    free(keep);
    if (remap_out)
        *remap_out = remap;
    else
        free(remap);

    m->stats.dropped_degenerate = dropped;
    if (data->up) v3_store(m->up, v3_norm_or(v3_load(data->up), v3(0.0f, 1.0f, 0.0f)));
    if (!data->uvs) {
        compute_bounds(m);
        fallback_uvs(m);
        m->stats.fallback_uvs = true;
    }
    pelt__mesh_finish(m, !normals_ok);
    *out = m;
    return PELT_OK;
}
