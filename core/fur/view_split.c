/* Shell triangles drawn apart by the view (pelt__fur_gpu_view_split,
 * fur_gpu.h): those whose shells read the fur texture a second time, where
 * the eye sees the surface from the side (shell_gap, shell_lod.glsl), and
 * those whose shells never do. */
#include "core/fur/fur_gpu.h"

#include "core/base/vec.h"
#include "core/fur/fur_internal.h"
#include "core/fur/lod.h"

#include <math.h>
#include <string.h>

/* Whether the shells over vertex i may read the gap: |N.V| inside the band
 * where shell_gap's weight is above 0, widened by `margin` plus the angle
 * the hair's length, seen from the eye, moves the shell vertex's ray by
 * (the vertex stage takes V at the shell vertex, not at the root). */
static bool vertex_side_on(const pelt_fur *f, const pelt_mesh_data *m, const float *tangents, const float *fit,
                           const pelt__view_split_desc *d, size_t i)
{
    const float *pv = f->pose ? f->pose + 10 * i : NULL;
    pelt_vec3 p = v3_load(pv ? pv : m->positions + 3 * i);
    pelt_vec3 n = v3_norm_or(v3_load(pv ? pv + 3 : m->normals + 3 * i), v3(0.0f, 1.0f, 0.0f));
    if (fit) {
        /* A coarse level's hair stands along its fitted normal (shell_vs.glsl). */
        const float *ti = pv ? pv + 6 : tangents + 4 * i;
        pelt_vec3 u = v3_norm_or(v3_load(ti), v3(1.0f, 0.0f, 0.0f));
        pelt_vec3 v = v3_scale(v3_cross(n, u), ti[3]);
        float nn[3] = {n.x, n.y, n.z}, uu[3] = {u.x, u.y, u.z}, vv[3] = {v.x, v.y, v.z}, out[3];
        pelt__lod_fit_normal(nn, uu, vv, fit + 3 * i, out);
        n = v3(out[0], out[1], out[2]);
    }
    pelt_vec3 world = pelt__mat4_apply(d->model, p, 1.0f);
    pelt_vec3 wn = pelt__mat4_apply(d->model, n, 0.0f);
    pelt_vec3 ray = v3_sub(world, v3_load(d->eye));
    float dist = v3_len(ray), nl = v3_len(wn);
    if (!(dist > 1e-12f) || !(nl > 1e-12f)) return true;
    float vn = fabsf(v3_dot(wn, ray)) / (nl * dist);
    /* The hair's reach in world units over the distance: about the most
     * its shell vertex's ray turns (in radians), taken twice for safety. */
    float reach = f->desc.length * f->groom.v[i].length * d->model_scale;
    float widen = d->margin + 2.0f * reach / dist;
    if (!(vn > PELT__SHELL_GAP_OUTLINE_NONE - widen && vn < PELT__SHELL_GAP_NONE + widen)) return false;
    if (d->shell_spacing > 0.0f) {
        /* The root's clip w, as the vertex stage takes it. */
        const float *r = d->w_row;
        float w = fmaxf(r[0] * world.x + r[1] * world.y + r[2] * world.z + r[3], 1e-6f);
        if (d->shell_spacing * f->groom.v[i].length / w < PELT__SHELL_GAP_PX_NONE * (1.0f - d->margin)) return false;
    }
    return true;
}

static bool triangle_side_on(const uint8_t *vertex_side, const uint32_t *tri)
{
    return vertex_side[tri[0]] == 2 || vertex_side[tri[1]] == 2 || vertex_side[tri[2]] == 2;
}

size_t pelt__fur_gpu_view_split(const pelt_fur *f, const pelt__view_split_desc *d, uint8_t *vertex_side,
                                uint32_t *indices, size_t *total)
{
    const pelt_mesh_data m = pelt_mesh_get_data(f->mesh);
    const float *tangents = pelt_mesh_tangents(f->mesh);
    const uint32_t *tris = m.indices;
    size_t count = m.triangle_count;
    const float *fit = NULL;
    if (!d->full_mesh && d->level < f->lod.count) {
        const pelt__lod_level *l = &f->lod.levels[d->level];
        tris = l->indices;
        count = l->triangle_count;
        fit = l->fit_normals;
    }
    if (d->triangles) tris = d->triangles, count = d->triangle_count;
    for (size_t i = 0; i < m.vertex_count; i++) vertex_side[i] = 0;
    for (size_t t = 0; t < 3 * count; t++) {
        uint32_t i = tris[t];
        if (!vertex_side[i]) vertex_side[i] = vertex_side_on(f, &m, tangents, fit, d, i) ? 2 : 1;
    }
    /* Face-on triangles first, then side-on ones, each part in the order
     * the level gives them (one shell's triangles blend in that order). */
    size_t side = 0;
    for (size_t t = 0; t < count; t++) side += triangle_side_on(vertex_side, tris + 3 * t);
    size_t face = 0, back = count - side;
    for (size_t t = 0; t < count; t++) {
        const uint32_t *tri = tris + 3 * t;
        memcpy(indices + 3 * (triangle_side_on(vertex_side, tri) ? back++ : face++), tri, 3 * sizeof(uint32_t));
    }
    *total = count;
    return face;
}
