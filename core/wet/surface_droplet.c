/* Seam-free droplets: Silva et al. §3.1 Alg. 1 applied to the texels whose
 * surface point lies within the droplet's world radius, per piece of the
 * atlas connected in uv. */
#include "core/wet/surface_droplet.h"
#include "core/wet/texel_raster.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "pelt/mesh.h"
#include "core/base/vec.h"
#include "core/base/weld.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NONE UINT32_MAX

/* ---- building the index -------------------------------------------------- */

void pelt__surface_index_destroy(pelt__surface_index *index)
{
    if (!index) return;
    pelt_allocator a = index->alloc;
    pelt__free(&a, index->welded);
    pelt__free(&a, index->fan_start);
    pelt__free(&a, index->fan);
    pelt__free(&a, index->vert_stamp);
    pelt__free(&a, index->tri_stamp);
    pelt__free(&a, index->tri_dist2);
    pelt__free(&a, index->queue);
    pelt__free(&a, index->group_stamp);
    pelt__free(&a, index->group);
    pelt__free(&a, index->stack);
    pelt__free(&a, index->group_ref);
    pelt__free(&a, index->group_dist2);
    pelt__free(&a, index);
}

pelt_status pelt__surface_index_create(const pelt_mesh *surface, const pelt_allocator *a, pelt__surface_index **out,
                                       pelt_error *err)
{
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "surface index: out is NULL");
    *out = NULL;
    const pelt_mesh_data md = surface ? pelt_mesh_get_data(surface) : (pelt_mesh_data){0}, *mesh = &md;
    if (!surface || !mesh->positions || !mesh->uvs || !mesh->indices)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "surface index: mesh with positions, uvs and indices required");
    size_t nv = mesh->vertex_count, nt = mesh->triangle_count;
    if (nv >= NONE || nt >= NONE / 3)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "surface index: %zu vertices / %zu triangles exceed 32-bit indices",
                          nv, nt);
    for (size_t i = 0; i < 3 * nt; i++)
        if (mesh->indices[i] >= nv)
            return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                              "surface index: triangle %zu names vertex %u of %zu", i / 3,
                              mesh->indices[i], nv);
    pelt__surface_index *x = pelt__alloc_zero(a, 1, sizeof *x);
    if (!x) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "surface index: out of memory");
    if (a) x->alloc = *a;
    x->mesh = surface;
    x->triangle_count = nt;
    size_t nt1 = nt ? nt : 1, nv1 = nv ? nv : 1;
    x->welded = pelt__alloc_zero(&x->alloc, nv1, sizeof *x->welded);
    x->fan = pelt__alloc_zero(&x->alloc, nt1, 3 * sizeof *x->fan);
    x->tri_stamp = pelt__alloc_zero(&x->alloc, nt1, sizeof *x->tri_stamp);
    x->tri_dist2 = pelt__alloc_zero(&x->alloc, nt1, sizeof *x->tri_dist2);
    x->queue = pelt__alloc_zero(&x->alloc, nt1, sizeof *x->queue);
    x->group_stamp = pelt__alloc_zero(&x->alloc, nt1, sizeof *x->group_stamp);
    x->group = pelt__alloc_zero(&x->alloc, nt1, sizeof *x->group);
    x->stack = pelt__alloc_zero(&x->alloc, nt1, sizeof *x->stack);
    x->group_ref = pelt__alloc_zero(&x->alloc, nt1, sizeof *x->group_ref);
    x->group_dist2 = pelt__alloc_zero(&x->alloc, nt1, sizeof *x->group_dist2);
    bool ok = x->welded && x->fan && x->tri_stamp && x->tri_dist2 && x->queue &&
              x->group_stamp && x->group && x->stack && x->group_ref && x->group_dist2 &&
              pelt__weld(mesh->positions, NULL, nv, x->welded);
    if (ok) x->welded_count = pelt__weld_ids(x->welded, nv, x->welded);
    if (ok) {
        x->fan_start = pelt__alloc_zero(&x->alloc, x->welded_count + 1, sizeof *x->fan_start);
        x->vert_stamp = pelt__alloc_zero(&x->alloc, x->welded_count + 1, sizeof *x->vert_stamp);
        ok = x->fan_start && x->vert_stamp;
    }
    if (!ok) {
        pelt__surface_index_destroy(x);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY,
                          "surface index: out of memory for %zu vertices, %zu triangles", nv, nt);
    }
    /* Triangles around each welded position, compressed rows. */
    for (size_t i = 0; i < 3 * nt; i++) x->fan_start[x->welded[mesh->indices[i]] + 1]++;
    for (size_t w = 0; w < x->welded_count; w++) x->fan_start[w + 1] += x->fan_start[w];
    /* A cursor per row fills it. */
    uint32_t *cursor = pelt__alloc_zero(&x->alloc, x->welded_count ? x->welded_count : 1, sizeof *cursor);
    if (!cursor) {
        pelt__surface_index_destroy(x);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "surface index: out of memory");
    }
    for (size_t i = 0; i < 3 * nt; i++) {
        uint32_t w = x->welded[mesh->indices[i]];
        x->fan[x->fan_start[w] + cursor[w]++] = (uint32_t)(i / 3);
    }
    pelt__free(&x->alloc, cursor);
    *out = x;
    return PELT_OK;
}

/* ---- geometry ------------------------------------------------------------ */

/* Squared distance from p to triangle abc (closest point by the Voronoi
 * regions of vertices, edges and face). */
static float triangle_dist2(pelt_vec3 p, pelt_vec3 a, pelt_vec3 b, pelt_vec3 c)
{
    pelt_vec3 ab = v3_sub(b, a), ac = v3_sub(c, a), ap = v3_sub(p, a);
    float d1 = v3_dot(ab, ap), d2 = v3_dot(ac, ap);
    pelt_vec3 q;
    if (d1 <= 0.0f && d2 <= 0.0f) {
        q = a;
    } else {
        pelt_vec3 bp = v3_sub(p, b);
        float d3 = v3_dot(ab, bp), d4 = v3_dot(ac, bp);
        pelt_vec3 cp = v3_sub(p, c);
        float d5 = v3_dot(ab, cp), d6 = v3_dot(ac, cp);
        float vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
        if (d3 >= 0.0f && d4 <= d3) {
            q = b;
        } else if (d6 >= 0.0f && d5 <= d6) {
            q = c;
        } else if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
            q = v3_mad(a, ab, d1 / (d1 - d3));
        } else if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
            q = v3_mad(a, ac, d2 / (d2 - d6));
        } else if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
            q = v3_mad(b, v3_sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)));
        } else {
            float den = va + vb + vc;
            if (!(den > 0.0f)) { /* degenerate: nearest of the vertices */
                float da = v3_dot(ap, ap), db = v3_dot(bp, bp), dc = v3_dot(cp, cp);
                return fminf(da, fminf(db, dc));
            }
            q = v3_add(a, v3_add(v3_scale(ab, vb / den), v3_scale(ac, vc / den)));
        }
    }
    pelt_vec3 d = v3_sub(p, q);
    return v3_dot(d, d);
}

static pelt_vec3 corner(const pelt_mesh_data *mesh, size_t t, int k)
{
    return v3_load(mesh->positions + (size_t)mesh->indices[3 * t + k] * 3);
}

static const float *corner_uv(const pelt_mesh_data *mesh, size_t t, int k)
{
    return mesh->uvs + (size_t)mesh->indices[3 * t + k] * 2;
}

/* The droplet in triangle t's coordinates: c = t's affine uv map at P projected
 * on t's plane, r = radius * uv length per world length on t. False when t
 * is degenerate in 3D or in uv. */
static bool droplet_in_triangle(const pelt_mesh_data *mesh, size_t t, pelt_vec3 p, float radius,
                                float c[2], float *r)
{
    pelt_vec3 p0 = corner(mesh, t, 0);
    pelt_vec3 e1 = v3_sub(corner(mesh, t, 1), p0), e2 = v3_sub(corner(mesh, t, 2), p0);
    const float *t0 = corner_uv(mesh, t, 0), *t1 = corner_uv(mesh, t, 1), *t2 = corner_uv(mesh, t, 2);
    double a11 = v3_dot(e1, e1), a12 = v3_dot(e1, e2), a22 = v3_dot(e2, e2);
    double det = a11 * a22 - a12 * a12; /* = |e1 x e2|^2 */
    double uv_area2 = fabs(((double)t1[0] - t0[0]) * ((double)t2[1] - t0[1]) -
                           ((double)t2[0] - t0[0]) * ((double)t1[1] - t0[1]));
    if (!(det > 0.0) || !(uv_area2 > 0.0)) return false;
    pelt_vec3 d = v3_sub(p, p0);
    double b1 = v3_dot(d, e1), b2 = v3_dot(d, e2);
    /* Least squares d ~ s e1 + u e2: the projection of P on the plane. */
    double s = (a22 * b1 - a12 * b2) / det, u = (a11 * b2 - a12 * b1) / det;
    c[0] = (float)(t0[0] + s * ((double)t1[0] - t0[0]) + u * ((double)t2[0] - t0[0]));
    c[1] = (float)(t0[1] + s * ((double)t1[1] - t0[1]) + u * ((double)t2[1] - t0[1]));
    /* uv length per world length on t: sqrt(uv area / world area). */
    *r = radius * (float)sqrt(uv_area2 / sqrt(det));
    return true;
}

/* ---- the droplet ---------------------------------------------------------- */

typedef struct changed_box {
    unsigned x0, y0, x1, y1; /* inclusive; empty when x0 > x1 */
} changed_box;

/* One droplet on the texels of one triangle (wet_triangle). */
typedef struct droplet_on_texels {
    pelt__wetness *m;
    pelt_vec3 p;
    float radius2, r, wd;
    const float *c;
    changed_box *box;
} droplet_on_texels;

static void wet_texel(void *user, size_t px, size_t py, pelt_vec3 X)
{
    droplet_on_texels *d = user;
    pelt_vec3 dv = v3_sub(X, d->p);
    if (v3_dot(dv, dv) > d->radius2) return;
    if (!pelt__wetness_blend_texel(d->m->texels + (py * d->m->width + px) * 4, d->c, d->r, d->wd)) return;
    changed_box *box = d->box;
    if ((unsigned)px < box->x0) box->x0 = (unsigned)px;
    if ((unsigned)px > box->x1) box->x1 = (unsigned)px;
    if ((unsigned)py < box->y0) box->y0 = (unsigned)py;
    if ((unsigned)py > box->y1) box->y1 = (unsigned)py;
}

/* Rasterizes triangle t's uv footprint at texel centres and applies the
 * droplet (c, r, wd) to each texel whose surface point is within the
 * world radius of p. */
static void wet_triangle(pelt__wetness *m, const pelt_mesh_data *mesh, size_t t, pelt_vec3 p,
                         float radius2, const float c[2], float r, float wd, changed_box *box)
{
    droplet_on_texels d = {m, p, radius2, r, wd, c, box};
    pelt__raster_surface_points(mesh, t, m->width, m->height, wet_texel, &d);
}

/* r grows to hold the inclusive box b (a mask rectangle, core/wet/mask.h). */
static void grow_rect(unsigned r[4], const changed_box *b)
{
    if (b->x0 > b->x1 || b->y0 > b->y1) return;
    unsigned add[4] = {b->x0, b->y0, b->x1 + 1, b->y1 + 1};
    pelt__rect_union(r, add);
}

static bool same_uv(const pelt_mesh_data *mesh, uint32_t a, uint32_t b)
{
    return a == b || (mesh->uvs[(size_t)a * 2] == mesh->uvs[(size_t)b * 2] &&
                      mesh->uvs[(size_t)a * 2 + 1] == mesh->uvs[(size_t)b * 2 + 1]);
}

/* Whether triangle n has the edge of positions (wa, wb) with the same uvs
 * as vertices a and b: the two triangles are then continuous in uv. */
static bool uv_continuous(const pelt_mesh_data *mesh, const pelt__surface_index *x, uint32_t n,
                          uint32_t a, uint32_t b, uint32_t wa, uint32_t wb)
{
    uint32_t va = NONE, vb = NONE;
    for (int k = 0; k < 3; k++) {
        uint32_t v = mesh->indices[3 * (size_t)n + k];
        if (x->welded[v] == wa) va = v;
        else if (x->welded[v] == wb) vb = v;
    }
    return va != NONE && vb != NONE && same_uv(mesh, va, a) && same_uv(mesh, vb, b);
}

/* A triangle can carry its piece's droplet when it has area in 3D and uv. */
static bool usable(const pelt_mesh_data *mesh, size_t t, pelt_vec3 p, float radius)
{
    float c[2], r;
    return droplet_in_triangle(mesh, t, p, radius, c, &r);
}

pelt_status pelt__droplet_surface(pelt__wetness *m, const pelt_mesh *surface,
                                  pelt__surface_index *index, size_t triangle,
                                  const float bary[3], float radius_world, float wetness,
                                  pelt_error *err)
{
    if (!m || !surface || !index || !bary)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "surface droplet: NULL argument");
    const pelt_mesh_data md = pelt_mesh_get_data(surface), *mesh = &md;
    if (index->mesh != surface || index->triangle_count != mesh->triangle_count)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "surface droplet: the index was built for another mesh");
    if (triangle >= mesh->triangle_count)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "surface droplet: triangle %zu out of range (mesh has %zu)", triangle,
                          mesh->triangle_count);
    if (!isfinite(bary[0]) || !isfinite(bary[1]) || !isfinite(bary[2]) ||
        !isfinite(radius_world) || radius_world < 0.0f || !isfinite(wetness))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "surface droplet: barycentrics (%g, %g, %g), radius %g, wetness %g "
                          "must be finite with radius >= 0",
                          (double)bary[0], (double)bary[1], (double)bary[2],
                          (double)radius_world, (double)wetness);
    pelt_vec3 p = v3_add(v3_scale(corner(mesh, triangle, 0), bary[0]),
                         v3_add(v3_scale(corner(mesh, triangle, 1), bary[1]),
                                v3_scale(corner(mesh, triangle, 2), bary[2])));
    if (!isfinite(p.x) || !isfinite(p.y) || !isfinite(p.z))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "surface droplet: non-finite point on triangle %zu", triangle);
    float wd = clampf(wetness, -1.0f, 1.0f);
    if (wd == 0.0f) return PELT_OK; /* Alg. 1 with alpha 0 changes nothing */
    float radius2 = radius_world * radius_world;

    if (++index->stamp == 0) { /* wrapped: forget every old stamp once */
        memset(index->tri_stamp, 0, index->triangle_count * sizeof *index->tri_stamp);
        memset(index->group_stamp, 0, index->triangle_count * sizeof *index->group_stamp);
        memset(index->vert_stamp, 0, index->welded_count * sizeof *index->vert_stamp);
        index->stamp = 1;
    }
    uint32_t stamp = index->stamp;

    /* Breadth-first over triangles sharing a position, keeping those that
     * reach into the ball |X - P| <= radius. */
    size_t head = 0, tail = 0;
    index->queue[tail++] = (uint32_t)triangle;
    index->tri_stamp[triangle] = stamp;
    index->tri_dist2[triangle] = 0.0f;
    while (head < tail) {
        size_t t = index->queue[head++];
        for (int k = 0; k < 3; k++) {
            uint32_t w = index->welded[mesh->indices[3 * t + k]];
            /* Each position's fan once: a pole shared by hundreds of
             * triangles is not rescanned for every one of them. */
            if (index->vert_stamp[w] == stamp) continue;
            index->vert_stamp[w] = stamp;
            for (uint32_t f = index->fan_start[w]; f < index->fan_start[w + 1]; f++) {
                uint32_t n = index->fan[f];
                if (index->tri_stamp[n] == stamp) continue;
                index->tri_stamp[n] = stamp;
                float d2 = triangle_dist2(p, corner(mesh, n, 0), corner(mesh, n, 1),
                                          corner(mesh, n, 2));
                index->tri_dist2[n] = d2;
                if (d2 <= radius2) index->queue[tail++] = n;
            }
        }
    }

    /* Pieces of the ball connected in uv; each gets the droplet through its
     * triangle nearest P (the hit triangle wins ties). */
    size_t groups = 0;
    for (size_t i = 0; i < tail; i++) {
        uint32_t seed = index->queue[i];
        if (index->group_stamp[seed] == stamp) continue;
        uint32_t g = (uint32_t)groups++;
        index->group_ref[g] = NONE;
        index->group_dist2[g] = INFINITY;
        size_t top = 0;
        index->stack[top++] = seed;
        index->group_stamp[seed] = stamp;
        index->group[seed] = g;
        while (top > 0) {
            uint32_t t = index->stack[--top];
            float d2 = index->tri_dist2[t];
            if ((d2 < index->group_dist2[g] || t == triangle) && usable(mesh, t, p, radius_world)) {
                index->group_ref[g] = t;
                index->group_dist2[g] = t == triangle ? -1.0f : d2;
            }
            for (int k = 0; k < 3; k++) {
                uint32_t a = mesh->indices[3 * t + k], b = mesh->indices[3 * t + (k + 1) % 3];
                uint32_t wa = index->welded[a], wb = index->welded[b];
                /* Triangles on the edge are in both fans: scan the smaller. */
                uint32_t ws = index->fan_start[wa + 1] - index->fan_start[wa] <=
                                      index->fan_start[wb + 1] - index->fan_start[wb]
                                  ? wa
                                  : wb;
                for (uint32_t f = index->fan_start[ws]; f < index->fan_start[ws + 1]; f++) {
                    uint32_t n = index->fan[f];
                    if (index->tri_stamp[n] != stamp || index->tri_dist2[n] > radius2 ||
                        index->group_stamp[n] == stamp || !uv_continuous(mesh, index, n, a, b, wa, wb))
                        continue;
                    index->group_stamp[n] = stamp;
                    index->group[n] = g;
                    index->stack[top++] = n;
                }
            }
        }
    }

    /* Alg. 1 on the texels of every triangle in the ball, with the droplet
     * expressed in its piece's coordinates. */
    changed_box box = {UINT32_MAX, UINT32_MAX, 0, 0};
    for (size_t i = 0; i < tail; i++) {
        size_t t = index->queue[i];
        uint32_t ref = index->group_ref[index->group[t]];
        float c[2], r;
        if (ref == NONE || !droplet_in_triangle(mesh, ref, p, radius_world, c, &r)) continue;
        wet_triangle(m, mesh, t, p, radius2, c, r, wd, &box);
    }
    grow_rect(m->dirty, &box);
    if (wd > 0.0f) grow_rect(m->wet, &box);
    return PELT_OK;
}

bool pelt__droplet_ray(pelt__wetness *m, const pelt_mesh *mesh, pelt__surface_index *index,
                       const pelt__bvh *bvh, const float origin[3], const float dir[3],
                       float radius_world, float wetness)
{
    pelt__hit hit;
    if (!bvh || !pelt__bvh_raycast(bvh, origin, dir, INFINITY, &hit)) return false;
    return pelt__droplet_surface(m, mesh, index, hit.triangle, hit.bary, radius_world, wetness,
                                 NULL) == PELT_OK;
}
