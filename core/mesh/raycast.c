/* Closest-hit ray casts over a mesh through a BVH (binned SAH). */
#include "core/mesh/raycast.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/mesh/mesh_internal.h"
#include "core/base/vec.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BINS 16
#define LEAF_FORCE 32    /* never keep a leaf bigger than this */
#define STACK_MAX 64

/* Interior: count == 0, children at first and first + 1.
 * Leaf: triangles [first, first + count) of the reordered arrays. */
typedef struct bvh_node {
    float lo[3], hi[3];
    uint32_t first, count;
} bvh_node;

/* A triangle as Moller-Trumbore wants it: a vertex and two edges. */
typedef struct bvh_tri {
    float v0[3], e1[3], e2[3];
} bvh_tri;

struct pelt__bvh {
    pelt_allocator alloc; /* the owner's; every array comes from it */
    bvh_node *nodes;
    size_t node_count;
    bvh_tri *tris;     /* in leaf order */
    uint32_t *source;  /* leaf order -> mesh triangle index */
    size_t tri_count;
    unsigned depth;
};

static bvh_tri make_tri(const pelt_mesh *mesh, size_t t)
{
    const uint32_t *ix = mesh->indices + t * 3;
    pelt_vec3 p0 = v3_load(mesh->positions + (size_t)ix[0] * 3);
    pelt_vec3 p1 = v3_load(mesh->positions + (size_t)ix[1] * 3);
    pelt_vec3 p2 = v3_load(mesh->positions + (size_t)ix[2] * 3);
    bvh_tri r;
    v3_store(r.v0, p0);
    v3_store(r.e1, v3_sub(p1, p0));
    v3_store(r.e2, v3_sub(p2, p0));
    return r;
}

/* Moller & Trumbore 1997: t along the ray and (u, v) weights of vertices
 * 1 and 2 when the ray hits the triangle with t in (0, best). */
static bool hit_tri(const bvh_tri *tr, pelt_vec3 o, pelt_vec3 d, float best,
                    float *t_out, float *u_out, float *v_out)
{
    pelt_vec3 e1 = v3_load(tr->e1), e2 = v3_load(tr->e2);
    pelt_vec3 pv = v3_cross(d, e2);
    float det = v3_dot(e1, pv);
    if (fabsf(det) < 1e-30f) return false; /* ray parallel to the plane */
    float inv = 1.0f / det;
    pelt_vec3 tv = v3_sub(o, v3_load(tr->v0));
    float u = v3_dot(tv, pv) * inv;
    if (!(u >= 0.0f && u <= 1.0f)) return false;
    pelt_vec3 qv = v3_cross(tv, e1);
    float v = v3_dot(d, qv) * inv;
    if (!(v >= 0.0f && u + v <= 1.0f)) return false;
    float t = v3_dot(e2, qv) * inv;
    if (!(t > 0.0f && t < best)) return false;
    *t_out = t;
    *u_out = u;
    *v_out = v;
    return true;
}

/* Plain comparisons: fminf/fmaxf are library calls on x86-64 and no NaN
 * reaches these (positions are validated finite, parallel axes skipped). */
static inline float min2(float a, float b) { return a < b ? a : b; }
static inline float max2(float a, float b) { return a > b ? a : b; }

static float box_area(const float lo[3], const float hi[3])
{
    float x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
    if (x < 0.0f) return 0.0f; /* empty box */
    return 2.0f * (x * y + y * z + z * x);
}

static void box_empty(float lo[3], float hi[3])
{
    for (int a = 0; a < 3; a++) {
        lo[a] = FLT_MAX;
        hi[a] = -FLT_MAX;
    }
}

static void box_grow(float lo[3], float hi[3], const float blo[3], const float bhi[3])
{
    for (int a = 0; a < 3; a++) {
        lo[a] = min2(lo[a], blo[a]);
        hi[a] = max2(hi[a], bhi[a]);
    }
}

typedef struct build_ctx {
    const float *tlo, *thi, *cen; /* per mesh triangle: box and centroid */
    uint32_t *idx;                /* mesh triangle indices, partitioned */
    bvh_node *nodes;
    size_t node_count;
} build_ctx;

typedef struct build_item {
    uint32_t node, begin, end;
    unsigned depth;
} build_item;

/* Bin index of centroid c on an axis spanning [lo, lo + ext). */
static int bin_of(float c, float lo, float scale)
{
    int b = (int)((c - lo) * scale);
    return b < 0 ? 0 : (b >= BINS ? BINS - 1 : b);
}

/* Splits [begin, end) by binned SAH (Wald 2007); returns the split point or
 * begin when the node should stay a leaf. */
static uint32_t split_node(build_ctx *c, const bvh_node *n, uint32_t begin, uint32_t end)
{
    uint32_t count = end - begin;
    if (count <= 1) return begin;
    float clo[3], chi[3];
    box_empty(clo, chi);
    for (uint32_t i = begin; i < end; i++) {
        const float *p = c->cen + (size_t)c->idx[i] * 3;
        box_grow(clo, chi, p, p);
    }
    /* One pass bins every triangle on all three axes at once. */
    float scale[3];
    uint32_t bcount[3][BINS] = {{0}};
    float blo[3][BINS][3], bhi[3][BINS][3];
    for (int a = 0; a < 3; a++) {
        float ext = chi[a] - clo[a];
        scale[a] = ext > 0.0f ? (float)BINS / ext : 0.0f;
        for (int b = 0; b < BINS; b++) box_empty(blo[a][b], bhi[a][b]);
    }
    for (uint32_t i = begin; i < end; i++) {
        uint32_t t = c->idx[i];
        const float *lo = c->tlo + (size_t)t * 3, *hi = c->thi + (size_t)t * 3;
        const float *ce = c->cen + (size_t)t * 3;
        for (int a = 0; a < 3; a++) {
            int b = bin_of(ce[a], clo[a], scale[a]);
            bcount[a][b]++;
            box_grow(blo[a][b], bhi[a][b], lo, hi);
        }
    }
    float best_cost = FLT_MAX;
    int best_axis = -1, best_split = 0;
    for (int a = 0; a < 3; a++) {
        if (scale[a] == 0.0f) continue; /* all centroids in one plane */
        /* Sweep from the right, then from the left, to cost each plane. */
        float rarea[BINS];
        uint32_t rcount[BINS];
        float lo[3], hi[3];
        box_empty(lo, hi);
        uint32_t acc = 0;
        for (int b = BINS - 1; b > 0; b--) {
            box_grow(lo, hi, blo[a][b], bhi[a][b]);
            acc += bcount[a][b];
            rarea[b] = box_area(lo, hi);
            rcount[b] = acc;
        }
        box_empty(lo, hi);
        acc = 0;
        for (int b = 0; b < BINS - 1; b++) {
            box_grow(lo, hi, blo[a][b], bhi[a][b]);
            acc += bcount[a][b];
            if (acc == 0 || rcount[b + 1] == 0) continue;
            float cost = box_area(lo, hi) * (float)acc + rarea[b + 1] * (float)rcount[b + 1];
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = a;
                best_split = b + 1;
            }
        }
    }
    float node_area = box_area(n->lo, n->hi);
    /* SAH: traversal costs about one triangle test. */
    bool leaf_cheaper = best_axis < 0 ||
                        (node_area > 0.0f && 1.0f + best_cost / node_area >= (float)count);
    if (leaf_cheaper && count <= LEAF_FORCE) return begin;
    if (best_axis < 0) return begin + count / 2; /* coincident centroids: halve */
    uint32_t i = begin, j = end;
    while (i < j) {
        uint32_t t = c->idx[i];
        if (bin_of(c->cen[(size_t)t * 3 + best_axis], clo[best_axis], scale[best_axis]) <
            best_split) {
            i++;
        } else {
            c->idx[i] = c->idx[--j];
            c->idx[j] = t;
        }
    }
    if (i == begin || i == end) return begin + count / 2;
    return i;
}

static void node_bounds(build_ctx *c, bvh_node *n, uint32_t begin, uint32_t end)
{
    box_empty(n->lo, n->hi);
    for (uint32_t i = begin; i < end; i++) {
        uint32_t t = c->idx[i];
        box_grow(n->lo, n->hi, c->tlo + (size_t)t * 3, c->thi + (size_t)t * 3);
    }
}

pelt_status pelt__bvh_build(const pelt_mesh *mesh, const pelt_allocator *alloc, pelt__bvh **out,
                            pelt_error *err)
{
    if (!mesh || !out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "bvh: NULL argument");
    *out = NULL;
    size_t n = mesh->triangle_count;
    if (n == 0) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "bvh: mesh has no triangles");
    if (n > UINT32_MAX / 2)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "bvh: %zu triangles is too many", n);
    pelt__bvh *bvh = pelt__alloc_zero(alloc, 1, sizeof *bvh);
    if (bvh && alloc) bvh->alloc = *alloc;
    float *tlo = pelt__alloc_zero(alloc, n * 3, sizeof(float));
    float *thi = pelt__alloc_zero(alloc, n * 3, sizeof(float));
    float *cen = pelt__alloc_zero(alloc, n * 3, sizeof(float));
    uint32_t *idx = pelt__alloc_zero(alloc, n, sizeof *idx);
    build_item *stack = pelt__alloc_zero(alloc, n, sizeof *stack);
    if (bvh) {
        bvh->nodes = pelt__alloc_zero(alloc, 2 * n, sizeof *bvh->nodes);
        bvh->tris = pelt__alloc_zero(alloc, n, sizeof *bvh->tris);
        bvh->source = pelt__alloc_zero(alloc, n, sizeof *bvh->source);
    }
    if (!bvh || !tlo || !thi || !cen || !idx || !stack || !bvh->nodes || !bvh->tris ||
        !bvh->source) {
        pelt__free(alloc, tlo);
        pelt__free(alloc, thi);
        pelt__free(alloc, cen);
        pelt__free(alloc, idx);
        pelt__free(alloc, stack);
        pelt__bvh_destroy(bvh);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "bvh: out of memory for %zu triangles", n);
    }
    for (size_t t = 0; t < n; t++) {
        const uint32_t *ix = mesh->indices + t * 3;
        box_empty(tlo + t * 3, thi + t * 3);
        for (int k = 0; k < 3; k++) {
            const float *p = mesh->positions + (size_t)ix[k] * 3;
            box_grow(tlo + t * 3, thi + t * 3, p, p);
        }
        for (int a = 0; a < 3; a++) cen[t * 3 + a] = 0.5f * (tlo[t * 3 + a] + thi[t * 3 + a]);
        idx[t] = (uint32_t)t;
    }

    build_ctx c = {tlo, thi, cen, idx, bvh->nodes, 1};
    size_t top = 0;
    stack[top++] = (build_item){0, 0, (uint32_t)n, 1};
    unsigned depth = 0;
    while (top > 0) {
        build_item it = stack[--top];
        bvh_node *node = &c.nodes[it.node];
        node_bounds(&c, node, it.begin, it.end);
        if (it.depth > depth) depth = it.depth;
        /* Cap the depth so traversal's fixed stack always suffices. */
        uint32_t mid = it.depth + 2 >= STACK_MAX ? it.begin
                                                 : split_node(&c, node, it.begin, it.end);
        if (mid == it.begin || mid == it.end) {
            node->first = it.begin;
            node->count = it.end - it.begin;
            continue;
        }
        uint32_t left = (uint32_t)c.node_count;
        c.node_count += 2;
        node->first = left;
        node->count = 0;
        /* At most one pending item per open subtree level: n suffices. */
        stack[top++] = (build_item){left + 1, mid, it.end, it.depth + 1};
        stack[top++] = (build_item){left, it.begin, mid, it.depth + 1};
    }
    for (size_t i = 0; i < n; i++) {
        bvh->source[i] = idx[i];
        bvh->tris[i] = make_tri(mesh, idx[i]);
    }
    /* 2n nodes was the worst case; give back what the tree did not use. */
    bvh_node *fit = pelt__alloc(alloc, c.node_count * sizeof *bvh->nodes);
    if (fit) {
        memcpy(fit, bvh->nodes, c.node_count * sizeof *bvh->nodes);
        pelt__free(alloc, bvh->nodes);
        bvh->nodes = fit;
    }
    bvh->node_count = c.node_count;
    bvh->tri_count = n;
    bvh->depth = depth;
    pelt__free(alloc, tlo);
    pelt__free(alloc, thi);
    pelt__free(alloc, cen);
    pelt__free(alloc, idx);
    pelt__free(alloc, stack);
    *out = bvh;
    return PELT_OK;
}

void pelt__bvh_destroy(pelt__bvh *bvh)
{
    if (!bvh) return;
    pelt_allocator a = bvh->alloc;
    pelt__free(&a, bvh->nodes);
    pelt__free(&a, bvh->tris);
    pelt__free(&a, bvh->source);
    pelt__free(&a, bvh);
}

void pelt__bvh_stats(const pelt__bvh *bvh, size_t *nodes, unsigned *depth)
{
    if (nodes) *nodes = bvh->node_count;
    if (depth) *depth = bvh->depth;
}

/* Slab test: entry distance of the ray into the box, or +inf on a miss.
 * An axis the ray runs parallel to (inv = inf) only checks the origin, so
 * no 0 * inf NaN reaches the comparisons. */
static float box_enter(const bvh_node *n, const float o[3], const float inv[3], float best)
{
    float t0 = 0.0f, t1 = best;
    for (int a = 0; a < 3; a++) {
        if (isinf(inv[a])) {
            if (o[a] < n->lo[a] || o[a] > n->hi[a]) return INFINITY;
            continue;
        }
        float ta = (n->lo[a] - o[a]) * inv[a], tb = (n->hi[a] - o[a]) * inv[a];
        t0 = max2(t0, min2(ta, tb));
        t1 = min2(t1, max2(ta, tb));
    }
    return t0 <= t1 ? t0 : INFINITY;
}

static bool valid_ray(const float o[3], const float d[3], float t_max)
{
    for (int a = 0; a < 3; a++)
        if (!isfinite(o[a]) || !isfinite(d[a])) return false;
    return !isnan(t_max) && t_max > 0.0f && (d[0] != 0.0f || d[1] != 0.0f || d[2] != 0.0f);
}

static void fill_hit(pelt__hit *hit, size_t tri, float t, float u, float v)
{
    hit->triangle = tri;
    hit->t = t;
    hit->bary[0] = 1.0f - u - v;
    hit->bary[1] = u;
    hit->bary[2] = v;
}

bool pelt__bvh_raycast(const pelt__bvh *bvh, const float origin[3],
                       const float dir[3], float t_max, pelt__hit *hit)
{
    if (!bvh || !valid_ray(origin, dir, t_max)) return false;
    pelt_vec3 o = v3_load(origin), d = v3_load(dir);
    float inv[3] = {1.0f / dir[0], 1.0f / dir[1], 1.0f / dir[2]};
    /* Strict test in hit_tri takes t < best, so allow t == t_max. */
    float best = nextafterf(t_max, INFINITY);
    float bu = 0.0f, bv = 0.0f;
    size_t found = SIZE_MAX;
    uint32_t stack[STACK_MAX];
    int top = 0;
    if (box_enter(&bvh->nodes[0], origin, inv, best) == INFINITY) return false;
    stack[top++] = 0;
    while (top > 0) {
        const bvh_node *n = &bvh->nodes[stack[--top]];
        if (n->count > 0) {
            for (uint32_t i = n->first; i < n->first + n->count; i++) {
                float t, u, v;
                if (hit_tri(&bvh->tris[i], o, d, best, &t, &u, &v)) {
                    best = t;
                    bu = u;
                    bv = v;
                    found = i;
                }
            }
            continue;
        }
        /* Visit the nearer child first; skip children beyond the best hit. */
        uint32_t a = n->first, b = n->first + 1;
        float ta = box_enter(&bvh->nodes[a], origin, inv, best);
        float tb = box_enter(&bvh->nodes[b], origin, inv, best);
        if (ta > tb) {
            uint32_t s = a;
            a = b;
            b = s;
            float f = ta;
            ta = tb;
            tb = f;
        }
        /* The build caps the depth below STACK_MAX - 1, so these fit. */
        if (tb != INFINITY) stack[top++] = b;
        if (ta != INFINITY) stack[top++] = a;
    }
    if (found == SIZE_MAX) return false;
    fill_hit(hit, bvh->source[found], best, bu, bv);
    return true;
}

/* Squared distance from c to the box [lo, hi]. */
static float box_distance2(const float lo[3], const float hi[3], const float c[3])
{
    float d2 = 0.0f;
    for (int k = 0; k < 3; k++) {
        float e = c[k] < lo[k] ? lo[k] - c[k] : c[k] > hi[k] ? c[k] - hi[k] : 0.0f;
        d2 += e * e;
    }
    return d2;
}

size_t pelt__bvh_query_ball(const pelt__bvh *bvh, const float center[3], float radius,
                            void (*visit)(size_t triangle, void *user), void *user)
{
    if (!bvh || !visit || !(radius >= 0.0f) || !isfinite(radius) || !isfinite(center[0]) ||
        !isfinite(center[1]) || !isfinite(center[2]))
        return 0;
    float r2 = radius * radius;
    size_t visited = 0;
    uint32_t stack[STACK_MAX];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const bvh_node *n = &bvh->nodes[stack[--top]];
        if (box_distance2(n->lo, n->hi, center) > r2) continue;
        if (n->count == 0) {
            stack[top++] = n->first;
            stack[top++] = n->first + 1;
            continue;
        }
        for (uint32_t i = n->first; i < n->first + n->count; i++) {
            const bvh_tri *t = &bvh->tris[i];
            float lo[3], hi[3];
            for (int k = 0; k < 3; k++) {
                float a = t->v0[k], b = a + t->e1[k], c = a + t->e2[k];
                lo[k] = fminf(a, fminf(b, c));
                hi[k] = fmaxf(a, fmaxf(b, c));
            }
            if (box_distance2(lo, hi, center) > r2) continue;
            visit(bvh->source[i], user);
            visited++;
        }
    }
    return visited;
}

bool pelt__raycast_brute(const pelt_mesh *mesh, const float origin[3],
                         const float dir[3], float t_max, pelt__hit *hit)
{
    if (!mesh || !valid_ray(origin, dir, t_max)) return false;
    pelt_vec3 o = v3_load(origin), d = v3_load(dir);
    float best = nextafterf(t_max, INFINITY), bu = 0.0f, bv = 0.0f;
    size_t found = SIZE_MAX;
    for (size_t i = 0; i < mesh->triangle_count; i++) {
        bvh_tri tr = make_tri(mesh, i);
        float t, u, v;
        if (hit_tri(&tr, o, d, best, &t, &u, &v)) {
            best = t;
            bu = u;
            bv = v;
            found = i;
        }
    }
    if (found == SIZE_MAX) return false;
    fill_hit(hit, found, best, bu, bv);
    return true;
}
