/* Natural wet clumps: cells fixed on the surface (Bruderlin's clump size,
 * beyond Silva et al.'s one clump per droplet; docs/wetness.md). */
#include "core/wet/clump_cells.h"
#include "core/wet/clump.h"
#include "core/wet/texel_raster.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/rng.h"
#include "core/base/vec.h"
#include "core/mesh/triangle_area.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NONE UINT32_MAX
#define LLOYD_STEPS 2
/* The weights' spread, a share of the clump size: power-diagram walls move
 * by up to about this much of a cell, so tuft sizes vary (docs/wetness.md). */
#define SIZE_SPREAD 0.5f
#define MAX_GRID_CELLS (1u << 22)

/* A mask texel a triangle covers: its surface point and the triangle. */
typedef struct texel_point {
    float x, y, z;
    uint32_t triangle;
} texel_point;

struct pelt__clump_cells {
    pelt_allocator alloc;
    pelt_mesh_data mesh; /* the surface's arrays, owned by its mesh */
    unsigned width, height;
    texel_point *points;   /* per texel; triangle NONE where uncovered */
    uint32_t *cell_of;     /* per texel: its cell, NONE where uncovered */
    size_t count;          /* cells */
    uint32_t *start;       /* count + 1 offsets into texels */
    uint32_t *texels;      /* each cell's texels, by index y * width + x */
    unsigned *box;         /* per cell: its texels' rectangle x0, y0, x1, y1 (exclusive) */
    uint32_t *stamp;       /* per cell: the apply that last visited it */
    uint32_t *touched;     /* scratch of one apply: the cells it visits */
    uint32_t stamp_now;
};

/* ---- seeds and the grid that finds the nearest --------------------------- */

/* Seeds in a uniform grid of `cell`-sized boxes over their bounds. */
typedef struct seed_grid {
    float lo[3], cell;
    unsigned dim[3];
    uint32_t *start, *items; /* start: dim product + 1 */
} seed_grid;

static unsigned grid_coord(const seed_grid *g, float v, int axis)
{
    float f = (v - g->lo[axis]) / g->cell;
    if (!(f > 0.0f)) return 0;
    unsigned i = (unsigned)f;
    return i >= g->dim[axis] ? g->dim[axis] - 1 : i;
}

static size_t grid_index(const seed_grid *g, unsigned x, unsigned y, unsigned z)
{
    return ((size_t)z * g->dim[1] + y) * g->dim[0] + x;
}

/* Fills the grid's buckets with the seeds; the arrays are the caller's
 * (start: dim product + 1, items: n). */
static void grid_fill(seed_grid *g, const float *seeds, size_t n)
{
    size_t cells = (size_t)g->dim[0] * g->dim[1] * g->dim[2];
    memset(g->start, 0, (cells + 1) * sizeof *g->start);
    for (size_t i = 0; i < n; i++) {
        const float *s = seeds + 3 * i;
        g->start[grid_index(g, grid_coord(g, s[0], 0), grid_coord(g, s[1], 1), grid_coord(g, s[2], 2)) + 1]++;
    }
    for (size_t c = 0; c < cells; c++) g->start[c + 1] += g->start[c];
    /* Place with each bucket's start as its cursor (it ends at the next
     * bucket's start), then shift the starts back by one bucket. */
    for (size_t i = 0; i < n; i++) {
        const float *s = seeds + 3 * i;
        size_t c = grid_index(g, grid_coord(g, s[0], 0), grid_coord(g, s[1], 1), grid_coord(g, s[2], 2));
        g->items[g->start[c]++] = (uint32_t)i;
    }
    for (size_t c = cells; c > 0; c--) g->start[c] = g->start[c - 1];
    g->start[0] = 0;
}

/* The seed nearest p by the power distance |p - s|^2 - weight_s (plain
 * distance when weights is NULL; max_weight is the largest weight): rings
 * of grid boxes outwards until a ring cannot hold anything nearer than the
 * best so far. */
static uint32_t grid_nearest(const seed_grid *g, const float *seeds, const float *weights, float max_weight,
                             const float p[3])
{
    int c[3] = {(int)grid_coord(g, p[0], 0), (int)grid_coord(g, p[1], 1), (int)grid_coord(g, p[2], 2)};
    int reach = (int)(g->dim[0] > g->dim[1] ? g->dim[0] : g->dim[1]);
    if ((int)g->dim[2] > reach) reach = (int)g->dim[2];
    uint32_t best = NONE;
    float best_d = INFINITY;
    for (int ring = 0; ring <= reach; ring++) {
        /* Every point of the boxes of this ring is at least (ring - 1)
         * boxes from p. */
        float floor_d = (float)(ring - 1) * g->cell;
        if (best != NONE && floor_d > 0.0f && floor_d * floor_d - max_weight > best_d) break;
        for (int z = c[2] - ring; z <= c[2] + ring; z++)
            for (int y = c[1] - ring; y <= c[1] + ring; y++)
                for (int x = c[0] - ring; x <= c[0] + ring; x++) {
                    if (x < 0 || y < 0 || z < 0 || x >= (int)g->dim[0] || y >= (int)g->dim[1] ||
                        z >= (int)g->dim[2])
                        continue;
                    if (abs(x - c[0]) != ring && abs(y - c[1]) != ring && abs(z - c[2]) != ring) continue;
                    size_t b = grid_index(g, (unsigned)x, (unsigned)y, (unsigned)z);
                    for (uint32_t k = g->start[b]; k < g->start[b + 1]; k++) {
                        const float *s = seeds + 3 * g->items[k];
                        float dx = s[0] - p[0], dy = s[1] - p[1], dz = s[2] - p[2];
                        float d = dx * dx + dy * dy + dz * dz - (weights ? weights[g->items[k]] : 0.0f);
                        if (d < best_d || (d == best_d && g->items[k] < best)) best_d = d, best = g->items[k];
                    }
                }
    }
    return best;
}

/* ---- the texels a triangle covers ------------------------------------------ */

/* The texels of one triangle (cover_triangle). */
typedef struct triangle_on_texels {
    pelt__clump_cells *c;
    uint32_t t;
    size_t covered;
} triangle_on_texels;

static void cover_texel(void *user, size_t px, size_t py, pelt_vec3 X)
{
    triangle_on_texels *d = user;
    texel_point *tp = d->c->points + py * d->c->width + px;
    if (tp->triangle == NONE) d->covered++;
    *tp = (texel_point){X.x, X.y, X.z, d->t};
}

/* Rasterizes triangle t at texel centres with the top-left rule (as
 * pelt_atlas_check_uvs and the surface droplets) and records each texel's
 * surface point; returns how many texels it newly covered. */
static size_t cover_triangle(pelt__clump_cells *c, size_t t)
{
    triangle_on_texels d = {c, (uint32_t)t, 0};
    pelt__raster_surface_points(&c->mesh, t, c->width, c->height, cover_texel, &d);
    return d.covered;
}

/* ---- building ------------------------------------------------------------ */

void pelt__clump_cells_destroy(pelt__clump_cells *c)
{
    if (!c) return;
    pelt_allocator a = c->alloc;
    pelt__free(&a, c->points);
    pelt__free(&a, c->cell_of);
    pelt__free(&a, c->start);
    pelt__free(&a, c->texels);
    pelt__free(&a, c->box);
    pelt__free(&a, c->stamp);
    pelt__free(&a, c->touched);
    pelt__free(&a, c);
}

/* Seeds spread by area: the triangle by its share of the area (binary
 * search in the running sum), the point uniform in it. */
static void scatter_seeds(const pelt_mesh_data *m, const double *area_sum, size_t n, uint32_t seed, float *out)
{
    pelt__rng rng = pelt__rng_seed(seed, 0x636c756dULL);
    double total = area_sum[m->triangle_count];
    for (size_t i = 0; i < n; i++) {
        double r = (double)pelt__rng_float(&rng) * total;
        size_t lo = 0, hi = m->triangle_count - 1;
        while (lo < hi) {
            size_t mid = (lo + hi) / 2;
            if (area_sum[mid + 1] <= r) lo = mid + 1;
            else hi = mid;
        }
        float u = pelt__rng_float(&rng), v = pelt__rng_float(&rng);
        if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
        const uint32_t *ix = m->indices + 3 * lo;
        pelt_vec3 a = v3_load(m->positions + 3 * ix[0]), b = v3_load(m->positions + 3 * ix[1]);
        pelt_vec3 c = v3_load(m->positions + 3 * ix[2]);
        v3_store(out + 3 * i, v3_add(a, v3_add(v3_scale(v3_sub(b, a), u), v3_scale(v3_sub(c, a), v))));
    }
}

/* A grid over the seeds' bounds with boxes of about the clump size (more
 * when that would make too many boxes). */
static seed_grid grid_for(const float *seeds, size_t n, float clump_size)
{
    seed_grid g = {{0, 0, 0}, clump_size, {1, 1, 1}, NULL, NULL};
    float hi[3] = {seeds[0], seeds[1], seeds[2]};
    memcpy(g.lo, seeds, sizeof g.lo);
    for (size_t i = 1; i < n; i++)
        for (int k = 0; k < 3; k++) {
            g.lo[k] = fminf(g.lo[k], seeds[3 * i + k]);
            hi[k] = fmaxf(hi[k], seeds[3 * i + k]);
        }
    for (;;) {
        double cells = 1.0;
        for (int k = 0; k < 3; k++) {
            g.dim[k] = (unsigned)fminf(floorf((hi[k] - g.lo[k]) / g.cell) + 1.0f, 65535.0f);
            cells *= g.dim[k];
        }
        if (cells <= MAX_GRID_CELLS) break;
        g.cell *= 2.0f;
    }
    return g;
}

pelt_status pelt__clump_cells_create(const pelt_mesh *mesh, unsigned width, unsigned height,
                                     float clump_size, uint32_t seed, const pelt_allocator *a,
                                     pelt__clump_cells **out, pelt_error *err)
{
    *out = NULL;
    if (!(clump_size > 0.0f) || !isfinite(clump_size))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "clump size must be a positive number, got %g",
                          (double)clump_size);
    const pelt_mesh_data md = mesh ? pelt_mesh_get_data(mesh) : (pelt_mesh_data){0};
    if (!mesh || !md.uvs || md.triangle_count == 0 || width == 0 || height == 0)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "clump cells need a mesh with uvs and a mask");
    pelt__clump_cells *c = pelt__alloc_zero(a, 1, sizeof *c);
    if (!c) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for clump cells");
    c->alloc = *a;
    c->mesh = md;
    c->width = width, c->height = height;
    size_t texels = (size_t)width * height;
    c->points = pelt__alloc_zero(a, texels, sizeof *c->points);
    c->cell_of = pelt__alloc_zero(a, texels, sizeof *c->cell_of);
    double *area_sum = pelt__alloc_zero(a, md.triangle_count + 1, sizeof *area_sum);
    if (!c->points || !c->cell_of || !area_sum) goto oom;
    for (size_t i = 0; i < texels; i++) c->points[i].triangle = NONE, c->cell_of[i] = NONE;
    size_t covered = 0;
    for (size_t t = 0; t < md.triangle_count; t++) {
        covered += cover_triangle(c, t);
        area_sum[t + 1] = area_sum[t] + (double)pelt__triangle_area(&md, t);
    }
    double want = area_sum[md.triangle_count] / ((double)clump_size * clump_size);
    size_t n = want < 1.0 ? 1 : (size_t)llround(fmin(want, 4.0e6));
    if (covered && n > covered) n = covered;
    c->count = n;

    float *seeds = pelt__alloc_zero(a, n, 3 * sizeof(float));
    float *weights = pelt__alloc_zero(a, n, sizeof(float));
    double *sum = pelt__alloc_zero(a, n, 4 * sizeof(double));
    seed_grid g = {{0, 0, 0}, 0, {0, 0, 0}, NULL, NULL};
    if (!seeds || !weights || !sum) goto oom_seeds;
    scatter_seeds(&md, area_sum, n, seed, seeds);
    g = grid_for(seeds, n, clump_size);
    size_t boxes = (size_t)g.dim[0] * g.dim[1] * g.dim[2];
    g.start = pelt__alloc_zero(a, boxes + 1, sizeof *g.start);
    g.items = pelt__alloc_zero(a, n, sizeof *g.items);
    if (!g.start || !g.items) goto oom_seeds;
    /* Lloyd: each seed moves to the centroid of the texels nearest it, so
     * the seeds spread evenly (blue noise, not a lattice: a few steps from
     * random, not converged). */
    for (int step = 0; step < LLOYD_STEPS; step++) {
        grid_fill(&g, seeds, n);
        memset(sum, 0, n * 4 * sizeof(double));
        for (size_t i = 0; i < texels; i++) {
            const texel_point *p = &c->points[i];
            if (p->triangle == NONE) continue;
            const float xyz[3] = {p->x, p->y, p->z};
            uint32_t s = grid_nearest(&g, seeds, NULL, 0.0f, xyz);
            sum[4 * s] += p->x, sum[4 * s + 1] += p->y, sum[4 * s + 2] += p->z, sum[4 * s + 3] += 1.0;
        }
        for (size_t s = 0; s < n; s++)
            if (sum[4 * s + 3] > 0.0)
                for (int k = 0; k < 3; k++) seeds[3 * s + k] = (float)(sum[4 * s + k] / sum[4 * s + 3]);
    }
    /* Tufts of varied size: each seed gets a weight, and a texel joins the
     * seed of least power distance |p - s|^2 - weight (a power diagram:
     * cells stay convex, their walls shift towards the lighter seed). */
    grid_fill(&g, seeds, n);
    pelt__rng rng = pelt__rng_seed(seed, 0x73697a65ULL);
    float spread = SIZE_SPREAD * clump_size, max_weight = 0.0f;
    for (size_t s = 0; s < n; s++) {
        weights[s] = spread * spread * (2.0f * pelt__rng_float(&rng) - 1.0f);
        max_weight = fmaxf(max_weight, weights[s]);
    }
    for (size_t i = 0; i < texels; i++) {
        const texel_point *p = &c->points[i];
        if (p->triangle == NONE) continue;
        const float xyz[3] = {p->x, p->y, p->z};
        c->cell_of[i] = grid_nearest(&g, seeds, weights, max_weight, xyz);
    }
    pelt__free(a, g.start);
    pelt__free(a, g.items);
    pelt__free(a, sum);
    pelt__free(a, seeds);
    pelt__free(a, weights);
    pelt__free(a, area_sum);
    area_sum = NULL;

    /* Each cell's texels, and their rectangle. */
    c->start = pelt__alloc_zero(a, n + 1, sizeof *c->start);
    c->texels = pelt__alloc_zero(a, covered ? covered : 1, sizeof *c->texels);
    c->box = pelt__alloc_zero(a, n, 4 * sizeof *c->box);
    c->stamp = pelt__alloc_zero(a, n, sizeof *c->stamp);
    c->touched = pelt__alloc_zero(a, n, sizeof *c->touched);
    if (!c->start || !c->texels || !c->box || !c->stamp || !c->touched) goto oom;
    for (size_t i = 0; i < texels; i++)
        if (c->cell_of[i] != NONE) c->start[c->cell_of[i] + 1]++;
    for (size_t s = 0; s < n; s++) {
        c->start[s + 1] += c->start[s];
        c->box[4 * s] = c->box[4 * s + 1] = UINT32_MAX;
    }
    for (size_t i = 0; i < texels; i++) {
        uint32_t s = c->cell_of[i];
        if (s == NONE) continue;
        c->texels[c->start[s] + c->stamp[s]++] = (uint32_t)i;
        unsigned x = (unsigned)(i % width), y = (unsigned)(i / width), *b = c->box + 4 * s;
        if (x < b[0]) b[0] = x;
        if (y < b[1]) b[1] = y;
        if (x + 1 > b[2]) b[2] = x + 1;
        if (y + 1 > b[3]) b[3] = y + 1;
    }
    memset(c->stamp, 0, n * sizeof *c->stamp);
    *out = c;
    return PELT_OK;

oom_seeds:
    pelt__free(a, g.start);
    pelt__free(a, g.items);
    pelt__free(a, sum);
    pelt__free(a, seeds);
    pelt__free(a, weights);
oom:
    pelt__free(a, area_sum);
    pelt__clump_cells_destroy(c);
    return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the clump cells of a %ux%u mask",
                      width, height);
}

uint32_t pelt__clump_cells_of_texel(const pelt__clump_cells *c, unsigned x, unsigned y)
{
    return x < c->width && y < c->height ? c->cell_of[(size_t)y * c->width + x] : NONE;
}

/* ---- clumping ------------------------------------------------------------ */

/* Point X projected on triangle t's plane, in its uv (the affine map of
 * the triangle extended beyond it); and at most how many uv units one
 * world unit becomes on it. False for a triangle without area. */
static bool triangle_uv(const pelt_mesh_data *m, uint32_t t, pelt_vec3 X, float uv[2], float *scale)
{
    const uint32_t *ix = m->indices + 3 * (size_t)t;
    pelt_vec3 p0 = v3_load(m->positions + 3 * ix[0]);
    pelt_vec3 e1 = v3_sub(v3_load(m->positions + 3 * ix[1]), p0);
    pelt_vec3 e2 = v3_sub(v3_load(m->positions + 3 * ix[2]), p0);
    const float *t0 = m->uvs + 2 * ix[0], *t1 = m->uvs + 2 * ix[1], *t2 = m->uvs + 2 * ix[2];
    double a = v3_dot(e1, e1), b = v3_dot(e1, e2), cc = v3_dot(e2, e2);
    double det = a * cc - b * b;
    if (!(det > 1e-30)) return false;
    pelt_vec3 d = v3_sub(X, p0);
    double r1 = v3_dot(e1, d), r2 = v3_dot(e2, d);
    float b1 = (float)((cc * r1 - b * r2) / det), b2 = (float)((a * r2 - b * r1) / det);
    uv[0] = t0[0] + b1 * (t1[0] - t0[0]) + b2 * (t2[0] - t0[0]);
    uv[1] = t0[1] + b1 * (t1[1] - t0[1]) + b2 * (t2[1] - t0[1]);
    /* The most a world length can stretch in uv on this triangle: the
     * largest singular value of the map from its plane to uv. In the
     * plane's basis (e1 / |e1|, its normal in the plane) e1 = (p, 0), e2 =
     * (q, r); the map's columns are then d1 / p and (d2 - d1 q / p) / r. */
    double p = sqrt(a), q = b / p, r = sqrt(det) / p;
    double d1[2] = {t1[0] - t0[0], t1[1] - t0[1]}, d2[2] = {t2[0] - t0[0], t2[1] - t0[1]};
    double m1[2] = {d1[0] / p, d1[1] / p};
    double m2[2] = {(d2[0] - m1[0] * q) / r, (d2[1] - m1[1] * q) / r};
    double s11 = m1[0] * m1[0] + m1[1] * m1[1], s22 = m2[0] * m2[0] + m2[1] * m2[1];
    double s12 = m1[0] * m2[0] + m1[1] * m2[1];
    double half = 0.5 * (s11 + s22), disc = sqrt(fmax(0.25 * (s11 - s22) * (s11 - s22) + s12 * s12, 0.0));
    *scale = (float)sqrt(half + disc);
    return isfinite(uv[0]) && isfinite(uv[1]) && isfinite(*scale);
}

/* One cell becomes one clump of its wet texels. */
static void clump_cell(pelt__clump_cells *c, pelt__wetness *m, uint32_t s, float half_diag)
{
    double sx = 0.0, sy = 0.0, sz = 0.0;
    size_t wet = 0;
    for (uint32_t k = c->start[s]; k < c->start[s + 1]; k++) {
        uint32_t i = c->texels[k];
        if (!(m->texels[4 * (size_t)i + 3] > 0.0f)) continue;
        const texel_point *p = &c->points[i];
        sx += p->x, sy += p->y, sz += p->z;
        wet++;
    }
    if (!wet) return;
    pelt_vec3 C = v3((float)(sx / (double)wet), (float)(sy / (double)wet), (float)(sz / (double)wet));
    float reach = 0.0f;
    for (uint32_t k = c->start[s]; k < c->start[s + 1]; k++) {
        uint32_t i = c->texels[k];
        if (!(m->texels[4 * (size_t)i + 3] > 0.0f)) continue;
        const texel_point *p = &c->points[i];
        reach = fmaxf(reach, v3_len(v3_sub(v3(p->x, p->y, p->z), C)));
    }
    for (uint32_t k = c->start[s]; k < c->start[s + 1]; k++) {
        uint32_t i = c->texels[k];
        float *t = m->texels + 4 * (size_t)i;
        if (!(t[3] > 0.0f)) continue;
        float uv[2], scale;
        if (!triangle_uv(&c->mesh, c->points[i].triangle, C, uv, &scale)) {
            /* A sliver: the texel is its own clump centre. */
            uv[0] = ((float)(i % c->width) + 0.5f) / (float)c->width;
            uv[1] = ((float)(i / c->width) + 0.5f) / (float)c->height;
            scale = 0.0f;
        }
        t[0] = uv[0];
        t[1] = uv[1];
        t[2] = pelt__clump_tag(reach * scale + half_diag, s); /* the tuft's lean: one byte a cell */
    }
    const unsigned *b = c->box + 4 * (size_t)s;
    pelt__rect_union(m->dirty, b);
}

void pelt__clump_cells_apply(pelt__clump_cells *c, pelt__wetness *m, const unsigned rect[4])
{
    if (!c || !m || m->width != c->width || m->height != c->height || pelt__rect_empty(rect)) return;
    unsigned x1 = rect[2] < c->width ? rect[2] : c->width, y1 = rect[3] < c->height ? rect[3] : c->height;
    if (++c->stamp_now == 0) { /* wrapped: start the stamps over */
        memset(c->stamp, 0, c->count * sizeof *c->stamp);
        c->stamp_now = 1;
    }
    size_t n = 0;
    for (unsigned y = rect[1]; y < y1; y++)
        for (unsigned x = rect[0]; x < x1; x++) {
            uint32_t s = c->cell_of[(size_t)y * c->width + x];
            if (s == NONE || c->stamp[s] == c->stamp_now) continue;
            c->stamp[s] = c->stamp_now;
            c->touched[n++] = s;
        }
    float half_diag = 0.5f * sqrtf(1.0f / ((float)c->width * c->width) + 1.0f / ((float)c->height * c->height));
    for (size_t k = 0; k < n; k++) clump_cell(c, m, c->touched[k], half_diag);
}
