/* Statistics of an atlas: flipped triangles and uv/world area stretch (Lengyel §2.1: low-distortion patches). */
#include "core/atlas/atlas_internal.h"

#include "core/base/vec.h"

#include <math.h>

/* Twice the signed uv area and twice the world area of triangle tri. */
static void doubled_areas(const float *pos, const float *uv, const uint32_t *tri, double *a,
                          double *w)
{
    *a = (uv[2 * tri[1]] - uv[2 * tri[0]]) * (uv[2 * tri[2] + 1] - uv[2 * tri[0] + 1]) -
         (uv[2 * tri[2]] - uv[2 * tri[0]]) * (uv[2 * tri[1] + 1] - uv[2 * tri[0] + 1]);
    pelt_vec3 p0 = v3_load(pos + 3 * tri[0]);
    pelt_vec3 e1 = v3_sub(v3_load(pos + 3 * tri[1]), p0);
    pelt_vec3 e2 = v3_sub(v3_load(pos + 3 * tri[2]), p0);
    *w = 2.0 * (0.5f * v3_len(v3_cross(e1, e2)));
}

void pelt__atlas_area_totals(const float *positions, const float *uvs, const uint32_t *indices,
                             size_t triangle_count, double *uv_total, double *world_total,
                             size_t *positive, size_t *negative)
{
    double tot_uv = 0, tot_w = 0;
    size_t pos = 0, neg = 0;
    for (size_t t = 0; t < triangle_count; t++) {
        double a, w;
        doubled_areas(positions, uvs, indices + 3 * t, &a, &w);
        tot_uv += fabs(a);
        tot_w += w;
        pos += a > 0, neg += a < 0;
    }
    *uv_total = tot_uv, *world_total = tot_w;
    if (positive) *positive = pos;
    if (negative) *negative = neg;
}

void pelt__atlas_uv_stats(const float *positions, const float *uv, const uint32_t *indices,
                          size_t triangle_count, pelt_atlas_stats *st)
{
    double tot_uv, tot_w;
    size_t pos, neg;
    pelt__atlas_area_totals(positions, uv, indices, triangle_count, &tot_uv, &tot_w, &pos, &neg);
    st->flipped = pos >= neg ? neg : pos;
    double norm = tot_uv > 0 ? tot_w / tot_uv : 0, sum = 0, lo = INFINITY, hi = 0;
    size_t counted = 0;
    for (size_t t = 0; t < triangle_count; t++) {
        double a, w;
        doubled_areas(positions, uv, indices + 3 * t, &a, &w);
        if (!(w > 0)) continue;
        double ratio = fabs(a) * norm / w;
        lo = fmin(lo, ratio), hi = fmax(hi, ratio), sum += ratio;
        counted++;
    }
    st->stretch_min = counted ? (float)lo : 0.0f;
    st->stretch_max = (float)hi;
    st->stretch_mean = counted ? (float)(sum / (double)counted) : 0.0f;
}
