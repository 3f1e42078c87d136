/* Flattening: LSCM by preconditioned CGLS, patch checks, orientation to the direction field (Lengyel §2.1, §3; Lévy 2002). */
#include "core/atlas/atlas_internal.h"

#include "core/atlas/direction_field.h"
#include "core/base/vec.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CG_MAX_ITERATIONS 400
#define CG_TOLERANCE 1e-7    /* on |A^T r| relative to its start */

/* ---- flattening: least-squares conformal map -------------------------- */

/* Per triangle i (local frame P0 = 0, P1 = (x1, 0), P2 = (x2, y2)) the
 * conformal residual grad u - rot(grad v) (Lévy et al. 2002, Eq. 3, as
 * written for an orientation-preserving map) is two rows of A:
 *   row1 = sum_j w(-ey_j u_j - ex_j v_j),  row2 = sum_j w(ex_j u_j - ey_j v_j)
 * with e_j = P_{j+2} - P_{j+1} and w = 1 / (2 sqrt(area)). */
static void apply_a(const pelt__atlas_builder *b, size_t n, const double *x, double *out)
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

static void apply_at(const pelt__atlas_builder *b, size_t n, size_t nl, const double *rows,
                     double *out)
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

size_t pelt__atlas_flatten(pelt__atlas_builder *b, size_t n)
{
    const pelt_mesh_data *m = &b->in;
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
    pelt_vec3 fld = pelt__atlas_face_field(b, seed);
    fld = v3_sub(fld, v3_scale(n0, v3_dot(n0, fld)));
    pelt_vec3 fb = v3_perpendicular(v3_load(b->fnormal + 3 * seed));
    pelt_vec3 t0 = v3_norm_or(fld, fb), b0 = v3_cross(n0, t0);
    pelt_vec3 origin = pelt__atlas_vpos(b, b->lverts[0]);
    double *X = b->X;
    size_t far = 0;
    double far_d = -1;
    for (size_t l = 0; l < nl; l++) {
        pelt_vec3 d = v3_sub(pelt__atlas_vpos(b, b->lverts[l]), origin);
        X[2 * l] = v3_dot(d, t0);
        X[2 * l + 1] = v3_dot(d, b0);
        double dd = X[2 * l] * X[2 * l] + X[2 * l + 1] * X[2 * l + 1];
        if (dd > far_d) far_d = dd, far = l;
    }
    for (size_t i = 0; i < n; i++) {
        uint32_t f = b->order[i];
        pelt_vec3 p0 = pelt__atlas_vpos(b, m->indices[3 * f]);
        pelt_vec3 e1 = v3_sub(pelt__atlas_vpos(b, m->indices[3 * f + 1]), p0);
        pelt_vec3 e2 = v3_sub(pelt__atlas_vpos(b, m->indices[3 * f + 2]), p0);
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

void pelt__atlas_jacobian(const pelt__atlas_builder *b, size_t i, double J[4])
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
static bool patch_overlaps(pelt__atlas_builder *b, size_t n, size_t nl)
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
    qsort(keys, 3 * n, sizeof(uint64_t), pelt__atlas_compare_u64);
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

/* The raster check at the end catches what the exact tests above cannot
 * see at texel scale. */
size_t pelt__atlas_check_patch(pelt__atlas_builder *b, size_t n, size_t nl, double *scale_out)
{
    double uv_area = 0, world_area = 0;
    for (size_t i = 0; i < n; i++) {
        double J[4];
        pelt__atlas_jacobian(b, i, J);
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
        pelt__atlas_jacobian(b, i, J);
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

/* Lengyel §2.1: patches aligned to the global direction field. */
void pelt__atlas_orient_patch(pelt__atlas_builder *b, size_t n, size_t nl, double scale)
{
    double sx = 0, sy = 0;
    for (size_t i = 0; i < n; i++) {
        uint32_t f = b->order[i];
        const pelt_mesh_data *m = &b->in;
        pelt_vec3 p0 = pelt__atlas_vpos(b, m->indices[3 * f]);
        pelt_vec3 e1 = v3_sub(pelt__atlas_vpos(b, m->indices[3 * f + 1]), p0);
        pelt_vec3 nf = v3_load(b->fnormal + 3 * f);
        pelt_vec3 ax = v3_norm_or(e1, v3(1, 0, 0)), ay = v3_cross(nf, ax);
        pelt_vec3 fl = pelt__atlas_face_field(b, f);
        double lx = v3_dot(fl, ax), ly = v3_dot(fl, ay);
        double J[4];
        pelt__atlas_jacobian(b, i, J);
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
