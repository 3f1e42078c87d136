/* Brushes (Lengyel et al. 2001 §3, "local combing is done by dragging a
 * circle to select an active region, and then dragging the selection ...
 * to add a delta to the c_v of each selected vertex"): comb, length,
 * colour and density strokes with a smooth falloff. The vertices come from
 * the fur's triangle hierarchy (a ball query), each visited once per stroke
 * through a stamp, so a stroke costs what it touches and allocates nothing. */
#include "core/base/error.h"
#include "core/base/vec.h"
#include "core/fur/fur_internal.h"

#include <math.h>

typedef struct stroke {
    pelt_fur *fur;
    const pelt_brush *brush;
    pelt_vec3 center;
    float r2, strength;
    size_t touched, lo, hi;
    pelt_mesh_data mesh;   /* the fur's mesh, read once a stroke */
    const float *tangents; /* its tangent frames, 4 floats a vertex */
} stroke;



/* One vertex under the brush with weight w in (0, 1]. The stored record is
 * changed in place (a stroke over a big mesh touches thousands). */
static void apply(stroke *s, size_t i, float w)
{
    pelt_fur *f = s->fur;
    const pelt_brush *b = s->brush;
    const pelt_mesh_data *m = &s->mesh;
    const float *tangents = s->tangents;
    pelt__groom_vertex *g = &f->groom.v[i];
    switch (b->tool) {
    case PELT_BRUSH_COMB: {
        /* The tangential part of the delta, in the tangent frame (u, v) the
         * shader leans along, per unit of this vertex's hair length. */
        pelt_vec3 n = v3_load(m->normals + 3 * i);
        pelt_vec3 u = v3_load(tangents + 4 * i);
        pelt_vec3 bt = v3_scale(v3_cross(n, u), tangents[4 * i + 3]);
        pelt_vec3 d = v3_load(b->delta);
        d = v3_sub(d, v3_scale(n, v3_dot(d, n)));
        float k = w / (f->desc.length * fmaxf(g->length, 0.05f));
        float a = g->lean[0] + k * v3_dot(d, u), c = g->lean[1] + k * v3_dot(d, bt);
        float len = sqrtf(a * a + c * c);
        float shrink = len > PELT_GROOM_MAX_LEAN ? PELT_GROOM_MAX_LEAN / len : 1.0f;
        g->lean[0] = a * shrink;
        g->lean[1] = c * shrink;
        break;
    }
    case PELT_BRUSH_LENGTH:
        g->length = clampf(g->length + w * b->amount, 0.0f, PELT_GROOM_MAX_LENGTH);
        break;
    case PELT_BRUSH_DENSITY:
        g->density = clampf(g->density + w * (clampf(b->amount, 0.0f, 1.0f) - g->density), 0.0f, 1.0f);
        break;
    case PELT_BRUSH_COLOR: {
        /* Paint over: the new colour covers w of what shows, so the weight
         * grows as a' = a + w (1 - a) and the stored colour is the mix of
         * the old one (weight (1 - w) a) and the paint (weight w). */
        pelt_groom_value v = pelt__groom_get(&f->groom, i);
        float a = v.color[3], a2 = a + w * (1.0f - a);
        for (int k = 0; k < 3; k++)
            v.color[k] = a2 > 0.0f ? ((1.0f - w) * a * v.color[k] + w * b->color[k]) / a2 : b->color[k];
        v.color[3] = a2;
        pelt__groom_pack(&v, g);
        break;
    }
    }
    s->touched++;
    if (i < s->lo) s->lo = i;
    if (i + 1 > s->hi) s->hi = i + 1;
}

static void visit_triangle(size_t t, void *user)
{
    stroke *s = user;
    pelt__groom *g = &s->fur->groom;
    const pelt_mesh_data *m = &s->mesh;
    for (int k = 0; k < 3; k++) {
        uint32_t i = m->indices[3 * t + (size_t)k];
        if (g->stamp[i] == g->stroke) continue;
        g->stamp[i] = g->stroke;
        pelt_vec3 e = v3_sub(v3_load(m->positions + 3 * (size_t)i), s->center);
        float d2 = v3_dot(e, e);
        if (d2 >= s->r2) continue;
        float q = 1.0f - d2 / s->r2;
        apply(s, i, s->strength * q * q);
    }
}

static pelt_status check_brush(const pelt_brush *b, pelt_error *err)
{
    if (!b) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "brush: NULL");
    if ((int)b->tool < 0 || b->tool > PELT_BRUSH_DENSITY)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "brush: unknown tool %d", (int)b->tool);
    if (!(b->radius > 0.0f) || !isfinite(b->radius))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "brush: radius %g must be positive",
                          (double)b->radius);
    if (!(b->strength >= 0.0f && b->strength <= 1.0f))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "brush: strength %g must be in [0, 1]",
                          (double)b->strength);
    const float more[] = {b->delta[0], b->delta[1], b->delta[2], b->amount,
                          b->color[0], b->color[1], b->color[2]};
    for (size_t k = 0; k < sizeof more / sizeof more[0]; k++)
        if (!isfinite(more[k]))
            return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "brush: a value is not finite");
    return PELT_OK;
}

pelt_status pelt_fur_brush(pelt_fur *f, const float center[3], const pelt_brush *b, size_t *touched,
                           pelt_error *err)
{
    if (touched) *touched = 0;
    if (!f || !center) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "brush: fur or centre is NULL");
    pelt_status st = check_brush(b, err);
    if (st != PELT_OK) return st;
    if (!isfinite(center[0]) || !isfinite(center[1]) || !isfinite(center[2]))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "brush: centre is not finite");
    pelt__groom *g = &f->groom;
    if (++g->stroke == 0) {
        /* The stamp wrapped: forget every old visit once in 2^32 strokes. */
        for (size_t i = 0; i < g->count; i++) g->stamp[i] = 0;
        g->stroke = 1;
    }
    stroke s = {f, b, v3_load(center), b->radius * b->radius,
                b->strength > 0.0f ? b->strength : 1.0f, 0, (size_t)-1, 0,
                pelt_mesh_get_data(f->mesh), pelt_mesh_tangents(f->mesh)};
    pelt__bvh_query_ball(f->bvh, center, b->radius, visit_triangle, &s);
    if (s.touched) pelt__groom_changed(g, s.lo, s.hi);
    if (touched) *touched = s.touched;
    return PELT_OK;
}

bool pelt_fur_brush_ray(pelt_fur *f, const float origin[3], const float direction[3],
                        const pelt_brush *b, float hit[3])
{
    float p[3];
    if (check_brush(b, NULL) != PELT_OK || !pelt_fur_pick(f, origin, direction, p)) return false;
    if (hit)
        for (int k = 0; k < 3; k++) hit[k] = p[k];
    return pelt_fur_brush(f, p, b, NULL, NULL) == PELT_OK;
}
