/* The water on one fur: mask, clump cells, surface index and rain behind one
 * small API (water.h). */
#include "core/wet/water.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/vec.h"
#include "core/wet/clump_cells.h"
#include "core/wet/paint.h"
#include "core/wet/rain.h"
#include "core/wet/surface_droplet.h"

#include <math.h>
#include <string.h>

struct pelt__water {
    pelt_allocator alloc;
    const pelt_mesh *mesh;
    const pelt__bvh *bvh;
    pelt__wetness *mask;
    pelt__clump_cells *cells; /* natural clumps, or NULL: one clump per droplet */
    pelt__surface_index *surface;
    pelt__rain *rain;
    float dry_rate;
};

pelt_status pelt__water_create(const pelt_mesh *mesh, const pelt__bvh *bvh, const pelt__water_desc *desc,
                               const pelt_allocator *a, pelt__water **out, pelt_error *err)
{
    *out = NULL;
    pelt__water *w = pelt__alloc_zero(a, 1, sizeof *w);
    if (!w) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the water");
    if (a) w->alloc = *a;
    w->mesh = mesh;
    w->bvh = bvh;
    a = &w->alloc; /* never NULL below: the parts keep a copy */
    pelt_status st = pelt__wetness_create(desc->mask_size, desc->mask_size, a, &w->mask, err);
    if (st == PELT_OK && desc->clump_size > 0.0f)
        st = pelt__clump_cells_create(mesh, w->mask->width, w->mask->height, desc->clump_size, desc->seed, a,
                                      &w->cells, err);
    if (st == PELT_OK) st = pelt__surface_index_create(mesh, a, &w->surface, err);
    if (st == PELT_OK) st = pelt__rain_create(mesh, a, &w->rain, err);
    if (st == PELT_OK) *out = w;
    else pelt__water_destroy(w);
    return st;
}

void pelt__water_destroy(pelt__water *w)
{
    if (!w) return;
    pelt__wetness_destroy(w->mask);
    pelt__clump_cells_destroy(w->cells);
    pelt__surface_index_destroy(w->surface);
    pelt__rain_destroy(w->rain);
    pelt_allocator a = w->alloc;
    pelt__free(&a, w);
}

const pelt__wetness *pelt__water_mask(const pelt__water *w) { return w->mask; }

/* Water lands between begin and end, which clumps the cells it touched
 * anew (clump_cells.h). The mask's dirty rectangle is set aside meanwhile,
 * so that what this call changed can be told apart, and is then grown
 * back for the renderer. */
static void begin(pelt__water *w, unsigned saved[4])
{
    memcpy(saved, w->mask->dirty, 4 * sizeof saved[0]);
    if (w->cells) pelt__rect_clear(w->mask->dirty);
}

static void end(pelt__water *w, const unsigned saved[4])
{
    if (!w->cells) return;
    unsigned changed[4];
    memcpy(changed, w->mask->dirty, sizeof changed);
    pelt__clump_cells_apply(w->cells, w->mask, changed);
    pelt__rect_union(w->mask->dirty, saved);
}

pelt_status pelt__water_drop_uv(pelt__water *w, const pelt_droplet *d, size_t n, pelt_error *err)
{
    unsigned saved[4];
    begin(w, saved);
    pelt_status st = n == 1 ? pelt__wetness_add_droplet(w->mask, d, err)
                            : pelt__wetness_add_droplets(w->mask, d, n, err);
    end(w, saved);
    return st;
}

pelt_status pelt__water_drop_at(pelt__water *w, size_t triangle, const float bary[3], float radius_world,
                                float wetness, pelt_error *err)
{
    unsigned saved[4];
    begin(w, saved);
    pelt_status st = pelt__droplet_surface(w->mask, w->mesh, w->surface, triangle, bary, radius_world,
                                           wetness, err);
    end(w, saved);
    return st;
}

bool pelt__water_drop_ray(pelt__water *w, const float origin[3], const float dir[3], float radius_world,
                          float wetness)
{
    unsigned saved[4];
    begin(w, saved);
    bool hit = pelt__droplet_ray(w->mask, w->mesh, w->surface, w->bvh, origin, dir, radius_world, wetness);
    end(w, saved);
    return hit;
}

void pelt__water_random_drops(pelt__water *w, const pelt_rain *rain, unsigned count)
{
    unsigned saved[4];
    begin(w, saved);
    pelt__rain_random_drops(w->rain, rain, count, w->mask, w->surface);
    end(w, saved);
}

pelt_status pelt__water_paint(pelt__water *w, const uint8_t *grey, unsigned width, unsigned height,
                              float wetness, const pelt_allocator *a, pelt_error *err)
{
    if (!grey || width == 0 || height == 0)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "wetness image is empty");
    /* Scale the grey levels by `wetness` into a copy the painter reads. */
    uint8_t *scaled = pelt__alloc_zero(a, (size_t)width * height, 1);
    if (!scaled)
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for a %ux%u image", width, height);
    float k = isfinite(wetness) ? clampf(wetness, 0.0f, 1.0f) : 0.0f;
    for (size_t i = 0; i < (size_t)width * height; i++) scaled[i] = (uint8_t)(grey[i] * k + 0.5f);
    unsigned saved[4];
    begin(w, saved);
    pelt_status st = pelt__wetness_paint_image(w->mask, scaled, width, height, NULL, err);
    end(w, saved);
    pelt__free(a, scaled);
    return st;
}

void pelt__water_step(pelt__water *w, float dt)
{
    unsigned saved[4];
    begin(w, saved);
    pelt__rain_step(w->rain, w->mask, w->surface, w->bvh, dt);
    end(w, saved);
    if (w->dry_rate > 0.0f) pelt__wetness_dry(w->mask, w->dry_rate, dt);
}

void pelt__water_set_rain(pelt__water *w, const pelt_rain *rain) { pelt__rain_set(w->rain, rain); }

void pelt__water_set_rain_rate(pelt__water *w, float rate) { pelt__rain_set_rate(w->rain, rate); }

void pelt__water_set_dry_rate(pelt__water *w, float rate)
{
    w->dry_rate = isfinite(rate) && rate > 0.0f ? rate : 0.0f;
}

void pelt__water_clear(pelt__water *w) { pelt__wetness_clear(w->mask); }

bool pelt__water_take_dirty(pelt__water *w, unsigned rect[4]) { return pelt__wetness_take_dirty(w->mask, rect); }
