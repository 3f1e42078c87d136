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
#include "core/fur/vertex_strand.h"
#include "core/wet/clump.h"

#include <math.h>
#include <string.h>

static void put(float *t, pelt_vec3 a, float w)
{
    t[0] = a.x, t[1] = a.y, t[2] = a.z, t[3] = w;
}

fin_strand pelt__fur_vertex_strand(const pelt_fur *f, const pelt_mesh_data *m, const float *tangents, bool wet,
                                   float slant, float length_scale, size_t i)
{
    const pelt_fur_desc *fd = &f->desc;
    const pelt__groom_vertex *g = &f->groom.v[i];
    const float *pv = f->pose ? f->pose + 10 * i : NULL; /* a posed mesh: its own frame */
    const float *ti = pv ? pv + 6 : tangents + 4 * i;
    fin_strand st;
    st.p = v3_load(pv ? pv : m->positions + 3 * i);
    st.n = v3_norm_or(v3_load(pv ? pv + 3 : m->normals + 3 * i), v3(0.0f, 1.0f, 0.0f));
    st.u = v3_norm_or(v3_load(ti), v3(1.0f, 0.0f, 0.0f));
    st.v = v3_scale(v3_cross(st.n, st.u), ti[3]);
    pelt_vec3 comb = m->comb ? v3_load(m->comb + 3 * i) : v3_load(ti);
    const pelt__wetness *mask = pelt__water_mask(f->water);
    /* The texel GL's NEAREST + CLAMP_TO_EDGE picks, as the vertex stage reads it. */
    st.rho = wet ? pelt__clump_texel(mask->texels, mask->width, mask->height, m->uvs + 2 * i)[3] : 0.0f;
    float s = g->length * length_scale;
    st.L = fd->length * s;
    st.K = pelt__fur_vertex_curl_radius(fd) * s;
    st.omega = fd->look.curl_frequency;
    st.tip = v3_scale(v3_load(f->tips + 3 * i), s);
    /* Wet fur lies further along the comb (wet_slant in shell_vs.glsl). */
    st.shear = pelt__fur_groom_shear(comb, pelt__fur_wet_slant(slant, pelt__fur_wet_lie(fd), st.rho), st.u, st.v,
                                     g->lean);
    return st;
}

pelt_vec3 pelt__fur_vertex_strand_offset(const fin_strand *st, float h)
{
    return v3_add(v3_add(pelt__fur_bend(st->n, st->L, st->tip, h), pelt__fur_curl(st->u, st->v, st->omega, st->K, st->rho, h)),
                  pelt__fur_comb(st->shear, st->L, 1.0f, h));
}

/* How far the strand strays from its root-to-tip chord: the most of its
 * points at h = 1/4, 1/2, 3/4. */
static float strand_bow(const fin_strand *st)
{
    pelt_vec3 tip = pelt__fur_vertex_strand_offset(st, 1.0f);
    float tt = v3_dot(tip, tip), bow = 0.0f;
    for (int k = 1; k < 4; k++) {
        pelt_vec3 o = pelt__fur_vertex_strand_offset(st, 0.25f * (float)k);
        float t = tt > 0.0f ? fminf(fmaxf(v3_dot(o, tip) / tt, 0.0f), 1.0f) : 0.0f;
        float d = v3_len(v3_sub(o, v3_scale(tip, t)));
        bow = d > bow ? d : bow;
    }
    return bow;
}

size_t pelt__fur_gpu_fin_frame(const pelt_fur *f, const pelt__fin_frame_desc *d, uint32_t *fins, float *vertices,
                               unsigned *rows, size_t *dry)
{
    const pelt__lod_level *l = &f->lod.levels[d->level < f->lod.count ? d->level : 0];
    const pelt_mesh_data m = pelt_mesh_get_data(f->mesh);
    const float *tangents = pelt_mesh_tangents(f->mesh);
    const pelt_vec3 view = v3_load(d->view_dir);

    /* The fins and their fade, max(0, 2|p| - 1) (pelt__fin_fade), fainter
     * where they stand closer than the fin texture's slab. */
    const float slab = f->desc.fins.density / (float)f->desc.look.texture_size;
    /* Dry fins from the front of the table, wet ones from the back. */
    size_t kept = 0, wet_kept = 0;
    const uint8_t *vertex_wet = l == &f->lod.levels[0] ? d->vertex_wet : NULL;
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
        /* Cut on the view's fade alone: close fins are faint one by one
         * but add up along a line of sight, so their spacing must not
         * drop them (docs/gallery-fins.md, Fin spacing). */
        if (fade < PELT__FIN_CUT) continue;
        if (!d->unfaded) {
            size_t a = l->fins[i].a, b = l->fins[i].b;
            pelt_vec3 pa = v3_load(pose ? pose + 10 * a : m.positions + 3 * a);
            pelt_vec3 pb = v3_load(pose ? pose + 10 * b : m.positions + 3 * b);
            fade *= pelt__fin_spacing_opacity(v3_len(v3_sub(pb, pa)) * f->desc.look.tiling, slab);
            if (d->opacity > 0.0f) fade *= d->opacity;
        }
        bool wet_ends = vertex_wet && (vertex_wet[l->fins[i].a] || vertex_wet[l->fins[i].b]);
        uint32_t *t = wet_ends ? fins + 4 * (l->fin_count - ++wet_kept) : fins + 4 * kept++;
        t[0] = l->fin_ends[2 * i], t[1] = l->fin_ends[2 * i + 1];
        memcpy(&t[2], &l->fins[i].start, sizeof t[2]);
        memcpy(&t[3], &fade, sizeof t[3]);
    }
    /* The wet ones after the dry, in the order they came (written from the
     * back, they stand reversed). */
    *dry = kept;
    if (wet_kept) memmove(fins + 4 * kept, fins + 4 * (l->fin_count - wet_kept), 4 * wet_kept * sizeof *fins);
    for (size_t i = kept, j = kept + wet_kept; i + 1 < j; i++) { /* j: one past those left */
        j--;
        uint32_t t[4];
        memcpy(t, fins + 4 * i, sizeof t);
        memcpy(fins + 4 * i, fins + 4 * j, sizeof t);
        memcpy(fins + 4 * j, t, sizeof t);
    }
    kept += wet_kept;
    if (kept == 0) return 0;

    /* The strands, as shell_vs.glsl displaces them: the fewest rows that
     * follow every strand's bow within row_error, then its points. */
    const bool wet = !pelt__rect_empty(pelt__water_mask(f->water)->wet);
    const float slant = tanf(f->desc.comb.slant * 3.14159265f / 180.0f);
    unsigned most = d->rows < 1 ? 1 : d->rows > PELT__FIN_HEIGHTS - 1 ? PELT__FIN_HEIGHTS - 1 : d->rows;
    unsigned n_rows = most;
    if (d->row_error > 0.0f && most > 1) {
        float bow = 0.0f;
        for (size_t c = 0; c < l->fin_vertex_count; c++) {
            fin_strand st = pelt__fur_vertex_strand(f, &m, tangents, wet, slant, f->desc.fins.length, l->fin_vertices[c]);
            float b = strand_bow(&st);
            bow = b > bow ? b : bow;
        }
        /* A straight quad spanning 1/r of a bowed curve misses it by about
         * bow / r^2 (a parabola's sagitta). */
        n_rows = 1;
        while (n_rows < most && bow > d->row_error * (float)(n_rows * n_rows)) n_rows++;
    }
    *rows = n_rows;
    for (size_t c = 0; c < l->fin_vertex_count; c++) {
        size_t i = l->fin_vertices[c];
        float *t = vertices + c * 4 * PELT__FIN_VERTEX_TEXELS;
        const pelt__groom_vertex *g = &f->groom.v[i];
        fin_strand st = pelt__fur_vertex_strand(f, &m, tangents, wet, slant, f->desc.fins.length, i);
        for (unsigned r = 0; r <= n_rows; r++) {
            float h = (float)r / (float)n_rows;
            put(t + 8 * r, v3_add(st.p, pelt__fur_vertex_strand_offset(&st, h)), 1.0f);
            put(t + 8 * r + 4,
                pelt__fur_tangent_combed(st.n, st.L, st.tip, st.u, st.v, st.shear, st.omega, st.K, st.rho, 1.0f, h),
                0.0f);
        }
        put(t + 4 * 2 * PELT__FIN_HEIGHTS, st.n, g->density);
        /* Two bytes a float, as exact integers (float bits could be NaN). */
        float *e = t + 4 * (2 * PELT__FIN_HEIGHTS + 1);
        e[0] = m.uvs[2 * i], e[1] = m.uvs[2 * i + 1];
        e[2] = (float)(g->color[0] * 256u + g->color[1]);
        e[3] = (float)(g->color[2] * 256u + g->color[3]);
    }
    return kept;
}
