/* Fins (Lengyel et al. 2001 §2.3): the edge list and the references the
 * fin shader mirrors. */
#include "core/fur/fins.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/rng.h"

#include <stdlib.h>

static int cmp_u64(const void *x, const void *y)
{
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return (a > b) - (a < b);
}

pelt_status pelt__fin_edges_build(const uint32_t *indices, size_t triangle_count, uint32_t seed,
                                  const pelt_allocator *alloc, pelt__fin_edge **out, size_t *count,
                                  pelt_error *err)
{
    *out = NULL;
    *count = 0;
    size_t n = 3 * triangle_count;
    uint64_t *keys = pelt__alloc(alloc, (n ? n : 1) * sizeof *keys);
    if (!keys) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for %zu fin edges", n);
    for (size_t t = 0; t < triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            uint64_t a = indices[3 * t + (size_t)k], b = indices[3 * t + (size_t)(k + 1) % 3];
            keys[3 * t + (size_t)k] = a < b ? a << 32 | b : b << 32 | a;
        }
    qsort(keys, n, sizeof *keys, cmp_u64);
    size_t unique = 0;
    for (size_t i = 0; i < n; i++)
        if (i == 0 || keys[i] != keys[i - 1]) keys[unique++] = keys[i];
    pelt__fin_edge *e = pelt__alloc(alloc, (unique ? unique : 1) * sizeof *e);
    if (!e) {
        pelt__free(alloc, keys);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for %zu fins", unique);
    }
    for (size_t i = 0; i < unique; i++) {
        e[i].a = (uint32_t)(keys[i] >> 32);
        e[i].b = (uint32_t)keys[i];
        /* Random per edge, independent of the order edges are found in. */
        e[i].start = (float)(pelt__hash32((uint32_t)keys[i] * 2654435761u ^ (uint32_t)(keys[i] >> 32) ^ seed) >> 8) /
                     16777216.0f;
    }
    pelt__free(alloc, keys);
    *out = e;
    *count = unique;
    return PELT_OK;
}

pelt_vec3 pelt__fin_normal(pelt_vec3 pa, pelt_vec3 pb, pelt_vec3 na, pelt_vec3 nb)
{
    return v3_norm_or(v3_cross(v3_sub(pb, pa), v3_add(na, nb)), na);
}

float pelt__fin_fade(pelt_vec3 fin_normal, pelt_vec3 view_dir)
{
    return fmaxf(0.0f, 2.0f * fabsf(v3_dot(fin_normal, view_dir)) - 1.0f);
}

float pelt__fin_spacing_opacity(float edge, float slab)
{
    if (!(slab > 0.0f) || !(edge < slab)) return 1.0f;
    return edge > 0.0f ? edge / slab : 0.0f;
}

void pelt__fin_normals(const pelt__fin_edge *edges, size_t count, const float *positions, const float *normals,
                       float *out)
{
    for (size_t i = 0; i < count; i++) {
        size_t a = edges[i].a, b = edges[i].b;
        pelt_vec3 n = pelt__fin_normal(v3_load(positions + 3 * a), v3_load(positions + 3 * b),
                                       v3_load(normals + 3 * a), v3_load(normals + 3 * b));
        v3_store(out + 3 * i, n);
    }
}
