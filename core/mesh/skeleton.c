/* Skeletons and their animations: sampling keys, the nodes' transforms at
 * a time, linear-blend skinning (core/mesh/skeleton.h). */
#include "core/mesh/skeleton.h"

#include "core/base/error.h"
#include "core/base/vec.h"
#include "core/mesh/mesh_internal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void pelt__skeleton_free(pelt__skeleton *s)
{
    if (!s) return;
    for (uint32_t a = 0; a < s->animation_count; a++) {
        for (uint32_t c = 0; c < s->animations[a].channel_count; c++) {
            free(s->animations[a].channels[c].pos);
            free(s->animations[a].channels[c].rot);
            free(s->animations[a].channels[c].scale);
        }
        free(s->animations[a].channels);
    }
    free(s->animations);
    free(s->parent);
    free(s->rest);
    free(s->rest_trs);
    free(s->bone_node);
    free(s->bone_offset);
    free(s->bones);
    free(s->weights);
    free(s->bind);
    free(s->scratch_globals);
    free(s->scratch_skin);
    free(s);
}

/* ---- matrices (column-major) ------------------------------------------- */

void pelt__trs_matrix(const float t[3], const float q[4], const float s[3], float out[16])
{
    float x = q[0], y = q[1], z = q[2], w = q[3];
    float r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                  2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                  2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
    for (int c = 0; c < 3; c++) {
        for (int i = 0; i < 3; i++) out[4 * c + i] = r[3 * c + i] * s[c];
        out[4 * c + 3] = 0.0f;
    }
    out[12] = t[0], out[13] = t[1], out[14] = t[2], out[15] = 1.0f;
}

bool pelt__matrix_trs(const float m[16], float t[3], float q[4], float s[3])
{
    float r[9];
    for (int c = 0; c < 3; c++) {
        s[c] = sqrtf(m[4 * c] * m[4 * c] + m[4 * c + 1] * m[4 * c + 1] + m[4 * c + 2] * m[4 * c + 2]);
        if (!(s[c] > 0.0f)) return false;
        for (int i = 0; i < 3; i++) r[3 * c + i] = m[4 * c + i] / s[c];
    }
    /* A mirroring matrix: one negative scale keeps r a rotation. */
    float det = r[0] * (r[4] * r[8] - r[7] * r[5]) - r[3] * (r[1] * r[8] - r[7] * r[2]) + r[6] * (r[1] * r[5] - r[4] * r[2]);
    if (det < 0.0f) {
        s[0] = -s[0];
        for (int i = 0; i < 3; i++) r[i] = -r[i];
    }
    t[0] = m[12], t[1] = m[13], t[2] = m[14];
    /* Shepperd's method: the largest of w, x, y, z first. r[3c + i] is row i, column c. */
    float m00 = r[0], m11 = r[4], m22 = r[8], tr = m00 + m11 + m22;
    if (tr > 0.0f) {
        float k = 2.0f * sqrtf(1.0f + tr);
        q[3] = 0.25f * k, q[0] = (r[5] - r[7]) / k, q[1] = (r[6] - r[2]) / k, q[2] = (r[1] - r[3]) / k;
    } else if (m00 > m11 && m00 > m22) {
        float k = 2.0f * sqrtf(1.0f + m00 - m11 - m22);
        q[3] = (r[5] - r[7]) / k, q[0] = 0.25f * k, q[1] = (r[3] + r[1]) / k, q[2] = (r[6] + r[2]) / k;
    } else if (m11 > m22) {
        float k = 2.0f * sqrtf(1.0f + m11 - m00 - m22);
        q[3] = (r[6] - r[2]) / k, q[0] = (r[3] + r[1]) / k, q[1] = 0.25f * k, q[2] = (r[7] + r[5]) / k;
    } else {
        float k = 2.0f * sqrtf(1.0f + m22 - m00 - m11);
        q[3] = (r[1] - r[3]) / k, q[0] = (r[6] + r[2]) / k, q[1] = (r[7] + r[5]) / k, q[2] = 0.25f * k;
    }
    return true;
}

/* ---- keys -------------------------------------------------------------- */

/* Where t falls among n >= 1 keys sorted by time (each `stride` bytes
 * long, its time first): key *i and the way *f towards key *i + 1. Before
 * the first key and from the last on, *f = 0 holds that key. */
static void key_span(const void *keys, size_t stride, uint32_t n, float t, uint32_t *i, float *f)
{
    const char *k = keys;
#define KEY_TIME(j) (*(const float *)(k + (size_t)(j) * stride))
    *f = 0.0f;
    if (n == 1 || t <= KEY_TIME(0)) {
        *i = 0;
        return;
    }
    if (t >= KEY_TIME(n - 1)) {
        *i = n - 1;
        return;
    }
    uint32_t lo = 0, hi = n - 1; /* KEY_TIME(lo) <= t < KEY_TIME(hi) */
    while (hi - lo > 1) {
        uint32_t mid = (lo + hi) / 2;
        if (KEY_TIME(mid) <= t) lo = mid;
        else hi = mid;
    }
    float span = KEY_TIME(lo + 1) - KEY_TIME(lo);
    *i = lo;
    *f = span > 0.0f ? (t - KEY_TIME(lo)) / span : 0.0f;
#undef KEY_TIME
}

void pelt__sample_vec(const pelt__vec_key *k, uint32_t n, float t, const float rest[3], float out[3])
{
    if (n == 0) {
        memcpy(out, rest, 3 * sizeof *out);
        return;
    }
    uint32_t i;
    float f;
    key_span(k, sizeof *k, n, t, &i, &f);
    if (f == 0.0f) {
        memcpy(out, k[i].v, 3 * sizeof *out);
        return;
    }
    for (int c = 0; c < 3; c++) out[c] = k[i].v[c] + (k[i + 1].v[c] - k[i].v[c]) * f;
}

static void slerp(const float a[4], const float b_in[4], float f, float out[4])
{
    float b[4] = {b_in[0], b_in[1], b_in[2], b_in[3]};
    float d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    if (d < 0.0f) { /* the shorter way round */
        d = -d;
        for (int c = 0; c < 4; c++) b[c] = -b[c];
    }
    float wa = 1.0f - f, wb = f;
    if (d < 0.9995f) {
        float th = acosf(d), sn = sinf(th);
        wa = sinf((1.0f - f) * th) / sn;
        wb = sinf(f * th) / sn;
    }
    float l = 0.0f;
    for (int c = 0; c < 4; c++) {
        out[c] = wa * a[c] + wb * b[c];
        l += out[c] * out[c];
    }
    l = sqrtf(l);
    for (int c = 0; c < 4; c++) out[c] = l > 0.0f ? out[c] / l : (c == 3 ? 1.0f : 0.0f);
}

void pelt__sample_quat(const pelt__quat_key *k, uint32_t n, float t, const float rest[4], float out[4])
{
    if (n == 0) {
        memcpy(out, rest, 4 * sizeof *out);
        return;
    }
    uint32_t i;
    float f;
    key_span(k, sizeof *k, n, t, &i, &f);
    if (f == 0.0f) {
        memcpy(out, k[i].q, 4 * sizeof *out);
        return;
    }
    slerp(k[i].q, k[i + 1].q, f, out);
}

/* ---- poses ------------------------------------------------------------- */

void pelt__skeleton_globals(const pelt__skeleton *s, const pelt__animation *a, float seconds, float *globals)
{
    for (uint32_t i = 0; i < s->node_count; i++) memcpy(globals + 16 * i, s->rest + 16 * i, 16 * sizeof *globals);
    if (a)
        for (uint32_t c = 0; c < a->channel_count; c++) {
            const pelt__channel *ch = &a->channels[c];
            const float *trs = s->rest_trs + 10 * ch->node;
            float t[3], q[4], sc[3];
            pelt__sample_vec(ch->pos, ch->pos_count, seconds, trs, t);
            pelt__sample_quat(ch->rot, ch->rot_count, seconds, trs + 3, q);
            pelt__sample_vec(ch->scale, ch->scale_count, seconds, trs + 7, sc);
            pelt__trs_matrix(t, q, sc, globals + 16 * ch->node);
        }
    /* Parents come first: one pass makes the locals global. */
    for (uint32_t i = 0; i < s->node_count; i++)
        if (s->parent[i] >= 0) pelt__mat4_mul(globals + 16 * i, globals + 16 * s->parent[i], globals + 16 * i);
}

/* A vertex's blended bone matrix. */
static void blended(const pelt__skeleton *s, const float *skin, size_t v, float m[16])
{
    memset(m, 0, 16 * sizeof *m);
    for (int k = 0; k < PELT__BONES_PER_VERTEX; k++) {
        float w = s->weights[PELT__BONES_PER_VERTEX * v + k];
        if (w == 0.0f) continue;
        const float *b = skin + 16 * s->bones[PELT__BONES_PER_VERTEX * v + k];
        for (int i = 0; i < 16; i++) m[i] += w * b[i];
    }
}

static void apply(const float m[16], const float p[3], float w, float out[3])
{
    for (int i = 0; i < 3; i++) out[i] = m[i] * p[0] + m[4 + i] * p[1] + m[8 + i] * p[2] + m[12 + i] * w;
}

static void normalize3(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0.0f)
        for (int i = 0; i < 3; i++) v[i] /= l;
}

/* The cofactor matrix's columns (det times the inverse transpose): what
 * carries normals. */
static void cofactor(const float m[16], float c[9])
{
    const float *a = m, *b = m + 4, *d = m + 8; /* columns */
    c[0] = b[1] * d[2] - b[2] * d[1], c[1] = b[2] * d[0] - b[0] * d[2], c[2] = b[0] * d[1] - b[1] * d[0];
    c[3] = d[1] * a[2] - d[2] * a[1], c[4] = d[2] * a[0] - d[0] * a[2], c[5] = d[0] * a[1] - d[1] * a[0];
    c[6] = a[1] * b[2] - a[2] * b[1], c[7] = a[2] * b[0] - a[0] * b[2], c[8] = a[0] * b[1] - a[1] * b[0];
}

void pelt__skeleton_skin(const pelt__skeleton *s, const float *skin, float *positions, float *normals,
                         float *tangents)
{
    for (size_t v = 0; v < s->vertex_count; v++) {
        float m[16], c[9];
        blended(s, skin, v, m);
        const float *b = s->bind + 10 * v;
        apply(m, b, 1.0f, positions + 3 * v);
        cofactor(m, c);
        float *n = normals + 3 * v;
        for (int i = 0; i < 3; i++) n[i] = c[i] * b[3] + c[3 + i] * b[4] + c[6 + i] * b[5];
        normalize3(n);
        if (tangents) {
            float *t = tangents + 4 * v;
            apply(m, b + 6, 0.0f, t);
            normalize3(t);
            t[3] = b[9];
        }
    }
}

/* Inverts a 4x4 affine matrix (last row 0 0 0 1); false when singular. */
static bool invert_affine(const float m[16], float out[16])
{
    float c[9];
    cofactor(m, c);
    float det = m[0] * c[0] + m[1] * c[1] + m[2] * c[2];
    if (!(fabsf(det) > 1e-20f) || !isfinite(det)) return false;
    /* inverse = cofactor^T / det; column j of the inverse is row j of c. */
    for (int col = 0; col < 3; col++)
        for (int row = 0; row < 3; row++) out[4 * col + row] = c[3 * row + col] / det;
    out[3] = out[7] = out[11] = 0.0f;
    for (int i = 0; i < 3; i++) out[12 + i] = -(out[i] * m[12] + out[4 + i] * m[13] + out[8 + i] * m[14]);
    out[15] = 1.0f;
    return true;
}

bool pelt__skeleton_bind(pelt__skeleton *s, const float *positions, const float *normals, const float *tangents)
{
    pelt__skeleton_globals(s, NULL, 0.0f, s->scratch_globals);
    for (uint32_t b = 0; b < s->bone_count; b++)
        pelt__mat4_mul(s->scratch_skin + 16 * b, s->scratch_globals + 16 * s->bone_node[b], s->bone_offset + 16 * b);
    for (size_t v = 0; v < s->vertex_count; v++) {
        float m[16], inv[16], c[9];
        blended(s, s->scratch_skin, v, m);
        if (!invert_affine(m, inv)) return false;
        float *b = s->bind + 10 * v;
        apply(inv, positions + 3 * v, 1.0f, b);
        cofactor(inv, c);
        const float *n = normals + 3 * v;
        for (int i = 0; i < 3; i++) b[3 + i] = c[i] * n[0] + c[3 + i] * n[1] + c[6 + i] * n[2];
        normalize3(b + 3);
        apply(inv, tangents + 4 * v, 0.0f, b + 6);
        normalize3(b + 6);
        b[9] = tangents[4 * v + 3];
    }
    return true;
}

/* ---- copies ------------------------------------------------------------ */

static void *dup(const void *p, size_t bytes, bool *ok)
{
    if (!p || bytes == 0) return NULL;
    void *q = malloc(bytes);
    if (!q) {
        *ok = false;
        return NULL;
    }
    memcpy(q, p, bytes);
    return q;
}

const pelt__skeleton *pelt__mesh_skeleton(const pelt_mesh *mesh) { return mesh ? mesh->skeleton : NULL; }

pelt_status pelt__mesh_copy_skeleton(pelt_mesh *dst, const pelt_mesh *src, const uint32_t *source_vertex,
                                     pelt_error *err)
{
    const pelt__skeleton *s = src->skeleton;
    if (!s) return PELT_OK;
    pelt__skeleton *k = calloc(1, sizeof *k);
    if (!k) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the skeleton");
    dst->skeleton = k;
    bool ok = true;
    size_t nn = s->node_count, nb = s->bone_count ? s->bone_count : 1, nv = dst->vertex_count;
    k->node_count = s->node_count;
    k->parent = dup(s->parent, nn * sizeof *s->parent, &ok);
    k->rest = dup(s->rest, nn * 16 * sizeof(float), &ok);
    k->rest_trs = dup(s->rest_trs, nn * 10 * sizeof(float), &ok);
    k->bone_count = s->bone_count;
    k->real_bones = s->real_bones;
    k->bone_node = dup(s->bone_node, nb * sizeof *s->bone_node, &ok);
    k->bone_offset = dup(s->bone_offset, nb * 16 * sizeof(float), &ok);
    k->animations = s->animation_count ? calloc(s->animation_count, sizeof *k->animations) : NULL;
    if (s->animation_count && !k->animations) ok = false;
    for (uint32_t a = 0; ok && a < s->animation_count; a++) {
        const pelt__animation *sa = &s->animations[a];
        pelt__animation *ka = &k->animations[k->animation_count++];
        memcpy(ka->name, sa->name, sizeof ka->name);
        ka->duration = sa->duration;
        ka->channels = sa->channel_count ? calloc(sa->channel_count, sizeof *ka->channels) : NULL;
        if (sa->channel_count && !ka->channels) ok = false;
        for (uint32_t c = 0; ok && c < sa->channel_count; c++) {
            const pelt__channel *sc = &sa->channels[c];
            pelt__channel *kc = &ka->channels[ka->channel_count++];
            *kc = (pelt__channel){.node = sc->node};
            kc->pos = dup(sc->pos, sc->pos_count * sizeof *sc->pos, &ok);
            kc->rot = dup(sc->rot, sc->rot_count * sizeof *sc->rot, &ok);
            kc->scale = dup(sc->scale, sc->scale_count * sizeof *sc->scale, &ok);
            if (ok) kc->pos_count = sc->pos_count, kc->rot_count = sc->rot_count, kc->scale_count = sc->scale_count;
        }
    }
    k->vertex_count = nv;
    k->bones = calloc(nv, PELT__BONES_PER_VERTEX * sizeof *k->bones);
    k->weights = calloc(nv, PELT__BONES_PER_VERTEX * sizeof *k->weights);
    k->bind = calloc(nv, 10 * sizeof(float));
    k->scratch_globals = calloc(nn ? nn : 1, 16 * sizeof(float));
    k->scratch_skin = calloc(nb, 16 * sizeof(float));
    if (!ok || !k->parent || !k->rest || !k->rest_trs || !k->bone_node || !k->bone_offset || !k->bones ||
        !k->weights || !k->bind || !k->scratch_globals || !k->scratch_skin)
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory for the skeleton");
    for (size_t o = 0; o < nv; o++) {
        size_t i = source_vertex[o];
        if (i >= s->vertex_count) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "skeleton copy: vertex %zu of %zu", i, s->vertex_count);
        memcpy(k->bones + PELT__BONES_PER_VERTEX * o, s->bones + PELT__BONES_PER_VERTEX * i,
               PELT__BONES_PER_VERTEX * sizeof *k->bones);
        memcpy(k->weights + PELT__BONES_PER_VERTEX * o, s->weights + PELT__BONES_PER_VERTEX * i,
               PELT__BONES_PER_VERTEX * sizeof *k->weights);
    }
    k->skinned = 0;
    for (size_t o = 0; o < nv; o++) {
        bool real = false;
        for (int j = 0; j < PELT__BONES_PER_VERTEX; j++)
            real |= k->weights[PELT__BONES_PER_VERTEX * o + j] > 0.0f &&
                    k->bones[PELT__BONES_PER_VERTEX * o + j] < k->real_bones;
        k->skinned += real;
    }
    if (!pelt__skeleton_bind(k, dst->positions, dst->normals, dst->tangents))
        return pelt__fail(err, PELT_ERR_FORMAT, "a vertex's bones have a singular transform");
    return PELT_OK;
}

/* ---- the public calls -------------------------------------------------- */

pelt_skin_info pelt_mesh_skin_info(const pelt_mesh *m)
{
    pelt_skin_info info = {0};
    const pelt__skeleton *s = m ? m->skeleton : NULL;
    if (!s) return info;
    info.bones = s->real_bones;
    info.nodes = s->node_count;
    info.skinned_vertices = s->skinned;
    info.animations = s->animation_count;
    return info;
}

bool pelt_mesh_animation(const pelt_mesh *m, size_t i, pelt_animation_info *out)
{
    const pelt__skeleton *s = m ? m->skeleton : NULL;
    if (!s || i >= s->animation_count || !out) return false;
    memset(out, 0, sizeof *out);
    memcpy(out->name, s->animations[i].name, sizeof out->name);
    out->duration = s->animations[i].duration;
    out->channels = s->animations[i].channel_count;
    return true;
}

pelt_status pelt_mesh_find_animation(const pelt_mesh *m, const char *name_or_index, size_t *index, pelt_error *err)
{
    const pelt__skeleton *s = m ? m->skeleton : NULL;
    if (!name_or_index || !index)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_mesh_find_animation: no name or no index pointer");
    size_t count = s ? s->animation_count : 0;
    for (size_t i = 0; i < count; i++)
        if (!strcmp(s->animations[i].name, name_or_index)) {
            *index = i;
            return PELT_OK;
        }
    char *end = NULL;
    errno = 0;
    unsigned long long n = strtoull(name_or_index, &end, 10);
    if (*name_or_index >= '0' && *name_or_index <= '9' && end && *end == '\0' && errno == 0 && n < count) {
        *index = (size_t)n;
        return PELT_OK;
    }
    if (count == 0)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "no animation '%s': the mesh has no animations",
                          name_or_index);
    char list[256] = "";
    size_t at = 0;
    for (size_t i = 0; i < count && at < sizeof list - 1; i++)
        at += (size_t)snprintf(list + at, sizeof list - at, "%s%zu '%s'", i ? ", " : "", i, s->animations[i].name);
    return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "no animation '%s': the mesh has %s", name_or_index, list);
}

pelt_status pelt_mesh_pose(const pelt_mesh *m, size_t animation, float seconds, float *positions, float *normals,
                           float *tangents, pelt_error *err)
{
    pelt__skeleton *s = m ? m->skeleton : NULL;
    if (!s) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_mesh_pose: the mesh has no skeleton");
    if (animation >= s->animation_count)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_mesh_pose: animation %zu of %u", animation,
                          s->animation_count);
    if (!isfinite(seconds)) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_mesh_pose: time is not finite");
    if (!positions || !normals)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_mesh_pose: positions and normals are needed");
    const pelt__animation *a = &s->animations[animation];
    float t = fmodf(seconds, a->duration);
    if (t < 0.0f) t += a->duration;
    pelt__skeleton_globals(s, a, t, s->scratch_globals);
    for (uint32_t b = 0; b < s->bone_count; b++)
        pelt__mat4_mul(s->scratch_skin + 16 * b, s->scratch_globals + 16 * s->bone_node[b], s->bone_offset + 16 * b);
    pelt__skeleton_skin(s, s->scratch_skin, positions, normals, tangents);
    return PELT_OK;
}
