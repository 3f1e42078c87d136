/* Geometric level of detail for the shells: meshoptimizer's simplifier over
 * the mesh's own vertices (see lod.h). */
#include "core/fur/lod.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/weld.h"

#include <math.h>
#include <meshoptimizer.h>
#include <stdlib.h>
#include <string.h>

/* A level stops the chain when it keeps more than this share of the
 * previous level's triangles: the simplifier has run into locked borders. */
#define LOD_MIN_SHRINK 0.8
/* Nothing coarser than this many triangles is worth a level. */
#define LOD_MIN_TRIANGLES 64

static void bounding_sphere(const pelt_mesh_data *m, float center[3], float *radius)
{
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < m->vertex_count; i++)
        for (int k = 0; k < 3; k++) {
            float p = m->positions[3 * i + (size_t)k];
            lo[k] = fminf(lo[k], p);
            hi[k] = fmaxf(hi[k], p);
        }
    float r2 = 0.0f;
    for (int k = 0; k < 3; k++) center[k] = m->vertex_count ? 0.5f * (lo[k] + hi[k]) : 0.0f;
    for (size_t i = 0; i < m->vertex_count; i++) {
        float d2 = 0.0f;
        for (int k = 0; k < 3; k++) {
            float d = m->positions[3 * i + (size_t)k] - center[k];
            d2 += d * d;
        }
        r2 = fmaxf(r2, d2);
    }
    *radius = sqrtf(r2);
}

static int cmp_u64(const void *x, const void *y)
{
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return (a > b) - (a < b);
}

/* Closed: every edge, its end points welded by position (uv seams and patch
 * borders split vertices), is shared by exactly two triangles. Only then
 * are the shells' back faces hidden behind the skin. False when out of
 * memory (the safe answer: nothing gets culled). */
static bool is_closed(const pelt_mesh_data *m, const pelt_allocator *alloc)
{
    size_t n = 3 * m->triangle_count;
    if (n == 0) return false;
    uint32_t *canon = pelt__alloc(alloc, m->vertex_count * sizeof *canon);
    uint64_t *keys = pelt__alloc(alloc, n * sizeof *keys);
    bool closed = canon && keys && pelt__weld(m->positions, NULL, m->vertex_count, canon);
    if (closed) {
        for (size_t i = 0; i < n; i++) {
            uint64_t a = canon[m->indices[i]], b = canon[m->indices[i - i % 3 + (i + 1) % 3]];
            keys[i] = a < b ? a << 32 | b : b << 32 | a;
        }
        qsort(keys, n, sizeof *keys, cmp_u64);
        for (size_t i = 0; i < n && closed;) {
            size_t j = i;
            while (j < n && keys[j] == keys[i]) j++;
            closed = j - i == 2;
            i = j;
        }
    }
    pelt__free(alloc, canon);
    pelt__free(alloc, keys);
    return closed;
}

/* +1 when the triangles wind counter-clockwise about the vertex normals
 * (seen from outside), -1 clockwise, 0 when they disagree too often to
 * cull by winding. */
static int winding(const pelt_mesh_data *m)
{
    if (!m->normals || m->triangle_count == 0) return 0;
    size_t ccw = 0;
    for (size_t t = 0; t < m->triangle_count; t++) {
        const float *p[3], *n[3];
        for (int k = 0; k < 3; k++) {
            p[k] = m->positions + 3 * (size_t)m->indices[3 * t + (size_t)k];
            n[k] = m->normals + 3 * (size_t)m->indices[3 * t + (size_t)k];
        }
        float e1[3], e2[3];
        for (int k = 0; k < 3; k++) e1[k] = p[1][k] - p[0][k], e2[k] = p[2][k] - p[0][k];
        float c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        float d = 0.0f;
        for (int k = 0; k < 3; k++) d += c[k] * (n[0][k] + n[1][k] + n[2][k]);
        ccw += d > 0.0f;
    }
    double share = (double)ccw / (double)m->triangle_count;
    return share > 0.98 ? 1 : share < 0.02 ? -1 : 0;
}

static int cmp_u32(const void *x, const void *y)
{
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return (a > b) - (a < b);
}

static uint32_t index_of(const uint32_t *sorted, size_t n, uint32_t v)
{
    size_t lo = 0, hi = n;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (sorted[mid] <= v) lo = mid;
        else hi = mid;
    }
    return (uint32_t)lo;
}

/* The fins' vertices once each, and each fin's ends among them: a frame
 * works out the fins' strands once per vertex, not per fin. */
static pelt_status fin_vertices(pelt__lod_level *l, const pelt_allocator *alloc, pelt_error *err)
{
    size_t n = 2 * l->fin_count;
    l->fin_vertices = pelt__alloc(alloc, (n ? n : 1) * sizeof *l->fin_vertices);
    l->fin_ends = pelt__alloc(alloc, (n ? n : 1) * sizeof *l->fin_ends);
    if (!l->fin_vertices || !l->fin_ends)
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the vertices of %zu fins", l->fin_count);
    for (size_t i = 0; i < l->fin_count; i++) {
        l->fin_vertices[2 * i] = l->fins[i].a;
        l->fin_vertices[2 * i + 1] = l->fins[i].b;
    }
    qsort(l->fin_vertices, n, sizeof *l->fin_vertices, cmp_u32);
    size_t unique = 0;
    for (size_t i = 0; i < n; i++)
        if (i == 0 || l->fin_vertices[i] != l->fin_vertices[i - 1]) l->fin_vertices[unique++] = l->fin_vertices[i];
    l->fin_vertex_count = unique;
    for (size_t i = 0; i < l->fin_count; i++) {
        l->fin_ends[2 * i] = index_of(l->fin_vertices, unique, l->fins[i].a);
        l->fin_ends[2 * i + 1] = index_of(l->fin_vertices, unique, l->fins[i].b);
    }
    return PELT_OK;
}

static pelt_status add_level(pelt__lod_chain *c, uint32_t *indices, size_t triangles, float error,
                             const pelt_mesh_data *m, const float *tangents, uint32_t seed,
                             const pelt_allocator *alloc, pelt_error *err)
{
    size_t vertex_count = m->vertex_count;
    pelt__lod_level *l = &c->levels[c->count++];
    l->indices = indices;
    l->triangle_count = triangles;
    l->error = error;
    double sum = 0.0;
    for (size_t i = 0; i < 3 * triangles; i++) {
        const float *a = m->positions + 3 * (size_t)indices[i];
        const float *b = m->positions + 3 * (size_t)indices[i - i % 3 + (i + 1) % 3];
        sum += sqrt((double)((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])));
    }
    l->edge = triangles ? (float)(sum / (double)(3 * triangles)) : 0.0f;
    /* Vertex-cache order: each vertex shaded once for as many of its
     * triangles as the post-transform cache holds. In place is allowed. */
    meshopt_optimizeVertexCache(indices, indices, 3 * triangles, vertex_count);
    pelt_status st = pelt__fin_edges_build(indices, triangles, seed, alloc, &l->fins, &l->fin_count, err);
    if (st != PELT_OK) return st;
    l->fin_normals = pelt__alloc(alloc, (l->fin_count ? l->fin_count : 1) * 3 * sizeof(float));
    if (!l->fin_normals) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for %zu fin normals", l->fin_count);
    if (m->normals) pelt__fin_normals(l->fins, l->fin_count, m->positions, m->normals, l->fin_normals);
    else memset(l->fin_normals, 0, l->fin_count * 3 * sizeof(float));
    st = fin_vertices(l, alloc, err);
    if (st != PELT_OK || c->count == 1 || c->count > PELT__LOD_FIT_LEVELS + 1) return st;
    l->fit_normals = pelt__alloc(alloc, (vertex_count ? vertex_count : 1) * 3 * sizeof(float));
    if (!l->fit_normals) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for a level's normals");
    return pelt__lod_fit_normals(m, tangents, indices, triangles, l->edge, alloc, l->fit_normals, err);
}

pelt_status pelt__lod_chain_build(const pelt_mesh *mesh, uint32_t seed, unsigned max_levels,
                                  const pelt_allocator *alloc, pelt__lod_chain *out, pelt_error *err)
{
    memset(out, 0, sizeof *out);
    const pelt_mesh_data m = pelt_mesh_get_data(mesh);
    const float *tangents = pelt_mesh_tangents(mesh);
    bounding_sphere(&m, out->center, &out->radius);
    out->closed = is_closed(&m, alloc);
    out->winding = winding(&m);
    if (max_levels == 0 || max_levels > PELT__LOD_MAX_LEVELS) max_levels = PELT__LOD_MAX_LEVELS;
    size_t n = 3 * m.triangle_count;
    uint32_t *full = pelt__alloc(alloc, (n ? n : 3) * sizeof *full);
    if (!full) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the level-of-detail indices");
    memcpy(full, m.indices, n * sizeof *full);
    pelt_status st = add_level(out, full, m.triangle_count, 0.0f, &m, tangents, seed, alloc, err);
    /* Simplify the full mesh each time, not the previous level, so each
     * level's error is measured against the surface the skin draws. */
    float scale = m.vertex_count ? meshopt_simplifyScale(m.positions, m.vertex_count, 3 * sizeof(float)) : 0.0f;
    size_t previous = m.triangle_count;
    while (st == PELT_OK && out->count < max_levels && previous / 2 >= LOD_MIN_TRIANGLES) {
        uint32_t *dst = pelt__alloc(alloc, n * sizeof *dst);
        if (!dst) {
            st = pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the level-of-detail indices");
            break;
        }
        float relative = 0.0f;
        size_t got = meshopt_simplify(dst, m.indices, n, m.positions, m.vertex_count, 3 * sizeof(float),
                                      3 * (previous / 2), 1.0f, meshopt_SimplifyLockBorder, &relative);
        size_t triangles = got / 3;
        if (triangles == 0 || (double)triangles > LOD_MIN_SHRINK * (double)previous) {
            pelt__free(alloc, dst);
            break;
        }
        st = add_level(out, dst, triangles, relative * scale, &m, tangents, seed, alloc, err);
        previous = triangles;
    }
    if (st != PELT_OK) pelt__lod_chain_free(out, alloc);
    return st;
}

void pelt__lod_chain_free(pelt__lod_chain *c, const pelt_allocator *alloc)
{
    for (unsigned i = 0; i < c->count; i++) {
        pelt__free(alloc, c->levels[i].indices);
        pelt__free(alloc, c->levels[i].fins);
        pelt__free(alloc, c->levels[i].fin_normals);
        pelt__free(alloc, c->levels[i].fin_vertices);
        pelt__free(alloc, c->levels[i].fin_ends);
        pelt__free(alloc, c->levels[i].fit_normals);
    }
    memset(c, 0, sizeof *c);
}

unsigned pelt__lod_pick(const pelt__lod_chain *c, float pixels_per_unit, float max_error_px, float max_edge_px)
{
    if (!(pixels_per_unit > 0.0f) || !isfinite(pixels_per_unit)) return 0;
    unsigned pick = 0;
    for (unsigned i = 1; i < c->count; i++)
        if (c->levels[i].error * pixels_per_unit <= max_error_px && c->levels[i].edge * pixels_per_unit <= max_edge_px)
            pick = i;
    return pick;
}

unsigned pelt__lod_pick_fins(const pelt__lod_chain *c, unsigned mesh_level, float pixels_per_unit, float max_error_px,
                             float max_edge)
{
    /* The shells' pick with the slab, on screen, as the edge bound. */
    unsigned pick = pelt__lod_pick(c, pixels_per_unit, max_error_px, max_edge * pixels_per_unit);
    return pick > mesh_level ? pick : mesh_level;
}

float pelt__lod_pixels_per_unit(float proj_y, float height, float scale, float distance, float radius)
{
    float nearest = distance - radius * scale;
    if (!(nearest > 0.0f)) return INFINITY;
    return proj_y * 0.5f * height * scale / nearest;
}

/* ---- shell levels ---- */

unsigned pelt__lod_shell_count(unsigned layers, unsigned level)
{
    if (level >= 32) return 1;
    unsigned step = 1u << level;
    return (layers + step - 1) / step;
}

unsigned pelt__lod_shell_levels(unsigned layers)
{
    unsigned k = 0;
    while (pelt__lod_shell_count(layers, k) > 1) k++;
    return k + 1;
}

unsigned pelt__lod_shell_base(unsigned layers, unsigned level)
{
    unsigned base = 1;
    for (unsigned k = 0; k < level; k++) base += pelt__lod_shell_count(layers, k);
    return base;
}

size_t pelt__lod_shell_extra_slices(unsigned layers)
{
    unsigned levels = pelt__lod_shell_levels(layers);
    return pelt__lod_shell_base(layers, levels) - (layers + 1);
}

unsigned pelt__lod_shell_layer(unsigned layers, unsigned level, unsigned i)
{
    unsigned count = pelt__lod_shell_count(layers, level);
    return layers - 1 - (count - 1 - i) * (1u << level);
}

/* Premultiplied "over": the outer slice in front of the inner one. */
static void over(const uint8_t *outer, const uint8_t *inner, size_t texels, uint8_t *out)
{
    for (size_t i = 0; i < texels; i++) {
        unsigned keep = 255u - outer[4 * i + 3];
        for (int c = 0; c < 4; c++) {
            unsigned v = outer[4 * i + c] + (inner[4 * i + c] * keep + 127u) / 255u;
            out[4 * i + c] = (uint8_t)(v > 255u ? 255u : v);
        }
    }
}

/* Slice s of the whole array: the volume's N + 1, then the extra ones. */
static const uint8_t *slice_at(const uint8_t *volume, const uint8_t *extra, unsigned layers, unsigned s,
                               size_t slice)
{
    if (s <= layers) return volume + (size_t)s * slice;
    return extra + (size_t)(s - layers - 1) * slice;
}

void pelt__lod_shell_composite(const uint8_t *volume, unsigned size, unsigned layers, uint8_t *extra)
{
    size_t texels = (size_t)size * size, slice = texels * 4;
    unsigned levels = pelt__lod_shell_levels(layers);
    for (unsigned k = 1; k < levels; k++) {
        unsigned fine = k - 1, count = pelt__lod_shell_count(layers, k);
        unsigned fine_count = pelt__lod_shell_count(layers, fine);
        for (unsigned i = 0; i < count; i++) {
            /* Shell j of level k (j from the outside) is shell 2j of the
             * finer level over its shell 2j + 1, when there is one. */
            unsigned j = count - 1 - i;
            unsigned outer_i = fine_count - 1 - 2 * j;
            unsigned s = pelt__lod_shell_base(layers, fine) + outer_i;
            const uint8_t *outer = slice_at(volume, extra, layers, s, slice);
            uint8_t *dst = extra + (size_t)(pelt__lod_shell_base(layers, k) + i - layers - 1) * slice;
            if (2 * j + 1 < fine_count)
                over(outer, slice_at(volume, extra, layers, s - 1, slice), texels, dst);
            else
                memcpy(dst, outer, slice);
        }
    }
}

void pelt__lod_shell_choice(unsigned layers, float fur_pixels, float shell_pixels, unsigned *level,
                            float *blend)
{
    *level = 0;
    *blend = 0.0f;
    if (!(fur_pixels > 0.0f) || !isfinite(fur_pixels) || layers < 2) return;
    /* lambda: the level whose spacing is exactly shell_pixels. */
    float lambda = log2f((float)layers * shell_pixels / fur_pixels);
    if (!(lambda > 0.0f)) return;
    float top = (float)(pelt__lod_shell_levels(layers) - 1);
    if (lambda >= top) {
        *level = (unsigned)top;
        return;
    }
    *level = (unsigned)lambda;
    float f = lambda - (float)*level;
    *blend = f <= 0.5f ? 0.0f : (f - 0.5f) * 2.0f;
}

void pelt__lod_shell_uniforms(unsigned layers, unsigned level, float blend, unsigned first, float shells[4],
                              float next[2], unsigned *count)
{
    if (level == 0 && blend == 0.0f) {
        unsigned to_top = first >= layers ? 0 : layers - first;
        *count = to_top;
        shells[0] = (float)to_top, shells[1] = 1.0f, shells[2] = (float)(1 + first), shells[3] = 0.0f;
    } else {
        *count = pelt__lod_shell_count(layers, level);
        shells[0] = (float)*count, shells[1] = (float)(1u << level);
        shells[2] = (float)pelt__lod_shell_base(layers, level), shells[3] = blend;
    }
    next[0] = (float)pelt__lod_shell_base(layers, level + 1);
    next[1] = (float)pelt__lod_shell_count(layers, level + 1);
}

/* The shells' spacing on screen: side-on, side_px, foreshortened by sin
 * theta. Mirrors shell_view_spacing() in gl/shaders/shell_lod.glsl. */
static float view_spacing(float side_px, float n_dot_v)
{
    float c = fminf(fabsf(n_dot_v), 1.0f);
    return side_px * sqrtf(1.0f - c * c);
}

float pelt__lod_view_blend(float side_px, float n_dot_v, float target_px, float drift)
{
    float fore = view_spacing(side_px, n_dot_v), across = side_px * drift;
    float spacing = fmaxf(sqrtf(fore * fore + across * across), 1e-6f);
    return fminf(fmaxf(log2f(target_px / spacing), 0.0f), 1.0f);
}

bool pelt__lod_back_hidden(float n_dot_v, float reach) { return reach >= 0.0f && n_dot_v < -reach; }

float pelt__lod_fur_texture_aniso(float side_px, float n_dot_v, float max_aniso)
{
    float spacing = view_spacing(side_px, n_dot_v);
    float s = fminf(fmaxf(2.0f - spacing / PELT__FUR_TEXTURE_ROW_PX, 0.0f), 1.0f);
    return 1.0f + (max_aniso - 1.0f) * s;
}

float pelt__lod_sub_shell_need(float side_px, float n_dot_v, float drift)
{
    float fore = view_spacing(side_px, n_dot_v), across = side_px * drift;
    float spacing = sqrtf(fore * fore + across * across);
    float need = (spacing / PELT__SUB_SHELL_PIXELS - 0.35f) / 0.65f;
    return need > 0.0f ? (need < 1.0f ? need : 1.0f) : 0.0f; /* NaN: 0 */
}

float pelt__lod_sub_shell_exponent(float part, float k, float need)
{
    if (!(k > 1.0f)) return 1.0f;
    return part < k - 1.5f ? need / k : 1.0f - (k - 1.0f) * need / k;
}

unsigned pelt__lod_sub_shells(float side_px, unsigned max_sub)
{
    if (!(side_px > PELT__SUB_SHELL_PIXELS) || max_sub <= 1) return 1; /* also NaN */
    float k = ceilf(side_px / PELT__SUB_SHELL_PIXELS);
    return k >= (float)max_sub ? max_sub : (unsigned)k;
}

/* A texture read's footprint from its uv derivatives dx, dy (uv per pixel)
 * and the texture's size: the squared lengths of its longer and shorter
 * side, in texels. Mirrors footprint_sides() in shell_lod.glsl. */
static void footprint_sides(const float dx[2], const float dy[2], float texels, float *longer, float *shorter)
{
    float a = (dx[0] * dx[0] + dx[1] * dx[1]) * texels * texels;
    float b = (dy[0] * dy[0] + dy[1] * dy[1]) * texels * texels;
    *longer = fmaxf(a, b), *shorter = fminf(a, b);
}

float pelt__lod_fur_texture(const float dx[2], const float dy[2], float texels, float max_aniso)
{
    float longer, shorter;
    footprint_sides(dx, dy, texels, &longer, &shorter);
    /* Squared lengths: half their log2. */
    return 0.5f * log2f(fmaxf(fmaxf(longer / (max_aniso * max_aniso), shorter), 1e-12f));
}

float pelt__lod_shell_fur_texture(const float dx[2], const float dy[2], float texels, float max_aniso)
{
    float longer, shorter;
    footprint_sides(dx, dy, texels, &longer, &shorter);
    float elongation = sqrtf(longer / fmaxf(shorter, 1e-12f));
    float sharpen = PELT__FUR_TEXTURE_SHARPEN * fminf(fmaxf(2.0f - elongation, 0.0f), 1.0f);
    return pelt__lod_fur_texture(dx, dy, texels, max_aniso) - sharpen;
}

unsigned pelt__lod_fur_texture_taps(const float dx[2], const float dy[2], float texels, float max_aniso,
                                    unsigned max_taps, float *lod)
{
    float longer, shorter;
    footprint_sides(dx, dy, texels, &longer, &shorter);
    float n = fminf(fmaxf(ceilf(sqrtf(longer / fmaxf(shorter, 1e-12f)) / max_aniso), 1.0f), (float)max_taps);
    /* Each of n fetches covers 1/n of the long side: the one-fetch level
     * with n times the long side allowed to a pixel. */
    *lod = n > 1.0f ? pelt__lod_fur_texture(dx, dy, texels, max_aniso * n)
                    : pelt__lod_shell_fur_texture(dx, dy, texels, max_aniso);
    return n > 1.0f ? (unsigned)n : 1u;
}

float pelt__lod_fin_texture_aniso(const float dx[2], const float dy[2])
{
    float longer, shorter;
    footprint_sides(dx, dy, 1.0f, &longer, &shorter);
    return 1.0f + (PELT__FIN_TEXTURE_ANISO - 1.0f) * fminf(fmaxf(2.0f - sqrtf(shorter), 0.0f), 1.0f);
}

float pelt__lod_fur_edge_gain(const float dx[2], const float dy[2], float texels)
{
    float longer, shorter;
    footprint_sides(dx, dy, texels, &longer, &shorter);
    return fmaxf(1.0f / sqrtf(fmaxf(longer, 1e-12f)), 1.0f);
}

void pelt__lod_fur_edge(float rgba[4], float gain)
{
    float a = fminf(fmaxf((rgba[3] - 0.5f) * gain + 0.5f, 0.0f), 1.0f);
    float scale = a / fmaxf(rgba[3], 1e-4f);
    for (int k = 0; k < 4; k++) rgba[k] *= scale;
}

float pelt__lod_shell_overcount_cap(float layers)
{
    return fmaxf(PELT__SHELL_OVERCOUNT_MAX, layers * PELT__SHELL_OVERCOUNT_REACH);
}

float pelt__lod_shell_overcount(float width_over_spacing, float cos_view, float drift, float least, float cap)
{
    float c = fminf(fmaxf(fabsf(cos_view), 1e-3f), 1.0f);
    float tan_view = sqrtf(fmaxf(1.0f - c * c, 0.0f)) / c;
    float k = width_over_spacing / fmaxf(sqrtf(tan_view * tan_view + drift * drift), 1e-3f);
    return fminf(fmaxf(k, least), cap);
}

float pelt__lod_shell_stack_cos(const float t[3], const float V[3], const float n[3])
{
    float tn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2], vn = V[0] * n[0] + V[1] * n[1] + V[2] * n[2];
    float along = fabsf(tn * vn), across = 0.0f;
    for (int k = 0; k < 3; k++) across += (t[k] * vn - V[k] * tn) * (t[k] * vn - V[k] * tn);
    float len = sqrtf(along * along + across);
    return len > 1e-12f ? along / len : 0.0f;
}

/* GLSL's smoothstep(e0, e1, x). */
static float smooth_step(float e0, float e1, float x)
{
    float t = fminf(fmaxf((x - e0) / (e1 - e0), 0.0f), 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

void pelt__lod_shell_gap(const float n[3], const float t[3], const float V[3], const float u[3], const float v[3],
                         float step, float uv_per_world, float spacing_px, float gap[3])
{
    float vn = V[0] * n[0] + V[1] * n[1] + V[2] * n[2];
    gap[2] = (1.0f - smooth_step(PELT__SHELL_GAP_FULL, PELT__SHELL_GAP_NONE, fabsf(vn))) *
             smooth_step(PELT__SHELL_GAP_OUTLINE_NONE, PELT__SHELL_GAP_OUTLINE_FULL, fabsf(vn));
    if (spacing_px >= 0.0f) gap[2] *= smooth_step(PELT__SHELL_GAP_PX_NONE, PELT__SHELL_GAP_PX_FULL, spacing_px);
    vn = vn < 0.0f ? fminf(vn, -PELT__SHELL_GAP_MIN_COS) : fmaxf(vn, PELT__SHELL_GAP_MIN_COS);
    float tn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2], d[3];
    for (int k = 0; k < 3; k++) d[k] = V[k] * (step * tn / vn) - t[k] * step;
    gap[0] = (d[0] * u[0] + d[1] * u[1] + d[2] * u[2]) * uv_per_world;
    gap[1] = (d[0] * v[0] + d[1] * v[1] + d[2] * v[2]) * uv_per_world;
}

float pelt__lod_shell_edge_least(float n_dot_v, float depth)
{
    float t = fminf(fabsf(n_dot_v) / PELT__SHELL_EDGE_REACH, 1.0f);
    float s = t * t * (3.0f - 2.0f * t);
    return 1.0f - (1.0f - 1.0f / fmaxf(depth, 1.0f)) * (1.0f - s); /* exactly 1 at depth 1 */
}

float pelt__lod_shell_overcount_alpha(float a, float k)
{
    return 1.0f - powf(fmaxf(1.0f - a, 0.0f), 1.0f / fmaxf(k, 1.0f));
}

float pelt__lod_coverage_log(float a)
{
    float clear = 1.0f - a;
    return clear > 0.0f ? log2f(clear) : -1e30f;
}

float pelt__lod_coverage_share(float clear_log, float e)
{
    return 1.0f - exp2f(clear_log * e);
}

float pelt__lod_shell_hair_span(float width, float taper, float h, float layers, float length)
{
    return width * (1.0f - taper * fminf(fmaxf(h, 0.0f), 1.0f)) * layers / fmaxf(length, 1e-6f);
}

float pelt__lod_shell_hair_drift(float ringlet, float omega, float h, float length, float curl_radius,
                                 float curl_omega)
{
    /* d/dh of the helix k h (cos, sin)(omega h + psi) has length
     * k sqrt(1 + omega^2 h^2); over the spacing length / N per layer. */
    float ring = ringlet * sqrtf(1.0f + omega * omega * h * h) / fmaxf(length, 1e-6f);
    return ring + fabsf(curl_radius * curl_omega);
}

float pelt__lod_shell_lean_drift(const float t[3], const float n[3])
{
    float c[3] = {t[1] * n[2] - t[2] * n[1], t[2] * n[0] - t[0] * n[2], t[0] * n[1] - t[1] * n[0]};
    float across = sqrtf(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    float along = fabsf(t[0] * n[0] + t[1] * n[1] + t[2] * n[2]);
    float least = PELT__SHELL_LEAN_MIN_COS * sqrtf((t[0] * t[0] + t[1] * t[1] + t[2] * t[2]) *
                                                   (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
    return across > 0.0f ? across / fmaxf(along, least) : 0.0f;
}

void pelt__lod_view_texel(float w, float rgba[4])
{
    float gain = 1.0f + w * (1.0f - rgba[3]);
    for (int k = 0; k < 4; k++) rgba[k] *= gain;
}

float pelt__lod_shell_instance(const float shells[4], const float next[2], float layers, float i, float slices[3],
                               float *alpha)
{
    float j = shells[0] - 1.0f - i;
    bool kept = fmodf(j, 2.0f) < 0.5f;
    float own = shells[2] + i;
    slices[0] = own;
    slices[1] = kept ? next[0] + next[1] - 1.0f - floorf(j * 0.5f) : own;
    slices[2] = kept ? shells[3] : 0.0f;
    *alpha = kept ? 1.0f : 1.0f - shells[3];
    return layers - 1.0f - j * shells[1];
}
