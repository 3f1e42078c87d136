/* Surface atlas from patches: Lengyel et al. §2.1 (lapped textures with
 * patch borders on mesh edges, no overlap), each patch flattened by a
 * least-squares conformal map (Lévy et al. 2002) solved with preconditioned
 * CGLS, aligned to the direction field (§3) and packed with stb_rect_pack. */
#include "core/atlas/atlas.h"

#include "core/atlas/direction_field.h"
#include "core/base/error.h"
#include "core/mesh/mesh_internal.h"
#include "core/base/rng.h"
#include "core/base/vec.h"
#include "core/base/weld.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <stb/stb_rect_pack.h>

#define NONE UINT32_MAX
#define CONE_COS 0.34202014f  /* cos 70°: a patch never wraps around a tube */
#define FIELD_COS 0.81915204f /* cos 35°: the field turns little inside a patch */
#define CG_MAX_ITERATIONS 400
#define CG_TOLERANCE 1e-7    /* on |A^T r| relative to its start */

static double now_seconds(void)
{
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- the result object ------------------------------------------------- */

pelt_atlas *pelt__atlas_alloc(size_t vertex_count, size_t triangle_count)
{
    pelt_atlas *a = pelt__calloc(1, sizeof *a);
    if (!a) return NULL;
    a->vertex_count = vertex_count;
    a->triangle_count = triangle_count;
    a->source_vertex = pelt__calloc(vertex_count, sizeof(uint32_t));
    a->welded_vertex = pelt__calloc(vertex_count, sizeof(uint32_t));
    a->triangle_patch = pelt__calloc(triangle_count, sizeof(uint32_t));
    a->directions = pelt__calloc(vertex_count, 3 * sizeof(float));
    a->weights = pelt__calloc(vertex_count, sizeof(float));
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
    free(a->source_vertex);
    free(a->welded_vertex);
    free(a->triangle_patch);
    free(a->directions);
    free(a->weights);
    free(a);
}

const pelt_mesh *pelt_atlas_mesh(const pelt_atlas *a) { return a ? a->mesh : NULL; }
pelt_mesh *pelt_atlas_take_mesh(pelt_atlas *a)
{
    if (!a) return NULL;
    pelt_mesh *m = a->mesh;
    a->mesh = NULL;
    /* The direction field goes with the mesh as the comb direction, scaled
     * by its weight, so the renderer combs along the field and stands the
     * fur up where it vanishes. */
    if (m && a->directions && a->weights && !m->comb) {
        m->comb = pelt__calloc(m->vertex_count, 3 * sizeof(float));
        for (size_t i = 0; m->comb && i < m->vertex_count; i++)
            for (int k = 0; k < 3; k++) m->comb[3 * i + k] = a->directions[3 * i + k] * a->weights[i];
    }
    return m;
}
const pelt_atlas_stats *pelt_atlas_get_stats(const pelt_atlas *a) { return a ? &a->stats : NULL; }
size_t pelt_atlas_vertex_count(const pelt_atlas *a) { return a ? a->vertex_count : 0; }
const uint32_t *pelt_atlas_source_vertices(const pelt_atlas *a) { return a ? a->source_vertex : NULL; }
const uint32_t *pelt_atlas_welded_vertices(const pelt_atlas *a) { return a ? a->welded_vertex : NULL; }
const uint32_t *pelt_atlas_triangle_patches(const pelt_atlas *a) { return a ? a->triangle_patch : NULL; }
const float *pelt_atlas_directions(const pelt_atlas *a) { return a ? a->directions : NULL; }
const float *pelt_atlas_direction_weights(const pelt_atlas *a) { return a ? a->weights : NULL; }

static int compare_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

/* ---- mesh topology ----------------------------------------------------- */

typedef struct half_edge { uint32_t lo, hi, corner; } half_edge; /* corner = 3 * face + k */

static int compare_half_edge(const void *pa, const void *pb)
{
    const half_edge *a = pa, *b = pb;
    if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
    return (a->corner > b->corner) - (a->corner < b->corner);
}

/* adj[3f+k] = the face across edge (k, k+1) of f, or NONE on a border, a
 * non-manifold edge or an orientation flip (patches never cross those). */
static bool face_adjacency(const pelt_mesh *m, const uint32_t *canon, uint32_t *adj)
{
    size_t n = m->triangle_count * 3;
    half_edge *h = pelt__calloc(n, sizeof *h);
    if (!h) return false;
    for (size_t c = 0; c < n; c++) {
        size_t f = c / 3, k = c % 3;
        uint32_t a = canon[m->indices[c]], b = canon[m->indices[3 * f + (k + 1) % 3]];
        h[c].lo = a < b ? a : b;
        h[c].hi = a < b ? b : a;
        h[c].corner = (uint32_t)c;
        adj[c] = NONE;
    }
    qsort(h, n, sizeof *h, compare_half_edge);
    for (size_t b = 0; b < n;) {
        size_t e = b + 1;
        while (e < n && h[e].lo == h[b].lo && h[e].hi == h[b].hi) e++;
        if (e - b == 2) {
            uint32_t c0 = h[b].corner, c1 = h[b + 1].corner;
            uint32_t s0 = canon[m->indices[c0]], s1 = canon[m->indices[c1]];
            if (s0 != s1 && c0 / 3 != c1 / 3) { /* opposite traversal = consistent orientation */
                adj[c0] = c1 / 3;
                adj[c1] = c0 / 3;
            }
        }
        b = e;
    }
    free(h);
    return true;
}

/* ---- builder state ----------------------------------------------------- */

typedef struct heap_item { float d; uint32_t f; } heap_item;

typedef struct builder {
    const pelt_mesh *in;
    size_t vc, tc;
    unsigned cap;
    float max_stretch;
    uint32_t *canon, *adj, *face_patch;
    float *dir, *weight;       /* per input vertex */
    float *fnormal, *fcent;    /* 3 per face */
    /* growth */
    uint32_t *order, *face_stamp, *face_done, gen;
    float *dist;
    heap_item *heap;
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
} builder;

static void builder_free(builder *b)
{
    void *ptrs[] = {b->canon, b->adj, b->face_patch, b->dir, b->weight, b->fnormal, b->fcent,
                    b->order, b->face_stamp, b->face_done, b->dist, b->heap, b->local_of,
                    b->local_stamp, b->lverts, b->tri_local, b->coef, b->frame, b->X, b->r,
                    b->q, b->s, b->p, b->t, b->colscale, b->claims, b->out_source,
                    b->out_patch, b->out_index, b->vert_stamp, b->vert_out, b->out_local,
                    b->patch_box};
    for (size_t i = 0; i < sizeof ptrs / sizeof ptrs[0]; i++) free(ptrs[i]);
}

static bool builder_alloc(builder *b)
{
    size_t vc = b->vc, tc = b->tc, cap = b->cap, lv = 3 * (size_t)cap;
    b->canon = pelt__calloc(vc, sizeof(uint32_t));
    b->adj = pelt__calloc(tc, 3 * sizeof(uint32_t));
    b->face_patch = pelt__calloc(tc, sizeof(uint32_t));
    b->dir = pelt__calloc(vc, 3 * sizeof(float));
    b->weight = pelt__calloc(vc, sizeof(float));
    b->fnormal = pelt__calloc(tc, 3 * sizeof(float));
    b->fcent = pelt__calloc(tc, 3 * sizeof(float));
    b->order = pelt__calloc(cap, sizeof(uint32_t));
    b->face_stamp = pelt__calloc(tc, sizeof(uint32_t));
    b->face_done = pelt__calloc(tc, sizeof(uint32_t));
    b->dist = pelt__calloc(tc, sizeof(float));
    b->heap = pelt__calloc(lv + 4, sizeof(heap_item));
    b->local_of = pelt__calloc(vc, sizeof(uint32_t));
    b->local_stamp = pelt__calloc(vc, sizeof(uint32_t));
    b->lverts = pelt__calloc(lv, sizeof(uint32_t));
    b->tri_local = pelt__calloc(lv, sizeof(uint32_t));
    b->coef = pelt__calloc(cap, 6 * sizeof(double));
    b->frame = pelt__calloc(cap, 3 * sizeof(double));
    b->X = pelt__calloc(lv, 2 * sizeof(double));
    b->r = pelt__calloc(cap, 2 * sizeof(double));
    b->q = pelt__calloc(cap, 2 * sizeof(double));
    b->s = pelt__calloc(lv, 2 * sizeof(double));
    b->p = pelt__calloc(lv, 2 * sizeof(double));
    b->t = pelt__calloc(lv, 2 * sizeof(double));
    b->colscale = pelt__calloc(lv, 2 * sizeof(double));
    b->claims_res = 1024;
    b->claims = pelt__calloc((size_t)b->claims_res * b->claims_res, 1);
    b->out_source = pelt__calloc(tc, 3 * sizeof(uint32_t));
    b->out_patch = pelt__calloc(tc, 3 * sizeof(uint32_t));
    b->out_index = pelt__calloc(tc, 3 * sizeof(uint32_t));
    b->vert_stamp = pelt__calloc(vc, sizeof(uint32_t));
    b->vert_out = pelt__calloc(vc, sizeof(uint32_t));
    b->out_local = pelt__calloc(tc, 6 * sizeof(float));
    b->patch_box = pelt__calloc(tc, 4 * sizeof(float));
    return b->canon && b->adj && b->face_patch && b->dir && b->weight && b->fnormal &&
           b->fcent && b->order && b->face_stamp && b->face_done && b->dist && b->heap &&
           b->local_of && b->local_stamp && b->lverts && b->tri_local && b->coef &&
           b->frame && b->X && b->r && b->q && b->s && b->p && b->t && b->colscale &&
           b->claims && b->out_source && b->out_patch && b->out_index && b->vert_stamp &&
           b->vert_out && b->out_local && b->patch_box;
}

static pelt_vec3 vpos(const builder *b, uint32_t v) { return v3_load(b->in->positions + 3 * v); }

/* Unit field direction of face f in 3D scaled by its mean weight. */
static pelt_vec3 face_field(const builder *b, uint32_t f)
{
    pelt_vec3 s = v3(0, 0, 0);
    for (int k = 0; k < 3; k++) {
        uint32_t v = b->in->indices[3 * f + k];
        s = v3_mad(s, v3_load(b->dir + 3 * v), b->weight[v] / 3.0f);
    }
    return s;
}

/* ---- growth: Dijkstra over faces from the seed (a round "splotch") ------ */

static void heap_push(builder *b, float d, uint32_t f)
{
    size_t i = b->heap_n++;
    while (i > 0) {
        size_t parent = (i - 1) / 2;
        if (b->heap[parent].d <= d) break;
        b->heap[i] = b->heap[parent];
        i = parent;
    }
    b->heap[i].d = d;
    b->heap[i].f = f;
}

static heap_item heap_pop(builder *b)
{
    heap_item top = b->heap[0], last = b->heap[--b->heap_n];
    size_t i = 0;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= b->heap_n) break;
        if (c + 1 < b->heap_n && b->heap[c + 1].d < b->heap[c].d) c++;
        if (b->heap[c].d >= last.d) break;
        b->heap[i] = b->heap[c];
        i = c;
    }
    if (b->heap_n) b->heap[i] = last;
    return top;
}

/* Fills b->order with up to cap uncovered faces by distance from seed,
 * inside a normal cone around the seed's normal; returns the count. Every
 * prefix of the order is edge-connected. */
static size_t grow(builder *b, uint32_t seed)
{
    uint32_t gen = ++b->gen;
    size_t n = 0;
    pelt_vec3 n0 = v3_load(b->fnormal + 3 * seed);
    pelt_vec3 f0 = face_field(b, seed);
    float w0 = v3_len(f0);
    b->heap_n = 0;
    b->dist[seed] = 0.0f;
    b->face_stamp[seed] = gen;
    heap_push(b, 0.0f, seed);
    while (b->heap_n && n < b->cap) {
        heap_item it = heap_pop(b);
        uint32_t f = it.f;
        if (b->face_done[f] == gen || it.d > b->dist[f]) continue;
        b->face_done[f] = gen;
        b->order[n++] = f;
        for (int k = 0; k < 3; k++) {
            uint32_t g = b->adj[3 * f + k];
            if (g == NONE || b->face_patch[g] != NONE || b->face_done[g] == gen) continue;
            if (v3_dot(v3_load(b->fnormal + 3 * g), n0) < CONE_COS) continue;
            /* Where both faces are combed, keep their directions close so one
             * rotation aligns the whole patch (Lengyel §2.1). */
            pelt_vec3 fg = face_field(b, g);
            float wg = v3_len(fg);
            if (w0 > 0.5f && wg > 0.5f && v3_dot(fg, f0) < FIELD_COS * w0 * wg) continue;
            float d = it.d + v3_len(v3_sub(v3_load(b->fcent + 3 * g), v3_load(b->fcent + 3 * f)));
            if (b->face_stamp[g] != gen || d < b->dist[g]) {
                b->face_stamp[g] = gen;
                b->dist[g] = d;
                if (b->heap_n < 3 * (size_t)b->cap + 3) heap_push(b, d, g);
            }
        }
    }
    return n;
}

/* ---- flattening: least-squares conformal map -------------------------- */

/* Per triangle i (local frame P0 = 0, P1 = (x1, 0), P2 = (x2, y2)) the
 * conformal residual grad u - rot(grad v) (Lévy et al. 2002, Eq. 3, as
 * written for an orientation-preserving map) is two rows of A:
 *   row1 = sum_j w(-ey_j u_j - ex_j v_j),  row2 = sum_j w(ex_j u_j - ey_j v_j)
 * with e_j = P_{j+2} - P_{j+1} and w = 1 / (2 sqrt(area)). */
static void apply_a(const builder *b, size_t n, const double *x, double *out)
{
    for (size_t i = 0; i < n; i++) {
        const double *c = b->coef + 6 * i;
        double r1 = 0, r2 = 0;
        for (int j = 0; j < 3; j++) {
            uint32_t l = b->tri_local[3 * i + j];
            double u = x[2 * l], v = x[2 * l + 1], ex = c[2 * j], ey = c[2 * j + 1];
            r1 += -ey * u - ex * v;
            r2 += ex * u - ey * v;
        }
        out[2 * i] = r1;
        out[2 * i + 1] = r2;
    }
}

static void apply_at(const builder *b, size_t n, size_t nl, const double *rows, double *out)
{
    memset(out, 0, nl * 2 * sizeof(double));
    for (size_t i = 0; i < n; i++) {
        const double *c = b->coef + 6 * i;
        double r1 = rows[2 * i], r2 = rows[2 * i + 1];
        for (int j = 0; j < 3; j++) {
            uint32_t l = b->tri_local[3 * i + j];
            double ex = c[2 * j], ey = c[2 * j + 1];
            out[2 * l] += -ey * r1 + ex * r2;
            out[2 * l + 1] += -ex * r1 - ey * r2;
        }
    }
}

static double dot(const double *a, const double *c, size_t n)
{
    double s = 0;
    for (size_t i = 0; i < n; i++) s += a[i] * c[i];
    return s;
}

/* Flattens the first n faces of b->order into b->X (per local vertex);
 * returns the local vertex count. */
static size_t flatten(builder *b, size_t n)
{
    const pelt_mesh *m = b->in;
    uint32_t lgen = ++b->lgen;
    size_t nl = 0;
    for (size_t i = 0; i < n; i++) {
        uint32_t f = b->order[i];
        for (int k = 0; k < 3; k++) {
            uint32_t c = b->canon[m->indices[3 * f + k]];
            if (b->local_stamp[c] != lgen) {
                b->local_stamp[c] = lgen;
                b->local_of[c] = (uint32_t)nl;
                b->lverts[nl++] = c;
            }
            b->tri_local[3 * i + k] = b->local_of[c];
        }
    }
    /* Start from the projection on the seed's tangent plane, x along the
     * field: already near-conformal for a patch inside the normal cone. */
    uint32_t seed = b->order[0];
    pelt_vec3 n0 = v3_load(b->fnormal + 3 * seed);
    pelt_vec3 fld = face_field(b, seed);
    fld = v3_sub(fld, v3_scale(n0, v3_dot(n0, fld)));
    float fb[3];
    pelt__any_tangent(b->fnormal + 3 * seed, fb);
    pelt_vec3 t0 = v3_norm_or(fld, v3_load(fb)), b0 = v3_cross(n0, t0);
    pelt_vec3 origin = vpos(b, b->lverts[0]);
    double *X = b->X;
    size_t far = 0;
    double far_d = -1;
    for (size_t l = 0; l < nl; l++) {
        pelt_vec3 d = v3_sub(vpos(b, b->lverts[l]), origin);
        X[2 * l] = v3_dot(d, t0);
        X[2 * l + 1] = v3_dot(d, b0);
        double dd = X[2 * l] * X[2 * l] + X[2 * l + 1] * X[2 * l + 1];
        if (dd > far_d) far_d = dd, far = l;
    }
    for (size_t i = 0; i < n; i++) {
        uint32_t f = b->order[i];
        pelt_vec3 p0 = vpos(b, m->indices[3 * f]);
        pelt_vec3 e1 = v3_sub(vpos(b, m->indices[3 * f + 1]), p0);
        pelt_vec3 e2 = v3_sub(vpos(b, m->indices[3 * f + 2]), p0);
        double x1 = v3_len(e1);
        double twice = v3_len(v3_cross(e1, e2));
        if (!(x1 > 0)) x1 = 1e-30;
        double x2 = v3_dot(e1, e2) / x1, y2 = twice / x1;
        double *fr = b->frame + 3 * i;
        fr[0] = x1, fr[1] = x2, fr[2] = y2;
        double area = 0.5 * twice > 1e-30 ? 0.5 * twice : 1e-30;
        double w = 1.0 / (2.0 * sqrt(area));
        double P[3][2] = {{0, 0}, {x1, 0}, {x2, y2}};
        double *c = b->coef + 6 * i;
        for (int j = 0; j < 3; j++) {
            int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            c[2 * j] = w * (P[j2][0] - P[j1][0]);
            c[2 * j + 1] = w * (P[j2][1] - P[j1][1]);
        }
    }
    if (nl < 3) return nl;
    /* Jacobi column scaling of A (diag of A^T A), pins get 0: they stay put. */
    double *cs = b->colscale;
    memset(cs, 0, nl * 2 * sizeof(double));
    for (size_t i = 0; i < n; i++) {
        const double *c = b->coef + 6 * i;
        for (int j = 0; j < 3; j++) {
            uint32_t l = b->tri_local[3 * i + j];
            double d = c[2 * j] * c[2 * j] + c[2 * j + 1] * c[2 * j + 1];
            cs[2 * l] += d;
            cs[2 * l + 1] += d;
        }
    }
    for (size_t k = 0; k < 2 * nl; k++) cs[k] = cs[k] > 0 ? 1.0 / sqrt(cs[k]) : 0.0;
    cs[0] = cs[1] = cs[2 * far] = cs[2 * far + 1] = 0.0; /* two pinned vertices */
    /* Preconditioned CGLS on min |A X| with the pins fixed. */
    size_t nr = 2 * n, nx = 2 * nl;
    double *r = b->r, *q = b->q, *s = b->s, *p = b->p, *t = b->t;
    apply_a(b, n, X, r);
    for (size_t k = 0; k < nr; k++) r[k] = -r[k];
    apply_at(b, n, nl, r, s);
    for (size_t k = 0; k < nx; k++) s[k] *= cs[k];
    memcpy(p, s, nx * sizeof(double));
    double gamma = dot(s, s, nx), gamma0 = gamma;
    for (int it = 0; it < CG_MAX_ITERATIONS && gamma > CG_TOLERANCE * CG_TOLERANCE * gamma0 && gamma > 0; it++) {
        for (size_t k = 0; k < nx; k++) t[k] = cs[k] * p[k];
        apply_a(b, n, t, q);
        double qq = dot(q, q, nr);
        if (!(qq > 0)) break;
        double alpha = gamma / qq;
        for (size_t k = 0; k < nx; k++) X[k] += alpha * t[k];
        for (size_t k = 0; k < nr; k++) r[k] -= alpha * q[k];
        apply_at(b, n, nl, r, s);
        for (size_t k = 0; k < nx; k++) s[k] *= cs[k];
        double gnew = dot(s, s, nx);
        double beta = gnew / gamma;
        gamma = gnew;
        for (size_t k = 0; k < nx; k++) p[k] = s[k] + beta * p[k];
    }
    return nl;
}

/* Jacobian of the map from triangle i's local frame to uv. */
static void jacobian(const builder *b, size_t i, double J[4])
{
    const double *fr = b->frame + 3 * i;
    const uint32_t *tl = b->tri_local + 3 * i;
    const double *X = b->X;
    double d1u = X[2 * tl[1]] - X[2 * tl[0]], d1v = X[2 * tl[1] + 1] - X[2 * tl[0] + 1];
    double d2u = X[2 * tl[2]] - X[2 * tl[0]], d2v = X[2 * tl[2] + 1] - X[2 * tl[0] + 1];
    double x1 = fr[0], x2 = fr[1], y2 = fr[2] > 1e-30 ? fr[2] : 1e-30;
    /* J = D * inverse([[x1, x2], [0, y2]]) */
    J[0] = d1u / x1;
    J[1] = (d2u - J[0] * x2) / y2;
    J[2] = d1v / x1;
    J[3] = (d2v - J[2] * x2) / y2;
}

static void singular_values(const double J[4], double *smax, double *smin)
{
    double e = 0.5 * (J[0] + J[3]), f = 0.5 * (J[0] - J[3]);
    double g = 0.5 * (J[2] + J[1]), h = 0.5 * (J[2] - J[1]);
    double qq = sqrt(e * e + h * h), rr = sqrt(f * f + g * g);
    *smax = qq + rr;
    *smin = fabs(qq - rr);
}

typedef struct bedge { double minx, maxx; uint32_t a, b; } bedge;

static int compare_bedge(const void *pa, const void *pb)
{
    const bedge *x = pa, *y = pb;
    return (x->minx > y->minx) - (x->minx < y->minx);
}

static double orient(const double *X, uint32_t a, uint32_t b, uint32_t c)
{
    return (X[2 * b] - X[2 * a]) * (X[2 * c + 1] - X[2 * a + 1]) -
           (X[2 * b + 1] - X[2 * a + 1]) * (X[2 * c] - X[2 * a]);
}

/* Exact injectivity of a flattened patch without flipped triangles: no
 * vertex's triangles turn more than once around it, and no two boundary
 * edges (edges of one patch triangle only) cross or touch. Returns true
 * when the patch overlaps itself. */
static bool patch_overlaps(builder *b, size_t n, size_t nl)
{
    const double *X = b->X;
    double *angle = b->s; /* scratch, 1 per local vertex */
    memset(angle, 0, nl * sizeof(double));
    for (size_t i = 0; i < n; i++) {
        const uint32_t *tl = b->tri_local + 3 * i;
        for (int k = 0; k < 3; k++) {
            uint32_t o = tl[k], p = tl[(k + 1) % 3], q = tl[(k + 2) % 3];
            double ax = X[2 * p] - X[2 * o], ay = X[2 * p + 1] - X[2 * o + 1];
            double bx = X[2 * q] - X[2 * o], by = X[2 * q + 1] - X[2 * o + 1];
            angle[o] += atan2(fabs(ax * by - ay * bx), ax * bx + ay * by);
        }
    }
    for (size_t l = 0; l < nl; l++)
        if (angle[l] > 6.283185307179586 + 1e-6) return true;
    /* Boundary edges: sort the 3n directed edges by their undirected key. */
    uint64_t *keys = (uint64_t *)b->p; /* scratch: 3n <= 2 * 3 * cap doubles */
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            uint64_t u = b->tri_local[3 * i + k], v = b->tri_local[3 * i + (k + 1) % 3];
            keys[3 * i + k] = u < v ? (u << 32 | v) : (v << 32 | u);
        }
    qsort(keys, 3 * n, sizeof(uint64_t), compare_u64);
    bedge *edges = (bedge *)b->t; /* scratch: 24 bytes each, fits in 6 * cap doubles */
    size_t ne = 0;
    for (size_t i = 0; i < 3 * n;) {
        size_t j = i + 1;
        while (j < 3 * n && keys[j] == keys[i]) j++;
        if (j - i == 1 && ne < 2 * (size_t)b->cap) {
            uint32_t a = (uint32_t)(keys[i] >> 32), c = (uint32_t)keys[i];
            edges[ne].a = a, edges[ne].b = c;
            edges[ne].minx = fmin(X[2 * a], X[2 * c]);
            edges[ne].maxx = fmax(X[2 * a], X[2 * c]);
            ne++;
        }
        i = j;
    }
    qsort(edges, ne, sizeof *edges, compare_bedge);
    for (size_t i = 0; i < ne; i++) {
        uint32_t a = edges[i].a, c = edges[i].b;
        double miny = fmin(X[2 * a + 1], X[2 * c + 1]), maxy = fmax(X[2 * a + 1], X[2 * c + 1]);
        for (size_t j = i + 1; j < ne && edges[j].minx <= edges[i].maxx; j++) {
            uint32_t d = edges[j].a, e = edges[j].b;
            if (d == a || d == c || e == a || e == c) continue;
            if (fmax(X[2 * d + 1], X[2 * e + 1]) < miny || fmin(X[2 * d + 1], X[2 * e + 1]) > maxy) continue;
            double o1 = orient(X, a, c, d), o2 = orient(X, a, c, e);
            double o3 = orient(X, d, e, a), o4 = orient(X, d, e, c);
            if (o1 * o2 <= 0 && o3 * o4 <= 0) return true; /* crossing or touching */
        }
    }
    return false;
}

/* Checks the flattened patch: no flipped triangle, area ratio and
 * anisotropy within max_stretch, no overlap when rasterized. Returns the
 * number of faces to keep on failure (a prefix), or n when it passes. */
static size_t check_patch(builder *b, size_t n, size_t nl, double *scale_out)
{
    double uv_area = 0, world_area = 0;
    for (size_t i = 0; i < n; i++) {
        double J[4];
        jacobian(b, i, J);
        double a = 0.5 * b->frame[3 * i] * b->frame[3 * i + 2];
        uv_area += (J[0] * J[3] - J[1] * J[2]) * a;
        world_area += a;
    }
    if (!(uv_area > 0) || !(world_area > 0)) return n / 2;
    double norm = world_area / uv_area; /* area scale to world units */
    *scale_out = sqrt(norm);
    double ms = b->max_stretch;
    for (size_t i = 0; i < n; i++) {
        double J[4], smax, smin;
        jacobian(b, i, J);
        double det = (J[0] * J[3] - J[1] * J[2]) * norm;
        singular_values(J, &smax, &smin);
        if (!(det > 1e-9) || det > ms || det < 1.0 / ms || smax > ms * smin) return i;
    }
    /* Injectivity: a patch can overlap itself without a flipped triangle. */
    if (patch_overlaps(b, n, nl)) return (n * 3) / 4;
    double minx = INFINITY, miny = INFINITY, maxx = -INFINITY, maxy = -INFINITY;
    for (size_t l = 0; l < nl; l++) {
        minx = fmin(minx, b->X[2 * l]), maxx = fmax(maxx, b->X[2 * l]);
        miny = fmin(miny, b->X[2 * l + 1]), maxy = fmax(maxy, b->X[2 * l + 1]);
    }
    double ext = fmax(maxx - minx, maxy - miny);
    unsigned res = (unsigned)ceil(sqrt(32.0 * (double)n));
    if (res < 16) res = 16;
    if (res > b->claims_res) res = b->claims_res;
    float *uv = (float *)b->t; /* scratch: 2 floats per local vertex fit in t */
    for (size_t l = 0; l < nl; l++) {
        uv[2 * l] = (float)((b->X[2 * l] - minx) / ext * 0.999 + 0.0005);
        uv[2 * l + 1] = (float)((b->X[2 * l + 1] - miny) / ext * 0.999 + 0.0005);
    }
    if (pelt__raster_overlaps(uv, b->tri_local, n, res, b->claims, NULL) > 0) return (n * 3) / 4;
    return n;
}

/* Rotates the patch so the field runs along +u (Lengyel §2.1: patches
 * aligned to the global direction field) and scales it to world units. */
static void orient_patch(builder *b, size_t n, size_t nl, double scale)
{
    double sx = 0, sy = 0;
    for (size_t i = 0; i < n; i++) {
        uint32_t f = b->order[i];
        const pelt_mesh *m = b->in;
        pelt_vec3 p0 = vpos(b, m->indices[3 * f]);
        pelt_vec3 e1 = v3_sub(vpos(b, m->indices[3 * f + 1]), p0);
        pelt_vec3 nf = v3_load(b->fnormal + 3 * f);
        pelt_vec3 ax = v3_norm_or(e1, v3(1, 0, 0)), ay = v3_cross(nf, ax);
        pelt_vec3 fl = face_field(b, f);
        double lx = v3_dot(fl, ax), ly = v3_dot(fl, ay);
        double J[4];
        jacobian(b, i, J);
        double du = J[0] * lx + J[1] * ly, dv = J[2] * lx + J[3] * ly;
        double len = sqrt(du * du + dv * dv);
        if (len <= 0) continue;
        double wgt = 0.5 * b->frame[3 * i] * b->frame[3 * i + 2] * sqrt(lx * lx + ly * ly);
        sx += wgt * du / len;
        sy += wgt * dv / len;
    }
    double c = 1, s = 0;
    double len = sqrt(sx * sx + sy * sy);
    if (len > 0) c = sx / len, s = sy / len; /* else isotropic: any rotation */
    for (size_t l = 0; l < nl; l++) {
        double u = b->X[2 * l], v = b->X[2 * l + 1];
        b->X[2 * l] = scale * (c * u + s * v);
        b->X[2 * l + 1] = scale * (-s * u + c * v);
    }
}

static void accept_patch(builder *b, size_t n)
{
    const pelt_mesh *m = b->in;
    uint32_t pid = (uint32_t)b->patch_count++;
    float *box = b->patch_box + 4 * pid;
    box[0] = box[1] = INFINITY;
    box[2] = box[3] = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        uint32_t f = b->order[i];
        b->face_patch[f] = pid;
        for (int k = 0; k < 3; k++) {
            uint32_t v = m->indices[3 * f + k];
            if (b->vert_stamp[v] != pid + 1) { /* split: one copy per (vertex, patch) */
                b->vert_stamp[v] = pid + 1;
                size_t o = b->out_count++;
                b->vert_out[v] = (uint32_t)o;
                b->out_source[o] = v;
                b->out_patch[o] = pid;
                uint32_t l = b->local_of[b->canon[v]];
                float u = (float)b->X[2 * l], w = (float)b->X[2 * l + 1];
                b->out_local[2 * o] = u;
                b->out_local[2 * o + 1] = w;
                box[0] = fminf(box[0], u), box[1] = fminf(box[1], w);
                box[2] = fmaxf(box[2], u), box[3] = fmaxf(box[3], w);
            }
            b->out_index[3 * f + k] = b->vert_out[v];
        }
    }
}

/* ---- packing ---------------------------------------------------------- */

static bool try_pack(const builder *b, double s, unsigned size, stbrp_node *nodes, stbrp_rect *rects)
{
    for (size_t p = 0; p < b->patch_count; p++) {
        const float *box = b->patch_box + 4 * p;
        double w = ceil((box[2] - box[0]) * s + 0.01) + 2 * PELT__ATLAS_GUTTER;
        double h = ceil((box[3] - box[1]) * s + 0.01) + 2 * PELT__ATLAS_GUTTER;
        if (w > size || h > size) return false;
        rects[p].id = (int)p;
        rects[p].w = (stbrp_coord)w;
        rects[p].h = (stbrp_coord)h;
        rects[p].was_packed = 0;
    }
    stbrp_context ctx;
    /* The atlas border counts as a neighbour: pack inside a 1-texel margin. */
    stbrp_init_target(&ctx, (int)size, (int)size, nodes, (int)size);
    return stbrp_pack_rects(&ctx, rects, (int)b->patch_count) == 1;
}

/* ---- statistics -------------------------------------------------------- */

/* Twice the signed uv area and twice the world area of triangle t. */
static void doubled_areas(const pelt_mesh *m, const float *uv, size_t t, double *a, double *w)
{
    const uint32_t *tri = m->indices + 3 * t;
    *a = (uv[2 * tri[1]] - uv[2 * tri[0]]) * (uv[2 * tri[2] + 1] - uv[2 * tri[0] + 1]) -
         (uv[2 * tri[2]] - uv[2 * tri[0]]) * (uv[2 * tri[1] + 1] - uv[2 * tri[0] + 1]);
    *w = 2.0 * pelt__triangle_area(m, t);
}

static void uv_stats(const pelt_mesh *m, const float *uv, pelt_atlas_stats *st)
{
    double tot_uv = 0, tot_w = 0;
    size_t pos = 0, neg = 0;
    for (size_t t = 0; t < m->triangle_count; t++) {
        double a, w;
        doubled_areas(m, uv, t, &a, &w);
        tot_uv += fabs(a);
        tot_w += w;
        pos += a > 0, neg += a < 0;
    }
    st->flipped = pos >= neg ? neg : pos;
    double norm = tot_uv > 0 ? tot_w / tot_uv : 0, sum = 0, lo = INFINITY, hi = 0;
    size_t counted = 0;
    for (size_t t = 0; t < m->triangle_count; t++) {
        double a, w;
        doubled_areas(m, uv, t, &a, &w);
        if (!(w > 0)) continue;
        double ratio = fabs(a) * norm / w;
        lo = fmin(lo, ratio), hi = fmax(hi, ratio), sum += ratio;
        counted++;
    }
    st->stretch_min = counted ? (float)lo : 0.0f;
    st->stretch_max = (float)hi;
    st->stretch_mean = counted ? (float)(sum / (double)counted) : 0.0f;
}

/* ---- the two modes ----------------------------------------------------- */

static pelt_status fail_oom(pelt_error *err, const char *what)
{
    return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "pelt_atlas_create: out of memory (%s)", what);
}

void pelt__atlas_finish_mesh(pelt_atlas *a, const pelt_mesh *in)
{
    pelt_mesh *m = a->mesh;
    for (size_t o = 0; o < a->vertex_count; o++) {
        uint32_t v = a->source_vertex[o];
        memcpy(m->positions + 3 * o, in->positions + 3 * v, 3 * sizeof(float));
        /* The original normals: shells must not crack where vertices split. */
        memcpy(m->normals + 3 * o, in->normals + 3 * v, 3 * sizeof(float));
    }
    pelt__mesh_finish(m, false);
    m->stats.computed_normals = in->stats.computed_normals;
    m->stats.fallback_uvs = false;
    m->stats.dropped_degenerate = in->stats.dropped_degenerate;
    a->stats.vertex_count = a->vertex_count;
    a->stats.triangle_count = a->triangle_count;
    uv_stats(m, m->uvs, &a->stats);
}

static pelt_status finish_output(pelt_atlas *a, const pelt_mesh *in, const float *dir,
                                 const float *weight, const uint32_t *canon)
{
    for (size_t o = 0; o < a->vertex_count; o++) {
        uint32_t v = a->source_vertex[o];
        memcpy(a->directions + 3 * o, dir + 3 * v, 3 * sizeof(float));
        a->weights[o] = weight[v];
        a->welded_vertex[o] = canon[v];
    }
    pelt__atlas_finish_mesh(a, in);
    return PELT_OK;
}

static pelt_status build_mesh_uvs(const pelt_mesh *in, float density, const float *dir,
                                  const float *weight, const uint32_t *canon, pelt_atlas **out,
                                  pelt_error *err)
{
    pelt_atlas *a = pelt__atlas_alloc(in->vertex_count, in->triangle_count);
    if (!a) return fail_oom(err, "atlas arrays");
    a->mesh = pelt__mesh_alloc(in->vertex_count, in->triangle_count);
    if (a->mesh) a->mesh->fur_uvs = pelt__calloc(in->vertex_count, 2 * sizeof(float));
    if (!a->mesh || !a->mesh->fur_uvs) {
        pelt_atlas_destroy(a);
        return fail_oom(err, "output mesh");
    }
    /* One density in world units: fur_uvs = uvs * sqrt(world area / uv area). */
    double tot_uv = 0, tot_w = 0;
    for (size_t t = 0; t < in->triangle_count; t++) {
        const uint32_t *tri = in->indices + 3 * t;
        const float *u = in->uvs;
        tot_uv += fabs((u[2 * tri[1]] - u[2 * tri[0]]) * (u[2 * tri[2] + 1] - u[2 * tri[0] + 1]) -
                       (u[2 * tri[2]] - u[2 * tri[0]]) * (u[2 * tri[1] + 1] - u[2 * tri[0] + 1]));
        pelt_vec3 p0 = v3_load(in->positions + 3 * tri[0]);
        tot_w += v3_len(v3_cross(v3_sub(v3_load(in->positions + 3 * tri[1]), p0),
                                 v3_sub(v3_load(in->positions + 3 * tri[2]), p0)));
    }
    float k = tot_uv > 0 ? (float)(density * sqrt(tot_w / tot_uv)) : density;
    for (size_t v = 0; v < in->vertex_count; v++) {
        a->source_vertex[v] = (uint32_t)v;
        a->mesh->uvs[2 * v] = in->uvs[2 * v];
        a->mesh->uvs[2 * v + 1] = in->uvs[2 * v + 1];
        a->mesh->fur_uvs[2 * v] = in->uvs[2 * v] * k;
        a->mesh->fur_uvs[2 * v + 1] = in->uvs[2 * v + 1] * k;
    }
    memcpy(a->mesh->indices, in->indices, in->triangle_count * 3 * sizeof(uint32_t));
    a->stats.mode_used = PELT_ATLAS_MESH_UVS;
    a->stats.patch_count = 1;
    a->stats.fur_per_atlas = k;
    a->stats.fill = 1.0f;
    *out = a;
    return finish_output(a, in, dir, weight, canon);
}

static pelt_status build_patches(builder *b, unsigned mask, float density, uint32_t seed,
                                 pelt_atlas **out, pelt_error *err)
{
    const pelt_mesh *in = b->in;
    for (size_t f = 0; f < b->tc; f++) {
        const uint32_t *tri = in->indices + 3 * f;
        pelt_vec3 p0 = vpos(b, tri[0]), p1 = vpos(b, tri[1]), p2 = vpos(b, tri[2]);
        v3_store(b->fnormal + 3 * f, v3_norm_or(v3_cross(v3_sub(p1, p0), v3_sub(p2, p0)), v3(0, 0, 1)));
        v3_store(b->fcent + 3 * f, v3_scale(v3_add(v3_add(p0, p1), p2), 1.0f / 3.0f));
        b->face_patch[f] = NONE;
    }
    if (!face_adjacency(in, b->canon, b->adj)) return fail_oom(err, "face adjacency");
    /* Seeds: uncovered faces in a seeded random order (Lengyel §2.1). */
    uint32_t *perm = pelt__calloc(b->tc, sizeof(uint32_t));
    if (!perm) return fail_oom(err, "seed order");
    pelt__rng rng = pelt__rng_seed(seed, 0x61746c6173u);
    for (size_t f = 0; f < b->tc; f++) perm[f] = (uint32_t)f;
    for (size_t f = b->tc; f > 1; f--) {
        size_t j = pelt__rng_next(&rng) % f;
        uint32_t tmp = perm[f - 1];
        perm[f - 1] = perm[j];
        perm[j] = tmp;
    }
    for (size_t s = 0; s < b->tc; s++) {
        uint32_t f = perm[s];
        if (b->face_patch[f] != NONE) continue;
        size_t n = grow(b, f);
        for (;;) {
            double scale = 1.0;
            size_t nl = flatten(b, n);
            size_t keep = n == 1 ? 1 : check_patch(b, n, nl, &scale);
            if (n == 1 && nl == 3) { /* one triangle flattens exactly: scale only */
                double J[4];
                jacobian(b, 0, J);
                double det = J[0] * J[3] - J[1] * J[2];
                scale = det > 0 ? 1.0 / sqrt(det) : 1.0;
            }
            if (keep >= n) {
                orient_patch(b, n, nl, scale);
                accept_patch(b, n);
                break;
            }
            /* Undo the offending faces and everything grown after them. */
            size_t shrink = (n * 7) / 8;
            n = keep < shrink ? keep : shrink;
            if (n < 1) n = 1;
        }
    }
    free(perm);

    /* Pack: one scale for all patches, area proportional to surface area. */
    double total = 0;
    for (size_t p = 0; p < b->patch_count; p++) {
        const float *box = b->patch_box + 4 * p;
        total += (double)(box[2] - box[0]) * (box[3] - box[1]);
    }
    stbrp_node *nodes = pelt__calloc(mask, sizeof(stbrp_node));
    stbrp_rect *rects = pelt__calloc(b->patch_count, sizeof(stbrp_rect));
    if (!nodes || !rects) {
        free(nodes);
        free(rects);
        return fail_oom(err, "packing");
    }
    double lo = 0.0, hi = total > 0 ? (double)mask / sqrt(total) : 1.0;
    if (!try_pack(b, 0.0, mask, nodes, rects)) {
        free(nodes);
        free(rects);
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "pelt_atlas_create: mask_size %u is too small for %zu patches with "
                          "their gutters; use a larger mask_size",
                          mask, b->patch_count);
    }
    for (int it = 0; it < 30; it++) {
        double mid = lo == 0.0 ? hi * 0.5 : sqrt(lo * hi);
        if (try_pack(b, mid, mask, nodes, rects)) lo = mid;
        else hi = mid;
        if (lo > 0 && hi / lo < 1.002) break;
    }
    try_pack(b, lo, mask, nodes, rects);
    free(nodes);

    pelt_atlas *a = pelt__atlas_alloc(b->out_count, b->tc);
    if (a) a->mesh = pelt__mesh_alloc(b->out_count, b->tc);
    if (a && a->mesh) a->mesh->fur_uvs = pelt__calloc(b->out_count, 2 * sizeof(float));
    if (!a || !a->mesh || !a->mesh->fur_uvs) {
        free(rects);
        pelt_atlas_destroy(a);
        return fail_oom(err, "output mesh");
    }
    double used = 0;
    for (size_t p = 0; p < b->patch_count; p++) used += (double)rects[p].w * rects[p].h;
    pelt_mesh *m = a->mesh;
    for (size_t o = 0; o < b->out_count; o++) {
        uint32_t p = b->out_patch[o];
        const float *box = b->patch_box + 4 * p;
        const stbrp_rect *rc = &rects[p];
        float lx = b->out_local[2 * o], ly = b->out_local[2 * o + 1];
        m->uvs[2 * o] = (float)(((double)rc->x + PELT__ATLAS_GUTTER + (lx - box[0]) * lo) / mask);
        m->uvs[2 * o + 1] = (float)(((double)rc->y + PELT__ATLAS_GUTTER + (ly - box[1]) * lo) / mask);
        m->fur_uvs[2 * o] = lx * density;
        m->fur_uvs[2 * o + 1] = ly * density;
        a->source_vertex[o] = b->out_source[o];
    }
    free(rects);
    memcpy(m->indices, b->out_index, b->tc * 3 * sizeof(uint32_t));
    memcpy(a->triangle_patch, b->face_patch, b->tc * sizeof(uint32_t));
    a->stats.mode_used = PELT_ATLAS_PATCHES;
    a->stats.patch_count = b->patch_count;
    a->stats.fur_per_atlas = (float)(density * mask / lo);
    a->stats.fill = (float)(used / ((double)mask * mask));
    *out = a;
    return finish_output(a, in, b->dir, b->weight, b->canon);
}

/* ---- entry points ------------------------------------------------------ */

static void mesh_uv_problem(const pelt_mesh *in, unsigned res, char *why, size_t size,
                            bool *ok)
{
    pelt_atlas_check c;
    *ok = false;
    if (in->stats.fallback_uvs) {
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
    if (in->triangle_count == 0 || in->vertex_count == 0)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_atlas_create: the mesh has no triangles");
    if (in->triangle_count > UINT32_MAX / 3)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_atlas_create: %zu triangles are too many", in->triangle_count);
    if (d.mode < PELT_ATLAS_AUTO || d.mode > PELT_ATLAS_PATCHES)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_atlas_create: mode %d is not auto (0), mesh uvs (1) or patches (2)", d.mode);
    if (!(d.texel_density >= 0.0f) || !isfinite(d.texel_density))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_atlas_create: texel_density %g must be >= 0", (double)d.texel_density);
    if (!(d.max_stretch == 0.0f || d.max_stretch >= 1.1f) || !isfinite(d.max_stretch))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_atlas_create: max_stretch %g must be 0 (default) or >= 1.1", (double)d.max_stretch);
    if (d.mask_size > 16384)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_atlas_create: mask_size %u exceeds 16384", d.mask_size);
    for (int k = 0; k < 3; k++)
        if (!isfinite(d.direction[k]))
            return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_atlas_create: direction[%d] is not finite", k);
    unsigned mask = d.mask_size;
    if (mask == 0) {
        mask = 256;
        while (mask < 4096 && (double)mask * mask < (double)in->triangle_count) mask *= 2;
    }
    float density = d.texel_density;
    if (density == 0.0f) {
        float diag = 0;
        for (int k = 0; k < 3; k++) diag += (in->bounds_max[k] - in->bounds_min[k]) * (in->bounds_max[k] - in->bounds_min[k]);
        diag = sqrtf(diag);
        density = diag > 0 ? 8.0f / diag : 1.0f;
    }
    float ms = d.max_stretch == 0.0f ? 2.0f : d.max_stretch;
    unsigned cap = d.max_patch_faces ? d.max_patch_faces : 1500;
    if (cap > 1000000) cap = 1000000;
    if (cap > in->triangle_count) cap = (unsigned)in->triangle_count;
    unsigned iters = d.smoothing_iterations ? d.smoothing_iterations : 4;

    bool use_cache = d.cache_dir && d.cache_dir[0];
    uint64_t key = 0;
    if (use_cache) {
        d.max_stretch = ms, d.max_patch_faces = cap, d.smoothing_iterations = iters;
        key = pelt__atlas_key(in, &d, mask, density);
        pelt_atlas *cached = NULL;
        if (pelt__atlas_cache_load(d.cache_dir, key, in, &cached)) {
            cached->stats.from_cache = true;
            cached->stats.build_seconds = now_seconds() - t0;
            *out = cached;
            return PELT_OK;
        }
    }

    builder b = {0};
    b.in = in, b.vc = in->vertex_count, b.tc = in->triangle_count, b.cap = cap, b.max_stretch = ms;
    if (!builder_alloc(&b)) {
        builder_free(&b);
        return fail_oom(err, "atlas builder");
    }
    pelt_status st = PELT_OK;
    if (!pelt__weld(in->positions, NULL, b.vc, b.canon) ||
        !pelt__direction_field(in->positions, in->normals, b.vc, in->indices, b.tc, b.canon,
                               d.direction, d.vertex_directions, iters, b.dir, b.weight)) {
        builder_free(&b);
        return fail_oom(err, "direction field");
    }
    char why[256] = "";
    bool uvs_ok = false;
    if (d.mode != PELT_ATLAS_PATCHES) mesh_uv_problem(in, mask, why, sizeof why, &uvs_ok);
    pelt_atlas *a = NULL;
    if (d.mode == PELT_ATLAS_MESH_UVS || (d.mode == PELT_ATLAS_AUTO && uvs_ok))
        st = build_mesh_uvs(in, density, b.dir, b.weight, b.canon, &a, err);
    else
        st = build_patches(&b, mask, density, d.seed, &a, err);
    builder_free(&b);
    if (st != PELT_OK) {
        pelt_atlas_destroy(a);
        return st;
    }
    snprintf(a->stats.uv_warning, sizeof a->stats.uv_warning, "%s", uvs_ok ? "" : why);
    a->stats.mask_size = mask;
    a->stats.texel_density = density;
    a->stats.build_seconds = now_seconds() - t0;
    if (use_cache) pelt__atlas_cache_store(d.cache_dir, key, a); /* best effort */
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

/* ---- drawing for `pelt atlas` ------------------------------------------ */

static void put_pixel(uint8_t *rgba, unsigned w, unsigned h, long x, long y, const uint8_t c[3])
{
    if (x < 0 || y < 0 || x >= (long)w || y >= (long)h) return;
    uint8_t *p = rgba + 4 * ((size_t)y * w + (size_t)x);
    p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
}

static void draw_line(uint8_t *rgba, unsigned w, unsigned h, double x0, double y0, double x1,
                      double y1, const uint8_t c[3])
{
    double dx = x1 - x0, dy = y1 - y0;
    double steps = ceil(fmax(fabs(dx), fabs(dy)));
    if (steps < 1) steps = 1;
    if (steps > 4.0 * (w + h)) steps = 4.0 * (w + h);
    for (double i = 0; i <= steps; i++)
        put_pixel(rgba, w, h, (long)floor(x0 + dx * i / steps), (long)floor(y0 + dy * i / steps), c);
}


pelt_status pelt_atlas_draw(const pelt_atlas *a, uint8_t *rgba, unsigned width, unsigned height,
                            uint32_t seed, pelt_error *err)
{
    if (!a || !a->mesh || !rgba || width == 0 || height == 0)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "pelt_atlas_draw: needs an atlas that still holds its mesh and a %ux%u buffer",
                          width, height);
    const pelt_mesh *m = a->mesh;
    size_t tc = m->triangle_count;
    for (size_t i = 0; i < (size_t)width * height; i++) {
        rgba[4 * i] = rgba[4 * i + 1] = rgba[4 * i + 2] = 24;
        rgba[4 * i + 3] = 255;
    }
    uint64_t *edges = pelt__calloc(tc, 3 * sizeof(uint64_t));
    uint8_t *cell = pelt__calloc(((size_t)width / 8 + 1) * ((size_t)height / 8 + 1), 1);
    if (!edges || !cell) {
        free(edges);
        free(cell);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "pelt_atlas_draw: out of memory");
    }
    /* Patches filled, one random colour each. */
    for (size_t t = 0; t < tc; t++) {
        pelt__rng r = pelt__rng_seed(seed, a->triangle_patch[t] + 1u);
        uint8_t c[3];
        for (int k = 0; k < 3; k++) c[k] = (uint8_t)(80 + pelt__rng_next(&r) % 176);
        double x[3], y[3];
        for (int k = 0; k < 3; k++) {
            x[k] = m->uvs[2 * m->indices[3 * t + k]] * width;
            y[k] = m->uvs[2 * m->indices[3 * t + k] + 1] * height;
        }
        double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
        if (area == 0) continue;
        long x0 = (long)floor(fmin(x[0], fmin(x[1], x[2]))), x1 = (long)ceil(fmax(x[0], fmax(x[1], x[2])));
        long y0 = (long)floor(fmin(y[0], fmin(y[1], y[2]))), y1 = (long)ceil(fmax(y[0], fmax(y[1], y[2])));
        if (x0 < 0) x0 = 0;
        if (y0 < 0) y0 = 0;
        if (x1 > (long)width) x1 = (long)width;
        if (y1 > (long)height) y1 = (long)height;
        for (long py = y0; py < y1; py++)
            for (long px = x0; px < x1; px++) {
                double sx = px + 0.5, sy = py + 0.5, e[3];
                for (int k = 0; k < 3; k++) {
                    int j = (k + 1) % 3;
                    e[k] = ((x[j] - x[k]) * (sy - y[k]) - (y[j] - y[k]) * (sx - x[k])) / area;
                }
                if (e[0] >= 0 && e[1] >= 0 && e[2] >= 0) put_pixel(rgba, width, height, px, py, c);
            }
        for (int k = 0; k < 3; k++) {
            uint64_t p = m->indices[3 * t + k], q = m->indices[3 * t + (k + 1) % 3];
            edges[3 * t + k] = p < q ? (p << 32 | q) : (q << 32 | p);
        }
    }
    /* Borders darker: an edge of split vertices that only one triangle uses. */
    qsort(edges, 3 * tc, sizeof(uint64_t), compare_u64);
    for (size_t i = 0; i < 3 * tc; i++) {
        bool twice = (i + 1 < 3 * tc && edges[i + 1] == edges[i]) || (i > 0 && edges[i - 1] == edges[i]);
        if (twice) continue;
        uint32_t p = (uint32_t)(edges[i] >> 32), q = (uint32_t)edges[i];
        const uint8_t dark[3] = {10, 10, 10};
        draw_line(rgba, width, height, m->uvs[2 * p] * width, m->uvs[2 * p + 1] * height,
                  m->uvs[2 * q] * width, m->uvs[2 * q + 1] * height, dark);
    }
    /* The direction field: a short line per triangle (one per 8x8 cell),
     * mapped into atlas space through the triangle's own map. */
    for (size_t t = 0; t < tc; t++) {
        const uint32_t *tri = m->indices + 3 * t;
        pelt_vec3 p0 = v3_load(m->positions + 3 * tri[0]);
        pelt_vec3 e1 = v3_sub(v3_load(m->positions + 3 * tri[1]), p0);
        pelt_vec3 e2 = v3_sub(v3_load(m->positions + 3 * tri[2]), p0);
        pelt_vec3 fl = v3(0, 0, 0);
        float wsum = 0;
        for (int k = 0; k < 3; k++) {
            fl = v3_mad(fl, v3_load(a->directions + 3 * tri[k]), a->weights[tri[k]]);
            wsum += a->weights[tri[k]] / 3.0f;
        }
        double cx = 0, cy = 0;
        for (int k = 0; k < 3; k++) cx += m->uvs[2 * tri[k]] * width / 3.0, cy += m->uvs[2 * tri[k] + 1] * height / 3.0;
        long gx = (long)cx / 8, gy = (long)cy / 8;
        if (cx < 0 || cy < 0 || gx > (long)width / 8 || gy > (long)height / 8) continue;
        uint8_t *used = cell + (size_t)gy * (width / 8 + 1) + (size_t)gx;
        if (*used) continue;
        /* Solve fl = a e1 + b e2 in the least-squares sense, then map a, b. */
        double g11 = v3_dot(e1, e1), g12 = v3_dot(e1, e2), g22 = v3_dot(e2, e2);
        double r1 = v3_dot(fl, e1), r2 = v3_dot(fl, e2), det = g11 * g22 - g12 * g12;
        if (!(det > 0)) continue;
        double ca = (r1 * g22 - r2 * g12) / det, cb = (r2 * g11 - r1 * g12) / det;
        double du = ca * (m->uvs[2 * tri[1]] - m->uvs[2 * tri[0]]) + cb * (m->uvs[2 * tri[2]] - m->uvs[2 * tri[0]]);
        double dv = ca * (m->uvs[2 * tri[1] + 1] - m->uvs[2 * tri[0] + 1]) + cb * (m->uvs[2 * tri[2] + 1] - m->uvs[2 * tri[0] + 1]);
        double len = sqrt(du * du * width * width + dv * dv * height * height);
        *used = 1;
        const uint8_t white[3] = {255, 255, 255}, root[3] = {0, 0, 0};
        if (len > 0 && wsum > 0.05f) {
            double sc = 6.0 * wsum / len;
            draw_line(rgba, width, height, cx, cy, cx + du * width * sc, cy + dv * height * sc, white);
        }
        put_pixel(rgba, width, height, (long)cx, (long)cy, root);
    }
    free(edges);
    free(cell);
    return PELT_OK;
}
