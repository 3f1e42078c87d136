/* Rain along -Y and random drops by area on a surface (Silva et al. §3.1 droplets). */
/* Rain falls along the mesh's -Y axis and wets where it hits; random drops land
 * uniformly by surface area; both wet by distance on the surface (seam-free). */
#include "core/wet/rain.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/mesh/triangle_area.h"
#include "core/base/rng.h"
#include "core/base/vec.h"

#include <stdlib.h>

struct pelt__rain {
    pelt_allocator alloc; /* the owner's */
    const pelt_mesh *mesh;
    pelt_rain settings;
    pelt__rng rng;
    double carry;       /* fraction of a drop carried to the next step */
    float *area_cdf;    /* cumulative triangle areas, for random drops */
    float world_per_uv; /* mean world length of one mask-uv unit */
};

/* Stream of the rain's generator (pelt__rng_seed). */
#define RAIN_STREAM 0x7261696eULL

pelt_status pelt__rain_create(const pelt_mesh *m, const pelt_allocator *a, pelt__rain **out, pelt_error *err)
{
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "rain: out is NULL");
    *out = NULL;
    const pelt_mesh_data md = m ? pelt_mesh_get_data(m) : (pelt_mesh_data){0};
    if (!m || !md.positions || !md.uvs || !md.indices || md.triangle_count == 0)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "rain: a mesh with positions, uvs and triangles is required");
    pelt__rain *r = pelt__alloc_zero(a, 1, sizeof *r);
    if (r && a) r->alloc = *a;
    if (r) r->area_cdf = pelt__alloc_zero(a, md.triangle_count, sizeof *r->area_cdf);
    if (!r || !r->area_cdf) {
        pelt__rain_destroy(r);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the fur");
    }
    r->mesh = m;
    double total = 0.0, uv_total = 0.0;
    for (size_t t = 0; t < md.triangle_count; t++) {
        total += pelt__triangle_area(&md, t);
        uv_total += pelt__triangle_area_2d(&md, md.uvs, t);
        r->area_cdf[t] = (float)total;
    }
    /* Mean world length of one mask-uv unit: converts droplet radii given
     * in mask units (pelt_rain) to the world units surface droplets use. */
    r->world_per_uv = uv_total > 0.0 ? (float)sqrt(total / uv_total) : 1.0f;
    r->rng = pelt__rng_seed(1, RAIN_STREAM);
    *out = r;
    return PELT_OK;
}

void pelt__rain_destroy(pelt__rain *r)
{
    if (!r) return;
    pelt_allocator a = r->alloc;
    pelt__free(&a, r->area_cdf);
    pelt__free(&a, r);
}

void pelt__rain_set(pelt__rain *r, const pelt_rain *settings)
{
    r->settings = *settings;
    r->rng = pelt__rng_seed(settings->seed, RAIN_STREAM);
    r->carry = 0.0;
}

void pelt__rain_set_rate(pelt__rain *r, float rate)
{
    r->settings.rate = isfinite(rate) && rate > 0.0f ? rate : 0.0f;
}

/* The settings with defaults filled in: zero radius range -> [0.015, 0.04]
 * uv, zero wetness range -> [0.5, 1]; reversed ranges are swapped. */
static pelt_rain resolve(const pelt_rain *rain)
{
    pelt_rain r = *rain;
    if (r.radius_min == 0.0f && r.radius_max == 0.0f) {
        r.radius_min = 0.015f;
        r.radius_max = 0.04f;
    }
    if (r.wetness_min == 0.0f && r.wetness_max == 0.0f) {
        r.wetness_min = 0.5f;
        r.wetness_max = 1.0f;
    }
    if (r.radius_min > r.radius_max) {
        float t = r.radius_min;
        r.radius_min = r.radius_max;
        r.radius_max = t;
    }
    if (r.wetness_min > r.wetness_max) {
        float t = r.wetness_min;
        r.wetness_min = r.wetness_max;
        r.wetness_max = t;
    }
    return r;
}

static float range(pelt__rng *r, float lo, float hi) { return pelt__rng_range(r, lo, hi); }

size_t pelt__rain_step(pelt__rain *rain, pelt__wetness *mask, pelt__surface_index *index,
                       const pelt__bvh *bvh, float dt)
{
    pelt_rain r = resolve(&rain->settings);
    double want = (double)r.rate * dt;
    if (!(want > 0.0) || !isfinite(want)) return 0;
    rain->carry += want;
    double whole = floor(rain->carry);
    rain->carry -= whole;
    size_t n = whole > (double)PELT__RAIN_MAX_PER_STEP ? PELT__RAIN_MAX_PER_STEP : (size_t)whole;
    float lo[3], hi[3];
    pelt_mesh_bounds(rain->mesh, lo, hi);
    const float down[3] = {0.0f, -1.0f, 0.0f};
    for (size_t i = 0; i < n; i++) {
        float x = range(&rain->rng, lo[0], hi[0]);
        float z = range(&rain->rng, lo[2], hi[2]);
        float origin[3] = {x, hi[1] + 1.0f + (hi[1] - lo[1]), z};
        float radius = range(&rain->rng, r.radius_min, r.radius_max) * rain->world_per_uv;
        float wetness = range(&rain->rng, r.wetness_min, r.wetness_max);
        pelt__droplet_ray(mask, rain->mesh, index, bvh, origin, down, radius, wetness);
    }
    return n;
}

void pelt__rain_random_drops(const pelt__rain *rain, const pelt_rain *settings, unsigned count,
                             pelt__wetness *mask, pelt__surface_index *index)
{
    pelt_rain r = resolve(settings);
    pelt__rng rng = pelt__rng_seed(r.seed, 0x64726f70ULL);
    size_t tris = pelt_mesh_get_data(rain->mesh).triangle_count;
    float total = rain->area_cdf[tris - 1];
    for (unsigned i = 0; i < count; i++) {
        /* A triangle with probability proportional to its area, then a
         * uniform point in it. */
        float pick = pelt__rng_float(&rng) * total;
        size_t a = 0, b = tris - 1;
        while (a < b) {
            size_t mid = a + (b - a) / 2;
            if (rain->area_cdf[mid] <= pick) a = mid + 1;
            else b = mid;
        }
        float s = sqrtf(pelt__rng_float(&rng)), t = pelt__rng_float(&rng);
        float bary[3] = {1.0f - s, s * (1.0f - t), s * t};
        float radius = range(&rng, r.radius_min, r.radius_max) * rain->world_per_uv;
        float wetness = range(&rng, r.wetness_min, r.wetness_max);
        pelt__droplet_surface(mask, rain->mesh, index, a, bary, radius, wetness, NULL);
    }
}
