/* Per-vertex grooming (Lengyel et al. 2001 §3): the store, the public
 * get/set, and the fields from images and vertex colours. Brushes are in
 * brush.c, groom files in groom_file.c. */
#include "core/fur/groom.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/fur/fur_internal.h"

#include <math.h>
#include <string.h>

static const pelt__groom_vertex untouched = {{0.0f, 0.0f}, 1.0f, 1.0f, {0, 0, 0, 0}};

pelt_status pelt__groom_init(pelt__groom *g, size_t count, const pelt_allocator *alloc,
                             pelt_error *err)
{
    memset(g, 0, sizeof *g);
    g->alloc = *alloc;
    g->count = count;
    g->v = pelt__alloc_zero(alloc, count ? count : 1, sizeof *g->v);
    g->stamp = pelt__alloc_zero(alloc, count ? count : 1, sizeof *g->stamp);
    if (!g->v || !g->stamp) {
        pelt__groom_free(g);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the groom of %zu vertices",
                          count);
    }
    for (size_t i = 0; i < count; i++) g->v[i] = untouched;
    g->version = 1;
    return PELT_OK;
}

void pelt__groom_free(pelt__groom *g)
{
    pelt__free(&g->alloc, g->v);
    pelt__free(&g->alloc, g->stamp);
    g->v = NULL;
    g->stamp = NULL;
    g->count = 0;
}


static uint8_t to_byte(float x) { return (uint8_t)(clampf(x, 0.0f, 1.0f) * 255.0f + 0.5f); }

pelt_groom_value pelt__groom_get(const pelt__groom *g, size_t i)
{
    const pelt__groom_vertex *v = &g->v[i];
    pelt_groom_value r;
    r.length = v->length;
    r.density = v->density;
    r.lean[0] = v->lean[0];
    r.lean[1] = v->lean[1];
    for (int k = 0; k < 4; k++) r.color[k] = v->color[k] / 255.0f;
    return r;
}

bool pelt__groom_pack(const pelt_groom_value *value, pelt__groom_vertex *out)
{
    const float *f = &value->length;
    for (size_t k = 0; k < sizeof *value / sizeof(float); k++)
        if (!isfinite(f[k])) return false;
    out->length = clampf(value->length, 0.0f, PELT_GROOM_MAX_LENGTH);
    out->density = clampf(value->density, 0.0f, 1.0f);
    float a = value->lean[0], b = value->lean[1];
    float m = sqrtf(a * a + b * b);
    float s = m > PELT_GROOM_MAX_LEAN ? PELT_GROOM_MAX_LEAN / m : 1.0f;
    out->lean[0] = a * s;
    out->lean[1] = b * s;
    for (int k = 0; k < 4; k++) out->color[k] = to_byte(value->color[k]);
    return true;
}

void pelt__groom_changed(pelt__groom *g, size_t lo, size_t hi)
{
    if (lo >= hi) return;
    if (g->dirty_lo >= g->dirty_hi) {
        g->dirty_lo = lo;
        g->dirty_hi = hi;
    } else {
        if (lo < g->dirty_lo) g->dirty_lo = lo;
        if (hi > g->dirty_hi) g->dirty_hi = hi;
    }
    g->version++;
}

bool pelt__groom_take_dirty(pelt__groom *g, size_t range[2])
{
    if (g->dirty_lo >= g->dirty_hi) return false;
    range[0] = g->dirty_lo;
    range[1] = g->dirty_hi;
    g->dirty_lo = g->dirty_hi = 0;
    return true;
}

/* ---- the public get / set --------------------------------------------------- */

pelt_groom_value pelt_groom_value_default(void)
{
    pelt_groom_value r = {1.0f, 1.0f, {0.0f, 0.0f}, {0.0f, 0.0f, 0.0f, 0.0f}};
    return r;
}

size_t pelt_fur_vertex_count(const pelt_fur *f) { return f ? f->groom.count : 0; }

pelt_groom_value pelt_fur_get_groom(const pelt_fur *f, size_t vertex)
{
    if (!f || vertex >= f->groom.count) return pelt_groom_value_default();
    return pelt__groom_get(&f->groom, vertex);
}

pelt_status pelt_fur_set_groom(pelt_fur *f, size_t first, size_t count,
                               const pelt_groom_value *values, pelt_error *err)
{
    if (!f || (count && !values))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_fur_set_groom: fur or values is NULL");
    pelt__groom *g = &f->groom;
    if (first > g->count || count > g->count - first)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "pelt_fur_set_groom: vertices %zu..%zu out of range (the mesh has %zu)",
                          first, first + count, g->count);
    pelt__groom_vertex probe;
    for (size_t i = 0; i < count; i++)
        if (!pelt__groom_pack(&values[i], &probe))
            return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                              "pelt_fur_set_groom: value %zu is not finite", i);
    for (size_t i = 0; i < count; i++) pelt__groom_pack(&values[i], &g->v[first + i]);
    pelt__groom_changed(g, first, first + count);
    return PELT_OK;
}

void pelt_fur_reset_groom(pelt_fur *f)
{
    if (!f) return;
    for (size_t i = 0; i < f->groom.count; i++) f->groom.v[i] = untouched;
    pelt__groom_changed(&f->groom, 0, f->groom.count);
}

/* ---- fields from images and vertex colours ---------------------------------- */

/* Bilinear sample of channel c at uv, wrapping; row 0 at v = 1. */
static float sample(const uint8_t *rgba, unsigned w, unsigned h, float u, float v, int c)
{
    float x = (u - floorf(u)) * (float)w - 0.5f;
    float y = (1.0f - (v - floorf(v))) * (float)h - 0.5f;
    float fx = floorf(x), fy = floorf(y);
    float tx = x - fx, ty = y - fy;
    long x0 = (long)fx, y0 = (long)fy;
    float acc = 0.0f;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            long xi = ((x0 + i) % (long)w + (long)w) % (long)w;
            long yj = ((y0 + j) % (long)h + (long)h) % (long)h;
            float wgt = (i ? tx : 1.0f - tx) * (j ? ty : 1.0f - ty);
            acc += wgt * rgba[((size_t)yj * w + (size_t)xi) * 4 + (size_t)c];
        }
    return acc / 255.0f;
}

pelt_status pelt_fur_groom_from_image(pelt_fur *f, pelt_groom_field field, const uint8_t *rgba,
                                      unsigned w, unsigned h, float lo, float hi, pelt_error *err)
{
    if (!f || !rgba || w == 0 || h == 0 || w > 16384 || h > 16384)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "groom image must be 1..16384 texels a side");
    if (!isfinite(lo) || !isfinite(hi) || (int)field < 0 || field > PELT_GROOM_COLOR)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "groom image: bad field or range");
    const float *uvs = pelt_mesh_get_data(f->mesh).uvs;
    pelt__groom *g = &f->groom;
    for (size_t i = 0; i < g->count; i++) {
        float u = uvs[2 * i], v = uvs[2 * i + 1];
        pelt_groom_value val = pelt__groom_get(g, i);
        switch (field) {
        case PELT_GROOM_LENGTH: val.length = lo + sample(rgba, w, h, u, v, 0) * (hi - lo); break;
        case PELT_GROOM_DENSITY: val.density = lo + sample(rgba, w, h, u, v, 0) * (hi - lo); break;
        case PELT_GROOM_FLOW:
            val.lean[0] = (2.0f * sample(rgba, w, h, u, v, 0) - 1.0f) * hi;
            val.lean[1] = (2.0f * sample(rgba, w, h, u, v, 1) - 1.0f) * hi;
            break;
        case PELT_GROOM_COLOR:
            for (int k = 0; k < 4; k++) val.color[k] = sample(rgba, w, h, u, v, k);
            break;
        }
        pelt__groom_pack(&val, &g->v[i]);
    }
    pelt__groom_changed(g, 0, g->count);
    return PELT_OK;
}

pelt_status pelt_fur_groom_from_vertex_colors(pelt_fur *f, pelt_error *err)
{
    const float *c = f ? pelt_mesh_colors(f->mesh) : NULL;
    if (!c) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "the mesh has no vertex colours");
    pelt__groom *g = &f->groom;
    for (size_t i = 0; i < g->count; i++) {
        for (int k = 0; k < 3; k++) g->v[i].color[k] = to_byte(c[4 * i + k]);
        g->v[i].color[3] = 255;
    }
    pelt__groom_changed(g, 0, g->count);
    return PELT_OK;
}
