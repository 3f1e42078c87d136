/* Hair direction field: global or per-vertex c_v projected and smoothed (Lengyel et al. §3, §2.1). */
#include "core/atlas/direction_field.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/vec.h"

#include <stdlib.h>
#include <string.h>

static pelt_vec3 project(pelt_vec3 v, pelt_vec3 n) { return v3_sub(v, v3_scale(n, v3_dot(n, v))); }

/* Slant weight from the length of the projected field (relative to the
 * input): below 0.1 (about 6 degrees from the normal) the fur stands up,
 * above 0.4 it slants fully; smooth in between so it never spins. */
static float ramp(float m)
{
    float x = clampf((m - 0.1f) / 0.3f, 0.0f, 1.0f);
    return x * x * (3.0f - 2.0f * x);
}

bool pelt__direction_field(const float *positions, const float *normals, size_t vertex_count,
                           const uint32_t *indices, size_t triangle_count, const uint32_t *canon,
                           const float global[3], const float *per_vertex, unsigned iterations,
                           float *dir, float *weight)
{
    (void)positions;
    float *field = pelt__calloc(vertex_count, 3 * sizeof(float));
    float *sum = pelt__calloc(vertex_count, 3 * sizeof(float));
    if (!field || !sum) {
        free(field);
        free(sum);
        return false;
    }
    pelt_vec3 g = v3_norm_or(v3_load(global), v3(0, -1, 0));
    /* Raw field: unit tangent direction times its slant weight (Lengyel §3:
     * the tangential part of c_v). Only canonical vertices carry the value. */
    for (size_t i = 0; i < vertex_count; i++) {
        if (canon[i] != i) continue;
        pelt_vec3 n = v3_load(normals + 3 * i);
        pelt_vec3 t;
        float strength;
        if (per_vertex) { /* the caller's tangential part is the slant (Lengyel §3, c_v) */
            t = project(v3_load(per_vertex + 3 * i), n);
            strength = clampf(v3_len(t), 0.0f, 1.0f);
        } else {
            t = project(g, n);
            strength = ramp(v3_len(t));
        }
        v3_store(field + 3 * i, v3_scale(v3_norm_or(t, v3(0, 0, 0)), strength));
    }
    /* Laplacian smoothing over the welded adjacency, re-projected each time:
     * opposing directions around a singularity cancel, lowering the weight. */
    float *count = weight; /* scratch until the final loop writes weights */
    for (size_t i = 0; i < vertex_count; i++) count[i] = 1.0f;
    for (size_t t = 0; t < triangle_count; t++)
        for (int k = 0; k < 3; k++) count[canon[indices[3 * t + k]]] += 1.0f;
    for (unsigned it = 0; it < iterations; it++) {
        memcpy(sum, field, vertex_count * 3 * sizeof(float));
        for (size_t t = 0; t < triangle_count; t++) {
            uint32_t c[3];
            for (int k = 0; k < 3; k++) c[k] = canon[indices[3 * t + k]];
            for (int k = 0; k < 3; k++) {
                float *s = sum + 3 * c[k];
                for (int j = 1; j < 3; j++) {
                    const float *f = field + 3 * c[(k + j) % 3];
                    s[0] += 0.5f * f[0];
                    s[1] += 0.5f * f[1];
                    s[2] += 0.5f * f[2];
                }
            }
        }
        for (size_t i = 0; i < vertex_count; i++) {
            if (canon[i] != i) continue;
            pelt_vec3 n = v3_load(normals + 3 * i);
            pelt_vec3 avg = v3_scale(v3_load(sum + 3 * i), 1.0f / count[i]);
            pelt_vec3 p = project(avg, n);
            /* Re-projection keeps the length (weight) of the average. */
            float la = v3_len(avg), lp = v3_len(p);
            if (lp > 1e-12f) p = v3_scale(p, la / lp);
            v3_store(field + 3 * i, p);
        }
    }
    for (size_t i = 0; i < vertex_count; i++) {
        size_t c = canon[i];
        pelt_vec3 n = v3_load(normals + 3 * i);
        pelt_vec3 f = project(v3_load(field + 3 * c), n);
        float w = clampf(v3_len(v3_load(field + 3 * c)), 0.0f, 1.0f);
        pelt_vec3 fallback = v3_perpendicular(v3_load(normals + 3 * i)); /* the one basis */
        pelt_vec3 d = v3_len(f) > 1e-6f ? v3_norm_or(f, fallback) : fallback;
        v3_store(dir + 3 * i, d);
        weight[i] = w > 1e-6f ? w : 0.0f;
    }
    free(field);
    free(sum);
    return true;
}
