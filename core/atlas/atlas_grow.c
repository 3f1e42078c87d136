/* Patch growth over the mesh topology: seeds, Dijkstra splotches, vertex splitting (Lengyel et al. 2001 §2.1). */
#include "core/atlas/atlas_internal.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/rng.h"
#include "core/base/vec.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NONE PELT__ATLAS_NONE
#define CONE_COS 0.34202014f  /* cos 70°: a patch never wraps around a tube */
#define FIELD_COS 0.81915204f /* cos 35°: the field turns little inside a patch */

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
static bool face_adjacency(const pelt_allocator *alloc, const pelt_mesh_data *m,
                           const uint32_t *canon, uint32_t *adj)
{
    size_t n = m->triangle_count * 3;
    half_edge *h = pelt__alloc_zero(alloc, n, sizeof *h);
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
    pelt__free(alloc, h);
    return true;
}

/* ---- growth: Dijkstra over faces from the seed (a round "splotch") ------ */

static void heap_push(pelt__atlas_builder *b, float d, uint32_t f)
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

static pelt__atlas_heap_item heap_pop(pelt__atlas_builder *b)
{
    pelt__atlas_heap_item top = b->heap[0], last = b->heap[--b->heap_n];
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
static size_t grow(pelt__atlas_builder *b, uint32_t seed)
{
    uint32_t gen = ++b->gen;
    size_t n = 0;
    pelt_vec3 n0 = v3_load(b->fnormal + 3 * seed);
    pelt_vec3 f0 = pelt__atlas_face_field(b, seed);
    float w0 = v3_len(f0);
    b->heap_n = 0;
    b->dist[seed] = 0.0f;
    b->face_stamp[seed] = gen;
    heap_push(b, 0.0f, seed);
    while (b->heap_n && n < b->cap) {
        pelt__atlas_heap_item it = heap_pop(b);
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
            pelt_vec3 fg = pelt__atlas_face_field(b, g);
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

/* Makes the first n faces of b->order patch number b->patch_count: one
 * output vertex per (input vertex, patch) at its flattened coordinates
 * (vertex splitting), and the patch's bounding box. */
static void accept_patch(pelt__atlas_builder *b, size_t n)
{
    const pelt_mesh_data *m = &b->in;
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

pelt_status pelt__atlas_grow_patches(pelt__atlas_builder *b, uint32_t seed, pelt_error *err)
{
    const pelt_mesh_data *in = &b->in;
    for (size_t f = 0; f < b->tc; f++) {
        const uint32_t *tri = in->indices + 3 * f;
        pelt_vec3 p0 = pelt__atlas_vpos(b, tri[0]), p1 = pelt__atlas_vpos(b, tri[1]),
                  p2 = pelt__atlas_vpos(b, tri[2]);
        v3_store(b->fnormal + 3 * f, v3_norm_or(v3_cross(v3_sub(p1, p0), v3_sub(p2, p0)), v3(0, 0, 1)));
        v3_store(b->fcent + 3 * f, v3_scale(v3_add(v3_add(p0, p1), p2), 1.0f / 3.0f));
        b->face_patch[f] = NONE;
    }
    if (!face_adjacency(&b->alloc, in, b->canon, b->adj)) return pelt__atlas_fail_oom(err, "face adjacency");
    /* Seeds: uncovered faces in a seeded random order (Lengyel §2.1). */
    uint32_t *perm = pelt__alloc_zero(&b->alloc, b->tc, sizeof(uint32_t));
    if (!perm) return pelt__atlas_fail_oom(err, "seed order");
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
            size_t nl = pelt__atlas_flatten(b, n);
            size_t keep = n == 1 ? 1 : pelt__atlas_check_patch(b, n, nl, &scale);
            if (n == 1 && nl == 3) { /* one triangle flattens exactly: scale only */
                double J[4];
                pelt__atlas_jacobian(b, 0, J);
                double det = J[0] * J[3] - J[1] * J[2];
                scale = det > 0 ? 1.0 / sqrt(det) : 1.0;
            }
            if (keep >= n) {
                pelt__atlas_orient_patch(b, n, nl, scale);
                accept_patch(b, n);
                break;
            }
            /* Undo the offending faces and everything grown after them. */
            size_t shrink = (n * 7) / 8;
            n = keep < shrink ? keep : shrink;
            if (n < 1) n = 1;
        }
    }
    pelt__free(&b->alloc, perm);
    return PELT_OK;
}
