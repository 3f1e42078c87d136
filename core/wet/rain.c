/* Rain and random droplets on the fur's surface (Silva §3.1 droplets, made
 * seam-free over an atlas): rain falls along the mesh's -Y axis and wets
 * where it hits; random drops land uniformly by surface area. */
#include "core/fur/fur_internal.h"

#include "core/base/error.h"
#include "core/mesh/mesh_internal.h"
#include "core/base/rng.h"
#include "core/base/vec.h"

#include <stdlib.h>

pelt_status pelt__fur_rain_init(pelt_fur *f, pelt_error *err)
{
    const pelt_mesh *m = f->mesh;
    f->area_cdf = pelt__calloc(m->triangle_count, sizeof *f->area_cdf);
    if (!f->area_cdf) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the fur");
    double total = 0.0, uv_total = 0.0;
    for (size_t t = 0; t < m->triangle_count; t++) {
        total += pelt__triangle_area(m, t);
        uv_total += pelt__triangle_area_2d(m, m->uvs, t);
        f->area_cdf[t] = (float)total;
    }
    /* Mean world length of one mask-uv unit: converts droplet radii given
     * in mask units (pelt_rain) to the world units surface droplets use. */
    f->world_per_uv = uv_total > 0.0 ? (float)sqrt(total / uv_total) : 1.0f;
    f->rain_rng = pelt__rng_seed(1, 0x7261696eULL);
    return PELT_OK;
}

static float range(pelt__rng *r, float lo, float hi) { return pelt__rng_range(r, lo, hi); }

/* Rain: rate * dt drops (fractions carried) from random points above the
 * mesh's bounds, falling along -Y; a drop that misses falls past. */
void pelt__fur_rain_step(pelt_fur *f, float dt)
{
    pelt_rain r = pelt__rain_resolve(&f->rain);
    double want = (double)r.rate * dt;
    if (!(want > 0.0) || !isfinite(want)) return;
    f->rain_carry += want;
    double whole = floor(f->rain_carry);
    f->rain_carry -= whole;
    size_t n = whole > (double)PELT__RAIN_MAX_PER_STEP ? PELT__RAIN_MAX_PER_STEP : (size_t)whole;
    const float *lo = f->mesh->bounds_min, *hi = f->mesh->bounds_max;
    const float down[3] = {0.0f, -1.0f, 0.0f};
    for (size_t i = 0; i < n; i++) {
        float origin[3] = {range(&f->rain_rng, lo[0], hi[0]), hi[1] + 1.0f + (hi[1] - lo[1]),
                           range(&f->rain_rng, lo[2], hi[2])};
        float radius = range(&f->rain_rng, r.radius_min, r.radius_max) * f->world_per_uv;
        float wetness = range(&f->rain_rng, r.wetness_min, r.wetness_max);
        pelt_fur_add_droplet_ray(f, origin, down, radius, wetness);
    }
}

void pelt_fur_add_random_droplets(pelt_fur *f, const pelt_rain *rain, unsigned count)
{
    pelt_rain r = pelt__rain_resolve(rain);
    pelt__rng rng = pelt__rng_seed(r.seed, 0x64726f70ULL);
    size_t tris = f->mesh->triangle_count;
    float total = f->area_cdf[tris - 1];
    for (unsigned i = 0; i < count; i++) {
        /* A triangle with probability proportional to its area, then a
         * uniform point in it. */
        float pick = pelt__rng_float(&rng) * total;
        size_t a = 0, b = tris - 1;
        while (a < b) {
            size_t mid = a + (b - a) / 2;
            if (f->area_cdf[mid] <= pick) a = mid + 1;
            else b = mid;
        }
        float s = sqrtf(pelt__rng_float(&rng)), t = pelt__rng_float(&rng);
        float bary[3] = {1.0f - s, s * (1.0f - t), s * t};
        float radius = range(&rng, r.radius_min, r.radius_max) * f->world_per_uv;
        float wetness = range(&rng, r.wetness_min, r.wetness_max);
        pelt_fur_add_droplet_at(f, a, bary, radius, wetness, NULL);
    }
}
