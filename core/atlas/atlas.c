/* Atlas build orchestration and public API: defaults, cache use, mode choice, output mesh (Lengyel §2.1, §3). */
#include "core/atlas/atlas_internal.h"
#include "core/mesh/skeleton.h"

#include "core/atlas/atlas_cache.h"
#include "core/atlas/direction_field.h"
#include "core/base/error.h"
#include "core/base/params.h"
#include "core/base/hooks.h"
#include "core/base/weld.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_seconds(void)
{
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- the result object ------------------------------------------------- */

pelt_atlas *pelt__atlas_alloc(const pelt_allocator *alloc, size_t vertex_count,
                              size_t triangle_count)
{
    pelt_atlas *a = pelt__alloc_zero(alloc, 1, sizeof *a);
    if (!a) return NULL;
    if (alloc) a->alloc = *alloc;
    a->vertex_count = vertex_count;
    a->triangle_count = triangle_count;
    a->source_vertex = pelt__alloc_zero(&a->alloc, vertex_count, sizeof(uint32_t));
    a->welded_vertex = pelt__alloc_zero(&a->alloc, vertex_count, sizeof(uint32_t));
    a->triangle_patch = pelt__alloc_zero(&a->alloc, triangle_count, sizeof(uint32_t));
    a->directions = pelt__alloc_zero(&a->alloc, vertex_count, 3 * sizeof(float));
    a->weights = pelt__alloc_zero(&a->alloc, vertex_count, sizeof(float));
    if (!a->source_vertex || !a->welded_vertex || !a->triangle_patch || !a->directions ||
        !a->weights) {
        pelt_atlas_destroy(a);
        return NULL;
    }
    return a;
}

void pelt_atlas_destroy(pelt_atlas *a)
{
    if (!a) return;
    pelt_mesh_destroy(a->mesh);
    pelt_allocator al = a->alloc;
    pelt__free(&al, a->source_vertex);
    pelt__free(&al, a->welded_vertex);
    pelt__free(&al, a->triangle_patch);
    pelt__free(&al, a->directions);
    pelt__free(&al, a->weights);
    pelt__free(&al, a);
}

const pelt_mesh *pelt_atlas_mesh(const pelt_atlas *a) { return a ? a->mesh : NULL; }
pelt_mesh *pelt_atlas_take_mesh(pelt_atlas *a)
{
    if (!a) return NULL;
    pelt_mesh *m = a->mesh;
    a->mesh = NULL;
    return m;
}
const pelt_atlas_stats *pelt_atlas_get_stats(const pelt_atlas *a) { return a ? &a->stats : NULL; }
size_t pelt_atlas_vertex_count(const pelt_atlas *a) { return a ? a->vertex_count : 0; }
const uint32_t *pelt_atlas_source_vertices(const pelt_atlas *a) { return a ? a->source_vertex : NULL; }
const uint32_t *pelt_atlas_welded_vertices(const pelt_atlas *a) { return a ? a->welded_vertex : NULL; }
const uint32_t *pelt_atlas_triangle_patches(const pelt_atlas *a) { return a ? a->triangle_patch : NULL; }
const float *pelt_atlas_directions(const pelt_atlas *a) { return a ? a->directions : NULL; }
const float *pelt_atlas_direction_weights(const pelt_atlas *a) { return a ? a->weights : NULL; }

/* ---- the builder's memory ---------------------------------------------- */

static void builder_free(pelt__atlas_builder *b)
{
    void *ptrs[] = {b->canon, b->adj, b->face_patch, b->dir, b->weight, b->fnormal, b->fcent,
                    b->order, b->face_stamp, b->face_done, b->dist, b->heap, b->local_of,
                    b->local_stamp, b->lverts, b->tri_local, b->coef, b->frame, b->X, b->r,
                    b->q, b->s, b->p, b->t, b->colscale, b->claims, b->out_source,
                    b->out_patch, b->out_index, b->vert_stamp, b->vert_out, b->out_local,
                    b->patch_box};
    for (size_t i = 0; i < sizeof ptrs / sizeof ptrs[0]; i++) pelt__free(&b->alloc, ptrs[i]);
}

static bool builder_alloc(pelt__atlas_builder *b)
{
    size_t vc = b->vc, tc = b->tc, cap = b->cap, lv = 3 * (size_t)cap;
    b->canon = pelt__alloc_zero(&b->alloc, vc, sizeof(uint32_t));
    b->adj = pelt__alloc_zero(&b->alloc, tc, 3 * sizeof(uint32_t));
    b->face_patch = pelt__alloc_zero(&b->alloc, tc, sizeof(uint32_t));
    b->dir = pelt__alloc_zero(&b->alloc, vc, 3 * sizeof(float));
    b->weight = pelt__alloc_zero(&b->alloc, vc, sizeof(float));
    b->fnormal = pelt__alloc_zero(&b->alloc, tc, 3 * sizeof(float));
    b->fcent = pelt__alloc_zero(&b->alloc, tc, 3 * sizeof(float));
    b->order = pelt__alloc_zero(&b->alloc, cap, sizeof(uint32_t));
    b->face_stamp = pelt__alloc_zero(&b->alloc, tc, sizeof(uint32_t));
    b->face_done = pelt__alloc_zero(&b->alloc, tc, sizeof(uint32_t));
    b->dist = pelt__alloc_zero(&b->alloc, tc, sizeof(float));
    b->heap = pelt__alloc_zero(&b->alloc, lv + 4, sizeof(pelt__atlas_heap_item));
    b->local_of = pelt__alloc_zero(&b->alloc, vc, sizeof(uint32_t));
    b->local_stamp = pelt__alloc_zero(&b->alloc, vc, sizeof(uint32_t));
    b->lverts = pelt__alloc_zero(&b->alloc, lv, sizeof(uint32_t));
    b->tri_local = pelt__alloc_zero(&b->alloc, lv, sizeof(uint32_t));
    b->coef = pelt__alloc_zero(&b->alloc, cap, 6 * sizeof(double));
    b->frame = pelt__alloc_zero(&b->alloc, cap, 3 * sizeof(double));
    b->X = pelt__alloc_zero(&b->alloc, lv, 2 * sizeof(double));
    b->r = pelt__alloc_zero(&b->alloc, cap, 2 * sizeof(double));
    b->q = pelt__alloc_zero(&b->alloc, cap, 2 * sizeof(double));
    b->s = pelt__alloc_zero(&b->alloc, lv, 2 * sizeof(double));
    b->p = pelt__alloc_zero(&b->alloc, lv, 2 * sizeof(double));
    b->t = pelt__alloc_zero(&b->alloc, lv, 2 * sizeof(double));
    b->colscale = pelt__alloc_zero(&b->alloc, lv, 2 * sizeof(double));
    b->claims_res = 1024;
    b->claims = pelt__alloc_zero(&b->alloc, (size_t)b->claims_res * b->claims_res, 1);
    b->out_source = pelt__alloc_zero(&b->alloc, tc, 3 * sizeof(uint32_t));
    b->out_patch = pelt__alloc_zero(&b->alloc, tc, 3 * sizeof(uint32_t));
    b->out_index = pelt__alloc_zero(&b->alloc, tc, 3 * sizeof(uint32_t));
    b->vert_stamp = pelt__alloc_zero(&b->alloc, vc, sizeof(uint32_t));
    b->vert_out = pelt__alloc_zero(&b->alloc, vc, sizeof(uint32_t));
    b->out_local = pelt__alloc_zero(&b->alloc, tc, 6 * sizeof(float));
    b->patch_box = pelt__alloc_zero(&b->alloc, tc, 4 * sizeof(float));
    return b->canon && b->adj && b->face_patch && b->dir && b->weight && b->fnormal &&
           b->fcent && b->order && b->face_stamp && b->face_done && b->dist && b->heap &&
           b->local_of && b->local_stamp && b->lverts && b->tri_local && b->coef &&
           b->frame && b->X && b->r && b->q && b->s && b->p && b->t && b->colscale &&
           b->claims && b->out_source && b->out_patch && b->out_index && b->vert_stamp &&
           b->vert_out && b->out_local && b->patch_box;
}

/* ---- the output mesh --------------------------------------------------- */

/* Makes the output mesh of an atlas whose per-vertex arrays are filled,
 * through pelt_mesh_create as an embedder would: positions and the original
 * normals come from `in` through source_vertex (shells must not crack where
 * vertices split), the comb direction is the direction field times its
 * weight (the fur stands up where the field vanishes), uvs, fur_uvs and
 * indices are given. The vertices are first put in the order pelt_mesh_create
 * numbers them (as the triangles first use them, unused ones left out), the
 * atlas's own arrays with them, so the mesh and the arrays agree and the mesh
 * round-trips through pelt_mesh_get_data. Fills the count, stretch and flip
 * statistics. */
static pelt_status make_output_mesh(pelt_atlas *a, const pelt_mesh *in, const float *uvs,
                                    const float *fur_uvs, const uint32_t *indices,
                                    pelt_error *err)
{
    const pelt_mesh_data src = pelt_mesh_get_data(in);
    size_t nv = a->vertex_count, tc = a->triangle_count;
    /* 3 + 3 + 3 + 2 + 2 + 3 (directions) + 1 (weight) + 4 (colours)
     * floats and 2 + 1 (old index) indices per vertex, 3 indices per
     * triangle. */
    float *fbuf = pelt__alloc_zero(&a->alloc, nv, 21 * sizeof(float));
    uint32_t *ibuf = pelt__alloc_zero(&a->alloc, 3 * nv + 3 * tc, sizeof(uint32_t));
    if (!fbuf || !ibuf) {
        pelt__free(&a->alloc, fbuf), pelt__free(&a->alloc, ibuf);
        return pelt__atlas_fail_oom(err, "output mesh");
    }
    float *positions = fbuf, *normals = fbuf + 3 * nv, *comb = fbuf + 6 * nv;
    float *ord_uvs = fbuf + 9 * nv, *ord_fur = fbuf + 11 * nv, *dirs = fbuf + 13 * nv,
          *wts = fbuf + 16 * nv, *colors = src.colors ? fbuf + 17 * nv : NULL;
    uint32_t *old_of = ibuf, *source = ibuf + nv, *welded = ibuf + 2 * nv,
             *ord_indices = ibuf + 3 * nv;
    uint32_t *new_of = source; /* scratch until the gather below: new index + 1, 0 = unused */
    size_t vc = 0;
    for (size_t i = 0; i < 3 * tc; i++) {
        uint32_t v = indices[i];
        if (!new_of[v]) {
            new_of[v] = (uint32_t)++vc;
            old_of[vc - 1] = v;
        }
        ord_indices[i] = new_of[v] - 1;
    }
    for (size_t o = 0; o < vc; o++) {
        uint32_t p = old_of[o];
        source[o] = a->source_vertex[p]; /* overwrites new_of, no longer needed */
        welded[o] = a->welded_vertex[p];
        memcpy(dirs + 3 * o, a->directions + 3 * p, 3 * sizeof(float));
        wts[o] = a->weights[p];
        memcpy(ord_uvs + 2 * o, uvs + 2 * p, 2 * sizeof(float));
        memcpy(ord_fur + 2 * o, fur_uvs + 2 * p, 2 * sizeof(float));
        memcpy(positions + 3 * o, src.positions + 3 * source[o], 3 * sizeof(float));
        memcpy(normals + 3 * o, src.normals + 3 * source[o], 3 * sizeof(float));
        for (int k = 0; k < 3; k++) comb[3 * o + k] = dirs[3 * o + k] * wts[o];
        if (colors) memcpy(colors + 4 * o, src.colors + 4 * source[o], 4 * sizeof(float));
    }
    a->vertex_count = vc;
    memcpy(a->source_vertex, source, vc * sizeof(uint32_t));
    memcpy(a->welded_vertex, welded, vc * sizeof(uint32_t));
    memcpy(a->directions, dirs, vc * 3 * sizeof(float));
    memcpy(a->weights, wts, vc * sizeof(float));
    pelt_mesh_data d = {.positions = positions, .normals = normals, .uvs = ord_uvs,
                        .vertex_count = vc, .indices = ord_indices, .triangle_count = tc,
                        .fur_uvs = ord_fur, .comb = comb, .colors = colors, .up = src.up};
    pelt_error merr = {0};
    pelt_mesh *m = NULL;
    pelt_status st = pelt_mesh_create(&d, &m, &merr);
    pelt__free(&a->alloc, fbuf), pelt__free(&a->alloc, ibuf);
    if (st != PELT_OK) return pelt__fail(err, st, "pelt_atlas_create: output mesh: %s", merr.message);
    const pelt_mesh_data out = pelt_mesh_get_data(m);
    if (out.vertex_count != vc || out.triangle_count != tc) {
        /* The input passed the same validation, so this cannot happen; the
         * per-vertex arrays would no longer match the mesh. */
        pelt_mesh_destroy(m);
        return pelt__fail(err, PELT_ERR_FORMAT,
                          "pelt_atlas_create: validation kept %zu of %zu triangles of the output mesh",
                          out.triangle_count, tc);
    }
    st = pelt__mesh_copy_skeleton(m, in, a->source_vertex, err);
    if (st != PELT_OK) {
        pelt_mesh_destroy(m);
        return st;
    }
    a->mesh = m;
    a->stats.vertex_count = vc;
    a->stats.triangle_count = tc;
    pelt__atlas_uv_stats(out.positions, out.uvs, out.indices, tc, &a->stats);
    return PELT_OK;
}

/* The per-output-vertex direction field and welded index from the input's
 * through source_vertex, then the mesh. */
static pelt_status finish_output(pelt_atlas *a, const pelt_mesh *in, const float *dir,
                                 const float *weight, const uint32_t *canon, const float *uvs,
                                 const float *fur_uvs, const uint32_t *indices, pelt_error *err)
{
    for (size_t o = 0; o < a->vertex_count; o++) {
        uint32_t v = a->source_vertex[o];
        memcpy(a->directions + 3 * o, dir + 3 * v, 3 * sizeof(float));
        a->weights[o] = weight[v];
        a->welded_vertex[o] = canon[v];
    }
    return make_output_mesh(a, in, uvs, fur_uvs, indices, err);
}

/* ---- the two modes ----------------------------------------------------- */

/* The mesh's own uvs, one fur density in world units:
 * fur_uvs = uvs * density * sqrt(world area / uv area). */
static pelt_status build_mesh_uvs(const pelt_allocator *al, const pelt_mesh *in, float density,
                                  const float *dir,
                                  const float *weight, const uint32_t *canon, pelt_atlas **out,
                                  pelt_error *err)
{
    const pelt_mesh_data m = pelt_mesh_get_data(in);
    pelt_atlas *a = pelt__atlas_alloc(al, m.vertex_count, m.triangle_count);
    float *fur_uvs = pelt__alloc_zero(al, m.vertex_count, 2 * sizeof(float));
    if (!a || !fur_uvs) {
        pelt_atlas_destroy(a);
        pelt__free(al, fur_uvs);
        return pelt__atlas_fail_oom(err, "atlas arrays");
    }
    double tot_uv, tot_w;
    pelt__atlas_area_totals(m.positions, m.uvs, m.indices, m.triangle_count, &tot_uv, &tot_w,
                            NULL, NULL);
    float k = tot_uv > 0 ? (float)(density * sqrt(tot_w / tot_uv)) : density;
    for (size_t v = 0; v < m.vertex_count; v++) {
        a->source_vertex[v] = (uint32_t)v;
        fur_uvs[2 * v] = m.uvs[2 * v] * k;
        fur_uvs[2 * v + 1] = m.uvs[2 * v + 1] * k;
    }
    a->stats.mode_used = PELT_ATLAS_MESH_UVS;
    a->stats.patch_count = 1;
    a->stats.fur_per_atlas = k;
    a->stats.fill = 1.0f;
    pelt_status st = finish_output(a, in, dir, weight, canon, m.uvs, fur_uvs, m.indices, err);
    pelt__free(al, fur_uvs);
    if (st != PELT_OK) {
        pelt_atlas_destroy(a);
        return st;
    }
    *out = a;
    return PELT_OK;
}

/* Patches grown, flattened and packed (Lengyel §2.1). */
static pelt_status build_patches(const pelt_mesh *in, pelt__atlas_builder *b, unsigned mask,
                                 float density, uint32_t seed, pelt_atlas **out, pelt_error *err)
{
    pelt_status st = pelt__atlas_grow_patches(b, seed, err);
    if (st != PELT_OK) return st;
    pelt_atlas *a = pelt__atlas_alloc(&b->alloc, b->out_count, b->tc);
    float *uvs = pelt__alloc_zero(&b->alloc, b->out_count, 4 * sizeof(float));
    if (!a || !uvs) {
        pelt_atlas_destroy(a);
        pelt__free(&b->alloc, uvs);
        return pelt__atlas_fail_oom(err, "output arrays");
    }
    float *fur_uvs = uvs + 2 * b->out_count;
    double scale = 0, used = 0;
    st = pelt__atlas_pack(b, mask, uvs, &scale, &used, err);
    if (st == PELT_OK) {
        for (size_t o = 0; o < b->out_count; o++) {
            fur_uvs[2 * o] = b->out_local[2 * o] * density;
            fur_uvs[2 * o + 1] = b->out_local[2 * o + 1] * density;
            a->source_vertex[o] = b->out_source[o];
        }
        memcpy(a->triangle_patch, b->face_patch, b->tc * sizeof(uint32_t));
        a->stats.mode_used = PELT_ATLAS_PATCHES;
        a->stats.patch_count = b->patch_count;
        a->stats.fur_per_atlas = (float)(density * mask / scale);
        a->stats.fill = (float)(used / ((double)mask * mask));
        st = finish_output(a, in, b->dir, b->weight, b->canon, uvs, fur_uvs, b->out_index, err);
    }
    pelt__free(&b->alloc, uvs);
    if (st != PELT_OK) {
        pelt_atlas_destroy(a);
        return st;
    }
    *out = a;
    return PELT_OK;
}

/* ---- the cache --------------------------------------------------------- */

static void hash_u64(pelt__atlas_hash *s, uint64_t v) { pelt__atlas_hash_bytes(s, &v, sizeof v); }
static void hash_f32(pelt__atlas_hash *s, float v) { pelt__atlas_hash_bytes(s, &v, sizeof v); }

uint64_t pelt__atlas_key(const pelt_mesh *in, const pelt_atlas_desc *d, unsigned mask_size,
                         float density)
{
    const pelt_mesh_data m = pelt_mesh_get_data(in);
    pelt__atlas_hash s = pelt__atlas_hash_begin();
    hash_u64(&s, PELT__ATLAS_CACHE_VERSION);
    hash_u64(&s, m.vertex_count);
    hash_u64(&s, m.triangle_count);
    pelt__atlas_hash_bytes(&s, m.positions, m.vertex_count * 3 * sizeof(float));
    pelt__atlas_hash_bytes(&s, m.normals, m.vertex_count * 3 * sizeof(float));
    pelt__atlas_hash_bytes(&s, m.uvs, m.vertex_count * 2 * sizeof(float));
    pelt__atlas_hash_bytes(&s, m.indices, m.triangle_count * 3 * sizeof(uint32_t));
    hash_u64(&s, pelt_mesh_get_stats(in).fallback_uvs);
    hash_u64(&s, mask_size);
    hash_f32(&s, density);
    for (int k = 0; k < 3; k++) hash_f32(&s, d->direction[k]);
    hash_u64(&s, d->vertex_directions != NULL);
    if (d->vertex_directions)
        pelt__atlas_hash_bytes(&s, d->vertex_directions, m.vertex_count * 3 * sizeof(float));
    hash_u64(&s, d->seed);
    hash_f32(&s, d->max_stretch);
    hash_u64(&s, (uint64_t)(int64_t)d->mode);
    hash_u64(&s, d->max_patch_faces);
    hash_u64(&s, d->smoothing_iterations);
    return s.h;
}

/* An atlas from a cached record: its arrays copied, its mesh made again
 * from `in` (the record was checked against in's counts). */
static pelt_status atlas_from_record(const pelt_allocator *al, const pelt_mesh *in,
                                     const pelt__atlas_record *r,
                                     pelt_atlas **out, pelt_error *err)
{
    pelt_atlas *a = pelt__atlas_alloc(al, r->vertex_count, r->triangle_count);
    if (!a) return pelt__atlas_fail_oom(err, "atlas arrays");
    size_t vc = r->vertex_count, tc = r->triangle_count;
    memcpy(a->source_vertex, r->source_vertex, vc * sizeof(uint32_t));
    memcpy(a->welded_vertex, r->welded_vertex, vc * sizeof(uint32_t));
    memcpy(a->directions, r->directions, vc * 3 * sizeof(float));
    memcpy(a->weights, r->weights, vc * sizeof(float));
    memcpy(a->triangle_patch, r->triangle_patch, tc * sizeof(uint32_t));
    a->stats = r->stats;
    pelt_status st = make_output_mesh(a, in, r->uvs, r->fur_uvs, r->indices, err);
    if (st != PELT_OK) {
        pelt_atlas_destroy(a);
        return st;
    }
    *out = a;
    return PELT_OK;
}

/* What the cache keeps of a (its mesh still in it). */
static pelt__atlas_record record_of(const pelt_atlas *a)
{
    const pelt_mesh_data m = pelt_mesh_get_data(a->mesh);
    pelt__atlas_record r = {.vertex_count = a->vertex_count,
                            .triangle_count = a->triangle_count,
                            .source_vertex = a->source_vertex,
                            .welded_vertex = a->welded_vertex,
                            .directions = a->directions,
                            .weights = a->weights,
                            .uvs = m.uvs,
                            .fur_uvs = m.fur_uvs,
                            .triangle_patch = a->triangle_patch,
                            .indices = m.indices,
                            .stats = a->stats};
    return r;
}

/* ---- entry points ------------------------------------------------------ */

static void mesh_uv_problem(const pelt_mesh *in, unsigned res, char *why, size_t size,
                            bool *ok)
{
    pelt_atlas_check c;
    *ok = false;
    if (pelt_mesh_get_stats(in).fallback_uvs) {
        snprintf(why, size, "the mesh has no uvs (a fallback map was made)");
        return;
    }
    if (pelt_atlas_check_uvs(in, res, &c, NULL) != PELT_OK) {
        snprintf(why, size, "the mesh uvs could not be checked (out of memory)");
        return;
    }
    if (c.outside)
        snprintf(why, size, "%zu triangles of the mesh uvs leave [0,1]", c.outside);
    else if (c.flipped)
        snprintf(why, size, "%zu triangles of the mesh uvs are flipped (mirrored)", c.flipped);
    else if (c.degenerate)
        snprintf(why, size, "%zu triangles of the mesh uvs have zero area", c.degenerate);
    else if (c.overlap_texels)
        snprintf(why, size, "%zu texels of a %ux%u mask are claimed by two triangles (overlapping uvs)",
                 c.overlap_texels, res, res);
    else
        *ok = true;
}

pelt_status pelt_atlas_create(const pelt_mesh *in, const pelt_atlas_desc *desc,
                              pelt_atlas **out, pelt_error *err)
{
    double t0 = now_seconds();
    if (!in || !out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_atlas_create: mesh and out are required");
    *out = NULL;
    pelt_atlas_desc d = {0};
    if (desc) d = *desc;
    pelt_status hst = pelt__hooks_check(&d.hooks, "pelt_atlas_desc", err);
    if (hst != PELT_OK) return hst;
    const pelt_mesh_data m = pelt_mesh_get_data(in);
    if (m.triangle_count == 0 || m.vertex_count == 0)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_atlas_create: the mesh has no triangles");
    if (m.triangle_count > UINT32_MAX / 3)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_atlas_create: %zu triangles are too many", m.triangle_count);
    /* Every field in its row's range (core/atlas/atlas_params.c); a zero
       stands for the row's default, derived ones below. */
    size_t rows_n;
    const pelt_param *rows = pelt_atlas_params(&rows_n);
    pelt_atlas_desc checked = d;
    pelt__params_defaults(rows, rows_n, &checked);
    if (checked.mask_size == 0) checked.mask_size = 256;
    if (checked.texel_density == 0.0f) checked.texel_density = 1.0f;
    pelt_status pst = pelt__params_check(rows, rows_n, &checked, "pelt_atlas_create:", err);
    if (pst != PELT_OK) return pst;
    unsigned mask = d.mask_size;
    if (mask == 0) {
        mask = 256;
        while (mask < 4096 && (double)mask * mask < (double)m.triangle_count) mask *= 2;
    }
    float density = d.texel_density;
    if (density == 0.0f) {
        float diag = pelt_mesh_diagonal(in);
        density = diag > 0 ? 8.0f / diag : 1.0f;
    }
    float ms = d.max_stretch == 0.0f ? 2.0f : d.max_stretch;
    unsigned cap = d.max_patch_faces ? d.max_patch_faces : 1500;
    if (cap > 1000000) cap = 1000000;
    if (cap > m.triangle_count) cap = (unsigned)m.triangle_count;
    unsigned iters = d.smoothing_iterations ? d.smoothing_iterations : 4;

    bool use_cache = d.cache_dir && d.cache_dir[0];
    uint64_t key = 0;
    if (use_cache) {
        d.max_stretch = ms, d.max_patch_faces = cap, d.smoothing_iterations = iters;
        key = pelt__atlas_key(in, &d, mask, density);
        pelt__atlas_record r;
        char why[128];
        bool hit = pelt__atlas_cache_load(d.cache_dir, key, m.vertex_count, m.triangle_count, &r,
                                          why, sizeof why);
        if (!hit && why[0]) {
            char path[4200];
            pelt__atlas_cache_path(d.cache_dir, key, path, sizeof path);
            pelt__log(&d.hooks.logger, PELT_LOG_WARNING, "atlas cache '%s' %s; building the atlas again",
                      path, why);
        }
        if (hit) {
            pelt_atlas *cached = NULL;
            pelt_status st = atlas_from_record(&d.hooks.allocator, in, &r, &cached, err);
            pelt__atlas_record_free(&r);
            if (st != PELT_OK) return st;
            cached->stats.from_cache = true;
            cached->stats.build_seconds = now_seconds() - t0;
            *out = cached;
            return PELT_OK;
        }
    }

    pelt__atlas_builder b = {0};
    b.alloc = d.hooks.allocator;
    b.in = m;
    b.vc = m.vertex_count, b.tc = m.triangle_count, b.cap = cap, b.max_stretch = ms;
    if (!builder_alloc(&b)) {
        builder_free(&b);
        return pelt__atlas_fail_oom(err, "atlas builder");
    }
    pelt_status st = PELT_OK;
    if (!pelt__weld(m.positions, NULL, b.vc, b.canon) ||
        !pelt__direction_field(m.positions, m.normals, b.vc, m.indices, b.tc, b.canon,
                               d.direction, d.vertex_directions, iters, b.dir, b.weight)) {
        builder_free(&b);
        return pelt__atlas_fail_oom(err, "direction field");
    }
    char why[256] = "";
    bool uvs_ok = false;
    if (d.mode != PELT_ATLAS_PATCHES) mesh_uv_problem(in, mask, why, sizeof why, &uvs_ok);
    pelt_atlas *a = NULL;
    if (d.mode == PELT_ATLAS_MESH_UVS || (d.mode == PELT_ATLAS_AUTO && uvs_ok))
        st = build_mesh_uvs(&d.hooks.allocator, in, density, b.dir, b.weight, b.canon, &a, err);
    else
        st = build_patches(in, &b, mask, density, d.seed, &a, err);
    builder_free(&b);
    if (st != PELT_OK) return st;
    snprintf(a->stats.uv_warning, sizeof a->stats.uv_warning, "%s", uvs_ok ? "" : why);
    if (!uvs_ok && d.mode == PELT_ATLAS_AUTO)
        pelt__log(&d.hooks.logger, PELT_LOG_WARNING, "not using the mesh's uvs: %s; grew %zu patches",
                  why, a->stats.patch_count);
    else if (!uvs_ok && d.mode == PELT_ATLAS_MESH_UVS)
        pelt__log(&d.hooks.logger, PELT_LOG_WARNING, "using the mesh's uvs although %s", why);
    a->stats.mask_size = mask;
    a->stats.texel_density = density;
    a->stats.build_seconds = now_seconds() - t0;
    if (use_cache) { /* best effort */
        pelt__atlas_record r = record_of(a);
        pelt__atlas_cache_store(d.cache_dir, key, &r);
    }
    *out = a;
    return PELT_OK;
}

pelt_status pelt_atlas_build(const pelt_mesh *in, const pelt_atlas_desc *desc,
                             pelt_mesh **out_mesh, pelt_atlas_stats *stats, pelt_error *err)
{
    if (!out_mesh) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_atlas_build: out_mesh is required");
    *out_mesh = NULL;
    pelt_atlas *a = NULL;
    pelt_status st = pelt_atlas_create(in, desc, &a, err);
    if (st != PELT_OK) return st;
    if (stats) *stats = a->stats;
    *out_mesh = pelt_atlas_take_mesh(a);
    pelt_atlas_destroy(a);
    return PELT_OK;
}
