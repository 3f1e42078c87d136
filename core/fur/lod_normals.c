/* A coarse level's normals fitted to the full mesh's (docs/lod.md, The
 * coarse levels' normals). A level keeps a subset of the vertices, each
 * with its own normal, and its triangles interpolate those normals over
 * the vertices it left out: a hair there stands along the interpolation,
 * not along the full mesh's normal, and its tip lands elsewhere. Each
 * left-out vertex is found on the level's surface (the nearest point of
 * its triangles, through a hashed grid) and the kept vertices' normals are fitted
 * by least squares so that their interpolation meets the full mesh's
 * normals at every vertex, held near their own by a small weight. */
#include "core/fur/lod.h"

#include "core/base/error.h"
#include "core/base/hooks.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The weight that holds a kept vertex's normal near its own. */
#define FIT_HOLD 0.1f
/* Jacobi steps: the bunny's fit settles within 8 (docs/lod.md). */
#define FIT_STEPS 12
/* The grid's hash table: slots a triangle. */
#define GRID_SLOTS_PER_TRIANGLE 4
/* Grid entries a triangle at most (the cells its bounding box touches). */
#define GRID_ENTRIES_PER_TRIANGLE 64
/* Rings of cells searched around a vertex before it is left out of the fit. */
#define SEARCH_RINGS 4

typedef struct sample {
    uint32_t v[3]; /* the level's triangle the vertex lies on */
    float b[3];    /* its barycentric weights there */
} sample;

/* A hashed grid: cells a mean edge wide, hashed into a table of about
 * four slots a triangle, so a surface's cells cost what its triangles do
 * and not what its bounding box holds. Cells that share a slot share
 * their triangles, which the search weighs by distance anyway. */
typedef struct grid {
    float lo[3], cell;
    size_t mask;     /* slots - 1, a power of two */
    uint32_t *start; /* slots + 1 */
    uint32_t *tris;
} grid;

static float dot3(const float *a, const float *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static int32_t cell_of(const grid *g, float p, int k)
{
    float c = floorf((p - g->lo[k]) / g->cell);
    if (isnan(c)) return 0;
    return (int32_t)fmaxf(-1e9f, fminf(c, 1e9f)); /* far from overflow, rings and all */
}

/* The cells a triangle's bounding box touches, per axis. */
static void triangle_cells(const grid *g, const float *pos, const uint32_t *t, int32_t a[3], int32_t b[3])
{
    for (int k = 0; k < 3; k++) {
        float mn = INFINITY, mx = -INFINITY;
        for (int c = 0; c < 3; c++) {
            float p = pos[3 * (size_t)t[c] + (size_t)k];
            mn = fminf(mn, p);
            mx = fmaxf(mx, p);
        }
        a[k] = cell_of(g, mn, k);
        b[k] = cell_of(g, mx, k);
    }
}

static size_t slot_of(const grid *g, int32_t x, int32_t y, int32_t z)
{
    uint32_t h = (uint32_t)x * 73856093u ^ (uint32_t)y * 19349663u ^ (uint32_t)z * 83492791u;
    return (size_t)h & g->mask;
}

/* Each triangle in every cell its bounding box touches (counting sort). */
static bool grid_build(grid *g, const float *pos, const uint32_t *idx, size_t triangles, float cell,
                       const pelt_allocator *alloc)
{
    for (int k = 0; k < 3; k++) g->lo[k] = INFINITY;
    for (size_t i = 0; i < 3 * triangles; i++)
        for (int k = 0; k < 3; k++) g->lo[k] = fminf(g->lo[k], pos[3 * (size_t)idx[i] + (size_t)k]);
    /* A few long triangles must not fill the table: cells twice as wide
     * until the entries stay within GRID_ENTRIES_PER_TRIANGLE a triangle. */
    g->cell = cell;
    for (int widen = 0; widen < 64; widen++) {
        double entries = 0.0;
        for (size_t t = 0; t < triangles; t++) {
            int32_t a[3], b[3];
            triangle_cells(g, pos, idx + 3 * t, a, b);
            entries += ((double)b[0] - a[0] + 1.0) * ((double)b[1] - a[1] + 1.0) * ((double)b[2] - a[2] + 1.0);
        }
        if (entries <= GRID_ENTRIES_PER_TRIANGLE * (double)triangles) break;
        g->cell *= 2.0f;
    }
    size_t slots = 1;
    while (slots < GRID_SLOTS_PER_TRIANGLE * triangles) slots *= 2;
    g->mask = slots - 1;
    g->start = pelt__alloc_zero(alloc, slots + 1, sizeof *g->start);
    if (!g->start) return false;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t t = 0; t < triangles; t++) {
            int32_t a[3], b[3];
            triangle_cells(g, pos, idx + 3 * t, a, b);
            for (int32_t z = a[2]; z <= b[2]; z++)
                for (int32_t y = a[1]; y <= b[1]; y++)
                    for (int32_t x = a[0]; x <= b[0]; x++) {
                        size_t c = slot_of(g, x, y, z);
                        if (pass == 0) g->start[c + 1]++;
                        else g->tris[g->start[c]++] = (uint32_t)t;
                    }
        }
        if (pass == 0) {
            for (size_t c = 0; c < slots; c++) g->start[c + 1] += g->start[c];
            g->tris = pelt__alloc(alloc, ((size_t)g->start[slots] ? g->start[slots] : 1) * sizeof *g->tris);
            if (!g->tris) return false;
        }
    }
    /* The fill moved each start to the next slot's: shift them back. */
    memmove(g->start + 1, g->start, slots * sizeof *g->start);
    g->start[0] = 0;
    return true;
}

/* The nearest point of triangle abc to p as barycentric weights (the
 * region tests of a point against a triangle's vertices, edges and face);
 * returns the squared distance. */
static float nearest_on_triangle(const float *p, const float *a, const float *b, const float *c, float w[3])
{
    float ab[3], ac[3], ap[3], bp[3], cp[3];
    for (int k = 0; k < 3; k++) {
        ab[k] = b[k] - a[k];
        ac[k] = c[k] - a[k];
        ap[k] = p[k] - a[k];
        bp[k] = p[k] - b[k];
        cp[k] = p[k] - c[k];
    }
    float d1 = dot3(ab, ap), d2 = dot3(ac, ap), d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    float d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    float va = d3 * d6 - d5 * d4, vb = d5 * d2 - d1 * d6, vc = d1 * d4 - d3 * d2;
    if (d1 <= 0.0f && d2 <= 0.0f) {
        w[0] = 1.0f, w[1] = 0.0f, w[2] = 0.0f;
    } else if (d3 >= 0.0f && d4 <= d3) {
        w[0] = 0.0f, w[1] = 1.0f, w[2] = 0.0f;
    } else if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
        float t = d1 / (d1 - d3);
        w[0] = 1.0f - t, w[1] = t, w[2] = 0.0f;
    } else if (d6 >= 0.0f && d5 <= d6) {
        w[0] = 0.0f, w[1] = 0.0f, w[2] = 1.0f;
    } else if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
        float t = d2 / (d2 - d6);
        w[0] = 1.0f - t, w[1] = 0.0f, w[2] = t;
    } else if (va <= 0.0f && d4 - d3 >= 0.0f && d5 - d6 >= 0.0f) {
        float t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        w[0] = 0.0f, w[1] = 1.0f - t, w[2] = t;
    } else {
        float s = 1.0f / (va + vb + vc);
        w[1] = vb * s, w[2] = vc * s, w[0] = 1.0f - w[1] - w[2];
    }
    float d2sum = 0.0f;
    for (int k = 0; k < 3; k++) {
        float q = w[0] * a[k] + w[1] * b[k] + w[2] * c[k] - p[k];
        d2sum += q * q;
    }
    return d2sum;
}

/* A level's triangle as the search reads it, in one place: its corners
 * and the sum of their normals. */
typedef struct triangle {
    float corner[3][3];
    float normal[3];
} triangle;

/* The nearest triangle in one cell facing the same side as n: updates
 * *best and the sample. */
static void search_cell(const grid *g, const triangle *tris, const uint32_t *idx, size_t slot, const float *p,
                        const float *n, float *best, sample *s)
{
    for (uint32_t e = g->start[slot]; e < g->start[slot + 1]; e++) {
        uint32_t t = g->tris[e];
        const triangle *tr = &tris[t];
        if (!(dot3(tr->normal, n) > 0.0f)) continue;
        float w[3];
        float d2 = nearest_on_triangle(p, tr->corner[0], tr->corner[1], tr->corner[2], w);
        if (d2 < *best) {
            *best = d2;
            memcpy(s->v, idx + 3 * (size_t)t, sizeof s->v);
            memcpy(s->b, w, sizeof s->b);
        }
    }
}

/* Where vertex i lies on the level: the nearest of the triangles in the
 * cells around it whose normals face the same side as its own (a thin
 * part's far side is near too). Its own cell first: a vertex lies within
 * the level's small error of the surface, so the nearest there is nearer
 * than the cell's walls and the neighbours need no search. False where
 * none is near. */
static bool locate(const grid *g, const triangle *tris, const uint32_t *idx, const float *p, const float *n,
                   sample *s)
{
    int32_t c[3];
    float margin = INFINITY;
    for (int k = 0; k < 3; k++) {
        c[k] = cell_of(g, p[k], k);
        float lo = p[k] - (g->lo[k] + (float)c[k] * g->cell);
        margin = fminf(margin, fminf(lo, g->cell - lo));
    }
    float best = INFINITY;
    search_cell(g, tris, idx, slot_of(g, c[0], c[1], c[2]), p, n, &best, s);
    if (best < INFINITY && best <= margin * margin) return true;
    /* Then the cells around it; where none holds a triangle near, ring
     * after ring further out, up to SEARCH_RINGS: a coarse level's
     * triangles can be many mean edges long. */
    for (int32_t r = 1; r <= SEARCH_RINGS && (r == 1 || best == INFINITY); r++)
        for (int32_t z = -r; z <= r; z++)
            for (int32_t y = -r; y <= r; y++)
                for (int32_t x = -r; x <= r; x++)
                    if (abs(x) == r || abs(y) == r || abs(z) == r)
                        search_cell(g, tris, idx, slot_of(g, c[0] + x, c[1] + y, c[2] + z), p, n, &best, s);
    return best < INFINITY;
}

void pelt__lod_fit_normal(const float n[3], const float u[3], const float v[3], const float d[3], float out[3])
{
    float len2 = 0.0f;
    for (int k = 0; k < 3; k++) {
        out[k] = n[k] + d[0] * u[k] + d[1] * v[k] + d[2] * n[k];
        len2 += out[k] * out[k];
    }
    float s = len2 > 0.0f ? 1.0f / sqrtf(len2) : 0.0f;
    for (int k = 0; k < 3; k++) out[k] *= s;
}

/* The vertex's frame as the shell vertex stage makes it: u the tangent,
 * v = n x u times its handedness. */
static void frame(const float *n, const float *t, float u[3], float v[3])
{
    float len = sqrtf(dot3(t, t));
    for (int k = 0; k < 3; k++) u[k] = len > 0.0f ? t[k] / len : 0.0f;
    v[0] = (n[1] * u[2] - n[2] * u[1]) * t[3];
    v[1] = (n[2] * u[0] - n[0] * u[2]) * t[3];
    v[2] = (n[0] * u[1] - n[1] * u[0]) * t[3];
}

pelt_status pelt__lod_fit_normals(const pelt_mesh_data *m, const float *tangents, const uint32_t *indices,
                                  size_t triangles, float cell, const pelt_allocator *alloc, float *out,
                                  pelt_error *err)
{
    size_t nv = m->vertex_count;
    memset(out, 0, nv * 3 * sizeof *out);
    if (!m->normals || !tangents || triangles == 0 || !(cell > 0.0f)) return PELT_OK;
    const float *pos = m->positions, *nrm = m->normals;
    grid g = {0};
    sample *samples = pelt__alloc(alloc, (nv ? nv : 1) * sizeof *samples);
    float *fit = pelt__alloc(alloc, (nv ? nv : 1) * 6 * sizeof *fit); /* the fit, then its step */
    float *weight = pelt__alloc_zero(alloc, nv ? nv : 1, sizeof *weight);
    bool *kept = pelt__alloc_zero(alloc, nv ? nv : 1, sizeof *kept);
    triangle *tris = pelt__alloc(alloc, triangles * sizeof *tris);
    pelt_status st = PELT_OK;
    if (!samples || !fit || !weight || !kept || !tris || !grid_build(&g, pos, indices, triangles, cell, alloc)) {
        st = pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for a level's normals (%zu vertices)", nv);
        goto done;
    }
    for (size_t i = 0; i < 3 * triangles; i++) kept[indices[i]] = true;
    for (size_t t = 0; t < triangles; t++) {
        memset(tris[t].normal, 0, sizeof tris[t].normal);
        for (int c = 0; c < 3; c++) {
            size_t v = indices[3 * t + (size_t)c];
            memcpy(tris[t].corner[c], pos + 3 * v, sizeof tris[t].corner[c]);
            for (int k = 0; k < 3; k++) tris[t].normal[k] += nrm[3 * v + (size_t)k];
        }
    }
    /* A kept vertex lies on itself; a left-out one where the level passes. */
    for (size_t i = 0; i < nv; i++) {
        sample *s = &samples[i];
        if (kept[i]) {
            s->v[0] = s->v[1] = s->v[2] = (uint32_t)i;
            s->b[0] = 1.0f, s->b[1] = s->b[2] = 0.0f;
        } else if (!locate(&g, tris, indices, pos + 3 * i, nrm + 3 * i, s)) {
            /* Nowhere near: it weighs nothing in the fit. */
            s->v[0] = s->v[1] = s->v[2] = (uint32_t)i;
            s->b[0] = s->b[1] = s->b[2] = 0.0f;
        }
    }
    memcpy(fit, nrm, nv * 3 * sizeof *fit);
    float *step = fit + 3 * nv;
    for (int it = 0; it < FIT_STEPS; it++) {
        memset(step, 0, nv * 3 * sizeof *step);
        memset(weight, 0, nv * sizeof *weight);
        for (size_t i = 0; i < nv; i++) {
            const sample *s = &samples[i];
            float r[3] = {-nrm[3 * i], -nrm[3 * i + 1], -nrm[3 * i + 2]};
            for (int c = 0; c < 3; c++)
                for (int k = 0; k < 3; k++) r[k] += s->b[c] * fit[3 * (size_t)s->v[c] + (size_t)k];
            for (int c = 0; c < 3; c++) {
                for (int k = 0; k < 3; k++) step[3 * (size_t)s->v[c] + (size_t)k] += s->b[c] * r[k];
                weight[s->v[c]] += s->b[c] * s->b[c];
            }
        }
        for (size_t j = 0; j < nv; j++) {
            if (!kept[j]) continue;
            float h = weight[j] + FIT_HOLD;
            for (int k = 0; k < 3; k++) {
                float g_k = step[3 * j + (size_t)k] + FIT_HOLD * (fit[3 * j + (size_t)k] - nrm[3 * j + (size_t)k]);
                fit[3 * j + (size_t)k] -= 0.5f * g_k / h;
            }
        }
    }
    /* The fitted unit normal less the vertex's own, in the vertex's frame. */
    for (size_t j = 0; j < nv; j++) {
        if (!kept[j]) continue;
        const float *n = nrm + 3 * j;
        float *f = fit + 3 * j, len = sqrtf(dot3(f, f));
        if (!(len > 0.0f)) continue;
        float d[3] = {f[0] / len - n[0], f[1] / len - n[1], f[2] / len - n[2]}, u[3], v[3];
        frame(n, tangents + 4 * j, u, v);
        out[3 * j] = dot3(d, u);
        out[3 * j + 1] = dot3(d, v);
        out[3 * j + 2] = dot3(d, n);
    }
done:
    pelt__free(alloc, g.start);
    pelt__free(alloc, g.tris);
    pelt__free(alloc, samples);
    pelt__free(alloc, fit);
    pelt__free(alloc, weight);
    pelt__free(alloc, kept);
    pelt__free(alloc, tris);
    return st;
}
