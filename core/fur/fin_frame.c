/* One frame of fins (Lengyel et al. 2001 §2.3) for the fin pass: the fins a
 * view shows with their fade, and the displaced strand of every vertex
 * they stand on, worked out once per vertex with the C references of the
 * shell shader (core/fur/fur_shape.c: the same beta + phi + comb and groom
 * as shell_vs.glsl, parity-tested), where the vertex stage would work it
 * out again for every fin that shares the vertex. */
#include "core/fur/fur_gpu.h"

#include "core/base/vec.h"
#include "core/fur/fur_internal.h"
#include "core/fur/fur_shape.h"

#include <math.h>
#include <string.h>

/* Wetness at a uv: the texel GL's NEAREST + CLAMP_TO_EDGE picks. */
static float rho_at(const pelt__wetness *w, float u, float v)
{
    float x = floorf(u * (float)w->width), y = floorf(v * (float)w->height);
    x = fminf(fmaxf(x, 0.0f), (float)w->width - 1.0f);
    y = fminf(fmaxf(y, 0.0f), (float)w->height - 1.0f);
    return w->texels[((size_t)y * w->width + (size_t)x) * 4 + 3];
}

static void put(float *t, pelt_vec3 a, float w)
{
    t[0] = a.x, t[1] = a.y, t[2] = a.z, t[3] = w;
}

size_t pelt__fur_gpu_fin_frame(const pelt_fur *f, const pelt__fin_frame_desc *d, uint32_t *fins, float *vertices)
{
    const pelt__lod_level *l = &f->lod.levels[d->level < f->lod.count ? d->level : 0];
    const pelt_fur_desc *fd = &f->desc;
    const pelt_mesh_data m = pelt_mesh_get_data(f->mesh);
    const float *tangents = pelt_mesh_tangents(f->mesh);
    const pelt_vec3 view = v3_load(d->view_dir);

    /* The fins and their fade, max(0, 2|p| - 1) (pelt__fin_fade). */
    size_t kept = 0;
    const float *pose = f->pose; /* a posed mesh: its own positions, normals, tangents */
    for (size_t i = 0; i < l->fin_count; i++) {
        pelt_vec3 fn = v3_load(l->fin_normals + 3 * i);
        if (pose) {
            size_t a = l->fins[i].a, b = l->fins[i].b;
            fn = pelt__fin_normal(v3_load(pose + 10 * a), v3_load(pose + 10 * b), v3_load(pose + 10 * a + 3),
                                  v3_load(pose + 10 * b + 3));
        }
        if (d->hidden_back) {
            size_t a = l->fins[i].a, b = l->fins[i].b;
            const float *na = pose ? pose + 10 * a + 3 : m.normals + 3 * a;
            const float *nb = pose ? pose + 10 * b + 3 : m.normals + 3 * b;
            if (v3_dot(v3_load(na), view) > PELT__FIN_BACK && v3_dot(v3_load(nb), view) > PELT__FIN_BACK) continue;
        }
        float fade = d->unfaded ? 1.0f : pelt__fin_fade(fn, view);
        if (fade < 0.05f) continue; /* the fragment stage's own cut: nothing to draw */
        uint32_t *t = fins + 4 * kept++;
        t[0] = l->fin_ends[2 * i], t[1] = l->fin_ends[2 * i + 1];
        memcpy(&t[2], &l->fins[i].start, sizeof t[2]);
        memcpy(&t[3], &fade, sizeof t[3]);
    }
    if (kept == 0) return 0;

    /* The strands, as shell_vs.glsl displaces them, at h = r / rows. */
    const bool wet = !pelt__rect_empty(f->wetness->wet);
    const float slant = tanf(fd->comb.slant * 3.14159265f / 180.0f);
    const unsigned rows = d->rows < 1 ? 1 : d->rows > PELT__FIN_HEIGHTS - 1 ? PELT__FIN_HEIGHTS - 1 : d->rows;
    for (size_t c = 0; c < l->fin_vertex_count; c++) {
        size_t i = l->fin_vertices[c];
        float *t = vertices + c * 4 * PELT__FIN_VERTEX_TEXELS;
        const pelt__groom_vertex *g = &f->groom.v[i];
        const float *pv = pose ? pose + 10 * i : NULL;
        const float *ti = pv ? pv + 6 : tangents + 4 * i;
        pelt_vec3 p = v3_load(pv ? pv : m.positions + 3 * i);
        pelt_vec3 n = v3_norm_or(v3_load(pv ? pv + 3 : m.normals + 3 * i), v3(0.0f, 1.0f, 0.0f));
        pelt_vec3 u = v3_norm_or(v3_load(ti), v3(1.0f, 0.0f, 0.0f));
        pelt_vec3 v = v3_scale(v3_cross(n, u), ti[3]);
        pelt_vec3 comb = m.comb ? v3_load(m.comb + 3 * i) : v3_load(ti);
        float rho = wet ? rho_at(f->wetness, m.uvs[2 * i], m.uvs[2 * i + 1]) : 0.0f;
        float s = g->length * fd->fins.length;
        float L = fd->length * s, K = pelt__fur_vertex_curl_radius(fd) * s;
        pelt_vec3 tip = v3_scale(v3_load(f->tips + 3 * i), s);
        pelt_vec3 shear = pelt__fur_groom_shear(comb, slant, u, v, g->lean);
        for (unsigned r = 0; r <= rows; r++) {
            float h = (float)r / (float)rows;
            pelt_vec3 offset = v3_add(v3_add(pelt__fur_bend(n, L, tip, h),
                                             pelt__fur_curl(u, v, fd->look.curl_frequency, K, rho, h)),
                                      pelt__fur_comb(shear, L, 1.0f, h));
            put(t + 8 * r, v3_add(p, offset), 1.0f);
            put(t + 8 * r + 4, pelt__fur_tangent_combed(n, L, tip, u, v, shear, fd->look.curl_frequency, K, rho, 1.0f, h),
                0.0f);
        }
        put(t + 4 * 2 * PELT__FIN_HEIGHTS, n, g->density);
        /* Two bytes a float, as exact integers (float bits could be NaN). */
        float *e = t + 4 * (2 * PELT__FIN_HEIGHTS + 1);
        e[0] = m.uvs[2 * i], e[1] = m.uvs[2 * i + 1];
        e[2] = (float)(g->color[0] * 256u + g->color[1]);
        e[3] = (float)(g->color[2] * 256u + g->color[3]);
    }
    return kept;
}
