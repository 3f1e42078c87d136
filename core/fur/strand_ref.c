/* The strand reference: the hairs of the fur texture's tile placed over
 * the surface as the shells tile them, each along the shells' curve at its
 * root (core/fur/strand_ref.h). */
#include "core/fur/strand_ref.h"

#include "core/base/vec.h"
#include "core/fur/fur_internal.h"
#include "core/fur/vertex_strand.h"
#include "core/wet/clump.h"

#include <math.h>
#include <string.h>

unsigned pelt__strand_ref_segments(const pelt_fur *f)
{
    float s = ceilf(8.0f * pelt__fur_curl_turns(&f->desc));
    /* A tuft gathers its hairs within a few layers above its base
     * (pelt__clump_tuft_profile's log term): 8 even pieces cut that bend
     * off with one chord, and the tuft's flanks came out straight. */
    if (!pelt__rect_empty(pelt__water_mask(f->water)->wet) && s < (float)PELT__STRAND_SEGMENTS_WET)
        s = (float)PELT__STRAND_SEGMENTS_WET;
    if (!(s > (float)PELT__STRAND_SEGMENTS_MIN)) return PELT__STRAND_SEGMENTS_MIN;
    return s < (float)PELT__STRAND_SEGMENTS_MAX ? (unsigned)s : PELT__STRAND_SEGMENTS_MAX;
}

size_t pelt__strand_ref_tile(const pelt_fur *f, pelt__furtex_strand *out, size_t cap)
{
    pelt__furtex_desc td = pelt__fur_texture_desc(&f->desc);
    return pelt__furtex_strands(&td, out, cap);
}

/* A triangle in fur-texture coordinates (tiles): its corners and the
 * inverse of its edge matrix, for barycentric weights of a point. */
typedef struct fur_tri {
    float f0[2];
    float inv[4]; /* (w1, w2) = inv * (q - f0) */
    float lo[2], hi[2];
    bool ok;
} fur_tri;

static fur_tri fur_tri_at(const float *uv, const uint32_t *ix)
{
    fur_tri t;
    memset(&t, 0, sizeof t);
    const float *a = uv + 2 * ix[0], *b = uv + 2 * ix[1], *c = uv + 2 * ix[2];
    float e1x = b[0] - a[0], e1y = b[1] - a[1], e2x = c[0] - a[0], e2y = c[1] - a[1];
    float det = e1x * e2y - e2x * e1y;
    if (!(fabsf(det) > 1e-12f) || !isfinite(det)) return t;
    t.f0[0] = a[0], t.f0[1] = a[1];
    t.inv[0] = e2y / det, t.inv[1] = -e2x / det, t.inv[2] = -e1y / det, t.inv[3] = e1x / det;
    for (int k = 0; k < 2; k++) {
        t.lo[k] = fminf(a[k], fminf(b[k], c[k]));
        t.hi[k] = fmaxf(a[k], fmaxf(b[k], c[k]));
    }
    t.ok = true;
    return t;
}

/* Barycentric weights of q; true when q lies in the triangle (edges
 * half-open, so a root on a shared edge belongs to one side only). */
static bool fur_tri_weights(const fur_tri *t, float qx, float qy, float w[3])
{
    float dx = qx - t->f0[0], dy = qy - t->f0[1];
    w[1] = t->inv[0] * dx + t->inv[1] * dy;
    w[2] = t->inv[2] * dx + t->inv[3] * dy;
    w[0] = 1.0f - w[1] - w[2];
    return w[0] > 0.0f && w[1] >= 0.0f && w[2] >= 0.0f;
}

/* The tile strands whose roots lie in a triangle's fur uvs, in every tile
 * it overlaps, one by one. */
typedef struct root_iter {
    const pelt__furtex_strand *tile;
    size_t tile_count, s;
    float inv_size, tx, ty;
    const fur_tri *t;
} root_iter;

static root_iter roots_begin(const fur_tri *t, const pelt__furtex_strand *tile, size_t tile_count, float inv_size)
{
    return (root_iter){tile, tile_count, 0, inv_size, floorf(t->lo[0]), floorf(t->lo[1]), t};
}

/* The next root's strand (NULL at the end) and its weights. */
static const pelt__furtex_strand *roots_next(root_iter *it, float w[3])
{
    while (it->ty <= it->t->hi[1]) {
        while (it->s < it->tile_count) {
            const pelt__furtex_strand *s = &it->tile[it->s++];
            if (fur_tri_weights(it->t, it->tx + s->x * it->inv_size, it->ty + s->y * it->inv_size, w)) return s;
        }
        it->s = 0;
        it->tx += 1.0f;
        if (it->tx > it->t->hi[0]) it->tx = floorf(it->t->lo[0]), it->ty += 1.0f;
    }
    return NULL;
}

size_t pelt__strand_ref_count(const pelt_fur *f, const pelt__furtex_strand *tile, size_t tile_count)
{
    const pelt_mesh_data m = pelt_mesh_get_data(f->mesh);
    const float inv_size = 1.0f / (float)f->desc.look.texture_size;
    size_t n = 0;
    for (size_t t = 0; t < m.triangle_count; t++) {
        fur_tri ft = fur_tri_at(f->fur_uvs, m.indices + 3 * t);
        if (!ft.ok) continue;
        root_iter it = roots_begin(&ft, tile, tile_count, inv_size);
        float w[3];
        while (roots_next(&it, w)) n++;
    }
    return n;
}

static pelt_vec3 mix3(const pelt_vec3 *p, const float w[3])
{
    return v3_add(v3_add(v3_scale(p[0], w[0]), v3_scale(p[1], w[1])), v3_scale(p[2], w[2]));
}

static void put(float *t, pelt_vec3 a, float w)
{
    t[0] = a.x, t[1] = a.y, t[2] = a.z, t[3] = w;
}

/* The tuft a hair belongs to (docs/wetness.md, Tufts), read forward: the
 * clump pulls the hair rooted at atlas uv `root` towards its tip, its
 * centre c plus its lean, by s rho f(h) of the way (f the tuft's profile),
 * roots in place. A hair
 * whose root is dry, outside its clump's radius or a stray is not pulled. */
typedef struct tuft {
    float pull_uv[2]; /* c + lean - root, atlas uv: towards the tuft's tip */
    float rho, s, w, layers;
    bool on;
} tuft;

static tuft tuft_at(const pelt_fur *f, const float root[2], float id)
{
    const pelt__wetness *mask = pelt__water_mask(f->water);
    const float *t = pelt__clump_texel(mask->texels, mask->width, mask->height, root);
    float lean[2];
    pelt__clump_lean(t, pelt__fur_clump_lean(&f->desc), lean);
    tuft k = {{t[0] + lean[0] - root[0], t[1] + lean[1] - root[1]}, t[3], f->desc.wet.clump_tightness,
              f->desc.wet.clump_blend, (float)f->desc.layers, false};
    k.on = k.rho > 0.0f && hypotf(t[0] - root[0], t[1] - root[1]) <= t[2] && !pelt__clump_stray(id, f->desc.wet.strays);
    return k;
}

/* One hair: root weights w in triangle (i0, i1, i2) with vertex strands
 * st, the triangle's map from fur-uv offsets to mesh offsets (du, dv per
 * texel) and from atlas-uv offsets (au, av per unit), the tile strand s. */
static void hair(const pelt_fur *f, const pelt__furtex_desc *td, const pelt_mesh_data *m, const uint32_t *ix,
                 const fin_strand *st, pelt_vec3 du, pelt_vec3 dv, pelt_vec3 au, pelt_vec3 av, float texel,
                 const pelt__furtex_strand *s, const float w[3], int segments, float *out)
{
    float c0[2];
    pelt__furtex_strand_center(td, s, 0.0f, c0);
    const float root_uv[2] = {w[0] * m->uvs[2 * ix[0]] + w[1] * m->uvs[2 * ix[1]] + w[2] * m->uvs[2 * ix[2]],
                              w[0] * m->uvs[2 * ix[0] + 1] + w[1] * m->uvs[2 * ix[1] + 1] +
                                  w[2] * m->uvs[2 * ix[2] + 1]};
    const tuft tf = tuft_at(f, root_uv, s->id);
    pelt_vec3 pts[PELT__STRAND_SEGMENTS_MAX + 1];
    for (int k = 0; k <= segments; k++) {
        float z = s->length * (float)k / (float)segments; /* of the full height */
        pelt_vec3 at[3];
        for (int j = 0; j < 3; j++) at[j] = v3_add(st[j].p, pelt__fur_vertex_strand_offset(&st[j], z));
        float c[2];
        pelt__furtex_strand_center(td, s, z, c);
        /* Its own shape in the tile, carried over the surface. */
        pts[k] = v3_add(mix3(at, w), v3_add(v3_scale(du, c[0] - c0[0]), v3_scale(dv, c[1] - c0[1])));
        if (tf.on) {
            float pull = clampf(tf.s * tf.rho * pelt__clump_tuft_profile(z, tf.w, tf.layers), 0.0f,
                                PELT__CLUMP_MAX_PULL);
            pts[k] = v3_add(pts[k], v3_add(v3_scale(au, tf.pull_uv[0] * pull), v3_scale(av, tf.pull_uv[1] * pull)));
        }
    }
    for (int k = 0; k <= segments; k++) {
        int a = k > 0 ? k - 1 : 0, b = k < segments ? k + 1 : segments;
        float along = (float)k / (float)segments;
        float r = td->strand_radius * (1.0f - td->taper * along);
        pelt_vec3 n0 = mix3((pelt_vec3[3]){st[0].n, st[1].n, st[2].n}, w);
        pelt_vec3 tan = v3_norm_or(v3_sub(pts[b], pts[a]), v3_norm_or(n0, v3(0.0f, 1.0f, 0.0f)));
        put(out + 8 * k, pts[k], r * texel);
        put(out + 8 * k + 4, tan, along);
    }
    float *e = out + 8 * (segments + 1);
    pelt_vec3 n = v3_norm_or(mix3((pelt_vec3[3]){st[0].n, st[1].n, st[2].n}, w), v3(0.0f, 1.0f, 0.0f));
    put(e, n, s->shade);
    e[4] = tf.rho; /* wet hair is darker and shines (strand_vs.glsl) */
    e[5] = s->length; /* of the full height: where along the fur's depth the hair ends */
    float col[4];
    for (int c = 0; c < 4; c++) {
        float x = 0.0f;
        for (int j = 0; j < 3; j++) x += w[j] * (float)f->groom.v[ix[j]].color[c];
        col[c] = floorf(x + 0.5f);
    }
    e[6] = col[0] * 256.0f + col[1];
    e[7] = col[2] * 256.0f + col[3];
}

size_t pelt__strand_ref_build(const pelt_fur *f, const pelt__furtex_strand *tile, size_t tile_count,
                              unsigned segments, float *out, size_t cap)
{
    if (segments < PELT__STRAND_SEGMENTS_MIN) segments = PELT__STRAND_SEGMENTS_MIN;
    if (segments > PELT__STRAND_SEGMENTS_MAX) segments = PELT__STRAND_SEGMENTS_MAX;
    const size_t stride = 4 * (size_t)PELT__STRAND_TEXELS(segments);
    const pelt_mesh_data m = pelt_mesh_get_data(f->mesh);
    const float *tangents = pelt_mesh_tangents(f->mesh);
    const pelt__furtex_desc td = pelt__fur_texture_desc(&f->desc);
    const bool wet = !pelt__rect_empty(pelt__water_mask(f->water)->wet);
    const float slant = tanf(f->desc.comb.slant * 3.14159265f / 180.0f);
    const float inv_size = 1.0f / (float)td.size;
    size_t n = 0;
    for (size_t t = 0; t < m.triangle_count && n < cap; t++) {
        const uint32_t *ix = m.indices + 3 * t;
        fur_tri ft = fur_tri_at(f->fur_uvs, ix);
        if (!ft.ok) continue;
        fin_strand st[3];
        pelt_vec3 p[3];
        float density[3];
        for (int j = 0; j < 3; j++) {
            st[j] = pelt__fur_vertex_strand(f, &m, tangents, wet, slant, 1.0f, ix[j]);
            p[j] = st[j].p;
            density[j] = f->groom.v[ix[j]].density;
        }
        /* Mesh offset of one texel along the fur texture's axes. */
        pelt_vec3 e1 = v3_sub(p[1], p[0]), e2 = v3_sub(p[2], p[0]);
        pelt_vec3 du = v3_scale(v3_add(v3_scale(e1, ft.inv[0]), v3_scale(e2, ft.inv[2])), inv_size);
        pelt_vec3 dv = v3_scale(v3_add(v3_scale(e1, ft.inv[1]), v3_scale(e2, ft.inv[3])), inv_size);
        float texel = sqrtf(v3_len(du) * v3_len(dv));
        /* Mesh offset of one atlas-uv unit: the tufts pull in the mask's uv. */
        fur_tri at = fur_tri_at(m.uvs, ix);
        pelt_vec3 au = v3(0.0f, 0.0f, 0.0f), av = au;
        if (at.ok) {
            au = v3_add(v3_scale(e1, at.inv[0]), v3_scale(e2, at.inv[2]));
            av = v3_add(v3_scale(e1, at.inv[1]), v3_scale(e2, at.inv[3]));
        }
        root_iter it = roots_begin(&ft, tile, tile_count, inv_size);
        float w[3];
        const pelt__furtex_strand *s;
        while (n < cap && (s = roots_next(&it, w))) {
            float keep = w[0] * density[0] + w[1] * density[1] + w[2] * density[2];
            if (keep < 1.0f && !(s->id < keep)) continue; /* groom_keeps */
            hair(f, &td, &m, ix, st, du, dv, au, av, texel, s, w, (int)segments, out + n * stride);
            n++;
        }
    }
    return n;
}
