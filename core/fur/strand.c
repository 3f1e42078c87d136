/* Mass-spring fur strands, one per mesh vertex: Silva et al. §3.2.1,
 * Eq. 2 (sum of forces = m p'') and Eq. 3 (hemisphere constraint). See
 * core/fur/strand.h for units and docs/dynamics.md for the model. */
#include "core/fur/strand.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/noise.h"
#include "core/base/vec.h"
#include "core/base/workers.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Bounds that keep every product finite in float: accelerations and
 * velocities are clamped to these (noise coordinates to PELT__NOISE_MAX). */
#define PELT__ACCEL_MAX 1e9f
#define PELT__RATE_MAX 1e9f
/* Strands stepped together (see pelt__strands_step). */
#define PELT__STRAND_BLOCK 32

struct pelt__strands {
    pelt_allocator alloc; /* the fur's: every array below comes from it */
    size_t count;
    pelt__strand_params params;
    float k_per_mass, c_per_mass; /* spring_k / mass, damping / mass, 1/s^2 and 1/s */

    /* Structure of arrays, [axis][vertex]; all carved from one block. */
    float *root_local[3]; /* mesh-local root positions */
    float *rest_local[3]; /* L0 * n, mesh-local */
    float *root[3];       /* world root positions under the current transform */
    float *normal[3];     /* unit world rest direction (the n of Eq. 3) */
    float *length;        /* world L0 (transform scale included) */
    float *tip[3];        /* world tip position p */
    float *vel[3];        /* world tip velocity */
    float *load;          /* water carried, a multiple of the tip's mass (0: dry) */
    float *offsets;       /* 3 per vertex, mesh-local p - p_root (interleaved for upload) */
    float *gust0[3], *gust1[3]; /* cached gust noise slices at the roots (see gust_slices) */
    float *block;
    pelt__workers *workers; /* the owner's threads for the step, or NULL */

    float model[16];  /* column-major, mesh-local to world */
    float inverse[9]; /* inverse of the 3x3 part, column-major */
    bool dirty;       /* model changed since the world arrays were filled */
    bool gust_valid;  /* gust0/gust1 hold slices gust_t0, gust_t0 + 1 for the current roots */
    int32_t gust_t0;
    float gust_inv_scale;
};

/* ---- small helpers ------------------------------------------------------ */

static float finite_or(float x, float fallback) { return isfinite(x) ? x : fallback; }

/* Non-finite components become 0, then the vector is scaled (by its largest
 * component, so nothing overflows) to at most `limit` per component. */
static pelt_vec3 sanitize(pelt_vec3 a, float limit)
{
    a = v3(finite_or(a.x, 0.0f), finite_or(a.y, 0.0f), finite_or(a.z, 0.0f));
    float m = fmaxf(fabsf(a.x), fmaxf(fabsf(a.y), fabsf(a.z)));
    return m > limit ? v3_scale(a, limit / m) : a;
}

static pelt_vec3 load_soa(float *const arr[3], size_t i) { return v3(arr[0][i], arr[1][i], arr[2][i]); }

static void store_soa(float *const arr[3], size_t i, pelt_vec3 a)
{
    arr[0][i] = a.x;
    arr[1][i] = a.y;
    arr[2][i] = a.z;
}

/* 3x3 part of a column-major 4x4 times a, and the inverse (column-major 3x3). */
static pelt_vec3 mul3(const float m[16], pelt_vec3 a)
{
    return v3(m[0] * a.x + m[4] * a.y + m[8] * a.z, m[1] * a.x + m[5] * a.y + m[9] * a.z,
              m[2] * a.x + m[6] * a.y + m[10] * a.z);
}

static pelt_vec3 mul_inv3(const float inv[9], pelt_vec3 a)
{
    return v3(inv[0] * a.x + inv[3] * a.y + inv[6] * a.z, inv[1] * a.x + inv[4] * a.y + inv[7] * a.z,
              inv[2] * a.x + inv[5] * a.y + inv[8] * a.z);
}

static bool invert3(const float m[16], float inv[9])
{
    /* Columns of the 3x3 part: a, b, c; inverse rows are (b x c, c x a, a x b) / det. */
    pelt_vec3 a = v3(m[0], m[1], m[2]), b = v3(m[4], m[5], m[6]), c = v3(m[8], m[9], m[10]);
    pelt_vec3 r0 = v3_cross(b, c), r1 = v3_cross(c, a), r2 = v3_cross(a, b);
    float det = v3_dot(a, r0);
    if (!isfinite(det) || fabsf(det) < 1e-12f) return false;
    float s = 1.0f / det;
    /* Row i of the inverse is r_i; column-major storage puts element (i, j) at j*3 + i. */
    inv[0] = r0.x * s, inv[3] = r0.y * s, inv[6] = r0.z * s;
    inv[1] = r1.x * s, inv[4] = r1.y * s, inv[7] = r1.z * s;
    inv[2] = r2.x * s, inv[5] = r2.y * s, inv[8] = r2.z * s;
    for (int i = 0; i < 9; i++)
        if (!isfinite(inv[i])) return false;
    return true;
}

/* World root, unit rest direction and world length of vertex i under the
 * current model matrix. */
static void place_root(const pelt__strands *s, size_t i, pelt_vec3 *root, pelt_vec3 *n, float *len)
{
    const float *m = s->model;
    pelt_vec3 r = load_soa(s->root_local, i);
    *root = v3_add(mul3(m, r), v3(m[12], m[13], m[14]));
    pelt_vec3 rest = mul3(m, load_soa(s->rest_local, i));
    float l = v3_len(rest);
    if (!(l > 0.0f && isfinite(l))) {
        /* A degenerate normal: keep a valid (if arbitrary) strand. */
        rest = v3(0.0f, s->params.length, 0.0f);
        l = s->params.length;
    }
    *n = v3_scale(rest, 1.0f / l);
    *len = l;
}

static void write_offset(pelt__strands *s, size_t i, pelt_vec3 tip, pelt_vec3 root)
{
    pelt_vec3 local = mul_inv3(s->inverse, v3_sub(tip, root));
    if (!(isfinite(local.x) && isfinite(local.y) && isfinite(local.z)))
        local = load_soa(s->rest_local, i);
    v3_store(s->offsets + 3 * i, local);
}

/* ---- gusts: seeded value noise in (x, y, z, t) ---------------------------- */

/* What a step needs to evaluate gusts, derived once per call. */
typedef struct gust_frame {
    bool enabled;
    uint32_t seed;
    float inv_scale, amplitude;
    int32_t t0;  /* time lattice cell of the sample time */
    float wt;    /* smoothstep weight between slices t0 and t0 + 1 */
    pelt_vec3 along, side1, side2; /* wind direction and two perpendiculars */
} gust_frame;

static gust_frame make_gust_frame(const pelt_forces *f, uint32_t seed, float time)
{
    gust_frame g;
    memset(&g, 0, sizeof g);
    pelt_vec3 wind = sanitize(v3_load(f->wind), PELT__ACCEL_MAX);
    float strength = finite_or(f->gust_strength, 0.0f);
    strength = clampf(strength, 0.0f, 100.0f);
    float speed = v3_len(wind);
    if (!(strength > 0.0f && speed > 0.0f)) return g;
    float scale = f->gust_scale;
    if (!(isfinite(scale) && scale > 1e-6f)) scale = pelt_forces_default().gust_scale;
    g.enabled = true;
    g.seed = seed;
    g.inv_scale = 1.0f / scale;
    float frequency = clampf(finite_or(f->gust_frequency, 0.0f), 0.0f, 1e4f);
    g.wt = pelt__noise_cell(finite_or(time, 0.0f) * frequency, &g.t0);
    g.amplitude = strength * speed;
    g.along = v3_scale(wind, 1.0f / speed);
    /* Two axes across the wind from the shared basis. Their signs are free
     * (the noise channels are symmetric); negated, a wind along +-X sways
     * along +-Z and -+Y as the gusts always have. */
    pelt_vec3 t, b;
    v3_basis(g.along, &t, &b);
    g.side1 = v3_scale(t, -1.0f);
    g.side2 = v3_scale(b, -1.0f);
    return g;
}

static void gust_slices(const gust_frame *g, pelt_vec3 pos, pelt_vec3 *s0, pelt_vec3 *s1)
{
    /* 4D value noise (x, y, z, time) as the smoothstep blend of the time
     * slices t0 and t0 + 1 (gust_combine): a still mesh caches the slices. */
    pelt_vec3 x = v3_scale(pos, g->inv_scale);
    const float xs[3] = {x.x, x.y, x.z};
    *s0 = pelt__value_noise(g->seed, 3, xs, g->t0, 0);
    *s1 = pelt__value_noise(g->seed, 3, xs, g->t0 + 1, 0);
}

/* Gust = strength * |wind| * (n0 along the wind + half of (n1, n2) across it):
 * the wind swells and slackens (never reverses for strength <= 1) and
 * sways sideways, differently in neighbouring regions. */
static pelt_vec3 gust_combine(const gust_frame *g, pelt_vec3 s0, pelt_vec3 s1)
{
    if (!g->enabled) return v3(0.0f, 0.0f, 0.0f);
    pelt_vec3 n = v3_lerp(s0, s1, g->wt);
    pelt_vec3 a = v3_scale(g->along, n.x);
    a = v3_mad(a, g->side1, 0.5f * n.y);
    a = v3_mad(a, g->side2, 0.5f * n.z);
    return v3_scale(a, g->amplitude);
}

void pelt__gust(const pelt_forces *f, uint32_t seed, const float pos[3], float time, float out[3])
{
    pelt_forces def = pelt_forces_default();
    gust_frame g = make_gust_frame(f ? f : &def, seed, time);
    pelt_vec3 s0 = v3(0.0f, 0.0f, 0.0f), s1 = s0;
    if (g.enabled) gust_slices(&g, v3_load(pos), &s0, &s1);
    v3_store(out, gust_combine(&g, s0, s1));
}

/* ---- create / destroy ----------------------------------------------------- */

static bool params_valid(const pelt__strand_params *p)
{
    return isfinite(p->length) && p->length > 0.0f && isfinite(p->spring_k) && p->spring_k > 0.0f &&
           isfinite(p->mass) && p->mass > 0.0f && isfinite(p->damping) && p->damping >= 0.0f;
}

pelt_status pelt__strands_create(const pelt_mesh *mesh, const pelt__strand_params *p,
                                 const pelt_allocator *alloc, pelt__strands **out, pelt_error *err)
{
    const char *fn = "pelt__strands_create";
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s: out is NULL", fn);
    *out = NULL;
    if (!mesh) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s: mesh is NULL", fn);
    if (!p) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s: params are NULL", fn);
    if (!params_valid(p))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "%s: length %g, spring_k %g and mass %g must be positive, damping %g >= 0", fn,
                          (double)p->length, (double)p->spring_k, (double)p->mass, (double)p->damping);

    pelt__strands *s = pelt__alloc_zero(alloc, 1, sizeof *s);
    if (!s) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", fn);
    const pelt_mesh_data md = pelt_mesh_get_data(mesh);
    size_t n = md.vertex_count;
    if (alloc) s->alloc = *alloc;
    s->count = n;
    s->params = *p;
    s->k_per_mass = fminf(s->params.spring_k / s->params.mass, PELT__RATE_MAX);
    s->c_per_mass = fminf(s->params.damping / s->params.mass, PELT__RATE_MAX);

    /* 3 (root_local) + 3 (rest_local) + 3 (root) + 3 (normal) + 1 (length)
     * + 3 (tip) + 3 (vel) + 6 (gust slices) + 1 (load) + 3 (offsets)
     * floats per vertex. */
    const size_t per_vertex = 29;
    if (n > (size_t)-1 / per_vertex) {
        pelt__free(alloc, s);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: %zu vertices overflow the strand arrays", fn, n);
    }
    s->block = pelt__alloc_zero(alloc, n * per_vertex, sizeof(float));
    if (!s->block) {
        pelt__free(alloc, s);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory for %zu strands", fn, n);
    }
    float *cursor = s->block;
    float **arrays[] = {&s->root_local[0], &s->root_local[1], &s->root_local[2],
                        &s->rest_local[0], &s->rest_local[1], &s->rest_local[2],
                        &s->root[0],       &s->root[1],       &s->root[2],
                        &s->normal[0],     &s->normal[1],     &s->normal[2],
                        &s->length,        &s->tip[0],        &s->tip[1],
                        &s->tip[2],        &s->vel[0],        &s->vel[1],
                        &s->vel[2],        &s->gust0[0],      &s->gust0[1],
                        &s->gust0[2],      &s->gust1[0],      &s->gust1[1],
                        &s->gust1[2],      &s->load};
    for (size_t a = 0; a < sizeof arrays / sizeof arrays[0]; a++) {
        *arrays[a] = cursor;
        cursor += n;
    }
    s->offsets = cursor; /* the remaining 3n floats */

    for (size_t i = 0; i < n; i++) {
        pelt_vec3 r = v3_load(md.positions + 3 * i);
        pelt_vec3 nrm = v3_norm_or(v3_load(md.normals + 3 * i), v3(0.0f, 1.0f, 0.0f));
        store_soa(s->root_local, i, r);
        store_soa(s->rest_local, i, v3_scale(nrm, s->params.length));
    }
    float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    memcpy(s->model, identity, sizeof identity);
    invert3(s->model, s->inverse);
    s->dirty = true;
    pelt__strands_reset(s);
    *out = s;
    return PELT_OK;
}

void pelt__strands_destroy(pelt__strands *s)
{
    if (!s) return;
    pelt_allocator alloc = s->alloc;
    pelt__free(&alloc, s->block);
    pelt__free(&alloc, s);
}

size_t pelt__strands_count(const pelt__strands *s) { return s ? s->count : 0; }

void pelt__strands_set_workers(pelt__strands *s, pelt__workers *w) { s->workers = w; }

pelt__strand_params pelt__strands_params(const pelt__strands *s) { return s->params; }

bool pelt__strands_set_transform(pelt__strands *s, const float model[16])
{
    if (!s || !model) return false;
    for (int i = 0; i < 16; i++)
        if (!isfinite(model[i])) return false;
    float inv[9];
    if (!invert3(model, inv)) return false;
    memcpy(s->model, model, sizeof s->model);
    memcpy(s->inverse, inv, sizeof inv);
    s->dirty = true;
    return true;
}

void pelt__strands_set_pose(pelt__strands *s, const float *positions, const float *normals)
{
    for (size_t i = 0; i < s->count; i++) {
        pelt_vec3 nrm = v3_norm_or(v3_load(normals + 3 * i), v3(0.0f, 1.0f, 0.0f));
        store_soa(s->root_local, i, v3_load(positions + 3 * i));
        store_soa(s->rest_local, i, v3_scale(nrm, s->params.length));
    }
    s->dirty = true;
}

void pelt__strands_reset(pelt__strands *s)
{
    if (!s) return;
    for (size_t i = 0; i < s->count; i++) {
        pelt_vec3 root, n;
        float len;
        place_root(s, i, &root, &n, &len);
        store_soa(s->root, i, root);
        store_soa(s->normal, i, n);
        s->length[i] = len;
        pelt_vec3 tip = v3_mad(root, n, len);
        store_soa(s->tip, i, tip);
        store_soa(s->vel, i, v3(0.0f, 0.0f, 0.0f));
        write_offset(s, i, tip, root);
    }
    s->dirty = false;
    s->gust_valid = false; /* roots may have moved */
}

/* ---- stepping --------------------------------------------------------------- */

/* Silva Eq. 3: projects the tip onto {|d| <= L0, d.n >= 0}, d = p - p_root.
 * The set is a half ball centred on the plane, so the plane projection
 * followed by the radial one is the exact closest point. The velocity
 * relative to the root loses its component into the violated constraint
 * (an inelastic contact). A non-finite state goes back to rest. */
static void project(pelt_vec3 root, pelt_vec3 n, float len, pelt_vec3 v_root, pelt_vec3 *tip,
                    pelt_vec3 *vel)
{
    pelt_vec3 d = v3_sub(*tip, root);
    float dn = v3_dot(d, n);
    if (!isfinite(dn) || !isfinite(v3_dot(*vel, *vel))) {
        *tip = v3_mad(root, n, len);
        *vel = v_root;
        return;
    }
    if (dn < 0.0f) {
        d = v3_mad(d, n, -dn);
        float vn = v3_dot(v3_sub(*vel, v_root), n);
        if (vn < 0.0f) *vel = v3_mad(*vel, n, -vn);
    }
    float d2 = v3_dot(d, d);
    if (d2 > len * len) {
        pelt_vec3 r = v3_scale(d, 1.0f / sqrtf(d2));
        d = v3_scale(r, len);
        float vr = v3_dot(v3_sub(*vel, v_root), r);
        if (vr > 0.0f) *vel = v3_mad(*vel, r, -vr);
        /* Rounding can leave d.n a hair below zero after the scaling. */
        if (v3_dot(d, n) < 0.0f) d = v3_mad(d, n, -v3_dot(d, n));
    }
    *tip = v3_add(root, d);
}

/* One step's inputs, the same for every strand: what the threads share. */
typedef struct step_work {
    pelt__strands *s;
    const gust_frame *gust;
    pelt_vec3 steady, gravity, blow, blow_c;
    float blow_r2;
    bool blowing, moved, refresh_gust;
    float dt, h;
    int substeps;
    float inv_denom;
} step_work;

/* Steps the strands [begin, end): begin is a multiple of the block. */
static void step_range(void *ctx, size_t begin, size_t end)
{
    const step_work *w = ctx;
    pelt__strands *s = w->s;
    const gust_frame *gust = w->gust;
    const pelt_vec3 steady = w->steady, gravity = w->gravity, blow = w->blow, blow_c = w->blow_c;
    const float blow_r2 = w->blow_r2, dt = w->dt, h = w->h, inv_denom = w->inv_denom;
    const bool blowing = w->blowing, moved = w->moved, refresh_gust = w->refresh_gust;
    const int substeps = w->substeps;
    const float km = s->k_per_mass, cm = s->c_per_mass;

    /* Vertices go in blocks, substeps inside a block: the strands are
     * independent, so interleaving them hides the latency of each one's
     * sqrt and division, and a block's state stays in L1. */
    for (size_t first = begin; first < end; first += PELT__STRAND_BLOCK) {
        const size_t nb = end - first < PELT__STRAND_BLOCK ? end - first : PELT__STRAND_BLOCK;
        pelt_vec3 root[PELT__STRAND_BLOCK], n[PELT__STRAND_BLOCK], v_root[PELT__STRAND_BLOCK];
        pelt_vec3 accel[PELT__STRAND_BLOCK], rest[PELT__STRAND_BLOCK];
        pelt_vec3 p[PELT__STRAND_BLOCK], v[PELT__STRAND_BLOCK];
        float len[PELT__STRAND_BLOCK], vmax[PELT__STRAND_BLOCK];
        float k_j[PELT__STRAND_BLOCK], inv_denom_j[PELT__STRAND_BLOCK];
        for (size_t j = 0; j < nb; j++) {
            const size_t i = first + j;
            v_root[j] = v3(0.0f, 0.0f, 0.0f);
            if (moved) {
                /* The root jumps with the mesh; the tip keeps its world position. */
                pelt_vec3 old = load_soa(s->root, i);
                place_root(s, i, &root[j], &n[j], &len[j]);
                v_root[j] = sanitize(v3_scale(v3_sub(root[j], old), 1.0f / dt), PELT__ACCEL_MAX);
                store_soa(s->root, i, root[j]);
                store_soa(s->normal, i, n[j]);
                s->length[i] = len[j];
            } else {
                root[j] = load_soa(s->root, i);
                n[j] = load_soa(s->normal, i);
                len[j] = s->length[i];
            }
            pelt_vec3 g0 = v3(0.0f, 0.0f, 0.0f), g1 = g0;
            if (refresh_gust) {
                gust_slices(gust, root[j], &g0, &g1);
                store_soa(s->gust0, i, g0);
                store_soa(s->gust1, i, g1);
            } else if (gust->enabled) {
                g0 = load_soa(s->gust0, i);
                g1 = load_soa(s->gust1, i);
            }
            pelt_vec3 a = v3_add(steady, gust_combine(gust, g0, g1));
            if (blowing) {
                pelt_vec3 dc = v3_sub(root[j], blow_c);
                float q = 1.0f - v3_dot(dc, dc) / blow_r2;
                if (q > 0.0f) a = v3_mad(a, blow, q * q);
            }
            k_j[j] = km;
            inv_denom_j[j] = inv_denom;
            const float load = s->load[i];
            if (load > 0.0f) {
                /* Water's weight (docs/dynamics.md, Wet fur hangs): the tip
                 * is 1 + load times as heavy; gravity pulls every gram
                 * alike, the spring, the drag and the air's push
                 * accelerate the heavier tip less. */
                const float inv_m = 1.0f / (1.0f + load);
                a = v3_add(gravity, v3_scale(v3_sub(a, gravity), inv_m));
                k_j[j] = km * inv_m;
                inv_denom_j[j] = 1.0f / (1.0f + h * cm * inv_m + h * h * k_j[j]);
            }
            accel[j] = sanitize(a, PELT__ACCEL_MAX);
            rest[j] = v3_mad(root[j], n[j], len[j]); /* p0 of Silva §3.2.1 */
            /* Relative speeds above this cross the tip's whole range in one
             * substep: clamping them loses nothing and bounds the state. */
            vmax[j] = 4.0f * len[j] / h;
            p[j] = load_soa(s->tip, i);
            v[j] = load_soa(s->vel, i);
        }
        for (int k = 0; k < substeps; k++) {
            for (size_t j = 0; j < nb; j++) {
                /* Silva Eq. 2 with f = m a_ext - k (p - p0) - c v. */
                pelt_vec3 force = v3_add(accel[j], v3_scale(v3_sub(p[j], rest[j]), -k_j[j]));
                pelt_vec3 vj = v3_scale(v3_mad(v[j], force, h), inv_denom_j[j]);
                pelt_vec3 rel = v3_sub(vj, v_root[j]);
                float rel2 = v3_dot(rel, rel);
                if (rel2 > vmax[j] * vmax[j]) vj = v3_mad(v_root[j], rel, vmax[j] / sqrtf(rel2));
                pelt_vec3 pj = v3_mad(p[j], vj, h);
                project(root[j], n[j], len[j], v_root[j], &pj, &vj); /* Silva Eq. 3 after every substep */
                p[j] = pj;
                v[j] = vj;
            }
        }
        for (size_t j = 0; j < nb; j++) {
            store_soa(s->tip, first + j, p[j]);
            store_soa(s->vel, first + j, v[j]);
            write_offset(s, first + j, p[j], root[j]);
        }
    }
}

void pelt__strands_step(pelt__strands *s, float dt, const pelt_forces *f, float time)
{
    if (!s || !(dt > 0.0f)) return; /* also rejects NaN */
    if (dt > PELT__STRAND_MAX_DT) dt = PELT__STRAND_MAX_DT;
    pelt_forces def;
    if (!f) {
        def = pelt_forces_default();
        f = &def;
    }
    time = finite_or(time, 0.0f);

    /* Substeps of at most PELT__STRAND_MAX_SUBSTEP, but never more than
     * PELT__STRAND_MAX_SUBSTEPS: longer ones stay stable (implicit below). */
    int substeps = (int)ceilf(dt / PELT__STRAND_MAX_SUBSTEP);
    if (substeps < 1) substeps = 1;
    if (substeps > PELT__STRAND_MAX_SUBSTEPS) substeps = PELT__STRAND_MAX_SUBSTEPS;
    const float h = dt / (float)substeps;

    const pelt_vec3 gravity = sanitize(v3_load(f->gravity), PELT__ACCEL_MAX);
    const pelt_vec3 steady = v3_add(gravity, sanitize(v3_load(f->wind), PELT__ACCEL_MAX));
    /* Gusts are held over the call, sampled mid-way. The noise slices at
     * the roots are cached while the mesh stands still, so a static mesh
     * pays for the noise once per time cell (1 / gust_frequency s). */
    const bool moved = s->dirty;
    const gust_frame gust = make_gust_frame(f, s->params.seed, time + 0.5f * dt);
    const bool refresh_gust = gust.enabled && (moved || !s->gust_valid || s->gust_t0 != gust.t0 ||
                                               s->gust_inv_scale != gust.inv_scale);
    /* The local blow, when there is one. */
    const pelt_vec3 blow = sanitize(v3_load(f->blow), PELT__ACCEL_MAX);
    const pelt_vec3 blow_c = sanitize(v3_load(f->blow_center), 1e30f);
    const float blow_r2 = isfinite(f->blow_radius) ? f->blow_radius * f->blow_radius : 0.0f;
    const bool blowing = blow_r2 > 0.0f && v3_dot(blow, blow) > 0.0f;
    step_work work = {s, &gust, steady, gravity, blow, blow_c, blow_r2, blowing, moved, refresh_gust, dt, h, substeps, 0.0f};
    /* v' = (v + h (a - km (p - p0))) / (1 + h cm + h^2 km): v and p at the end. */
    /* Implicit (backward) Euler for the linear spring-damper: stable for
     * every h, and close to symplectic Euler when h is small. */
    work.inv_denom = 1.0f / (1.0f + h * s->c_per_mass + h * h * s->k_per_mass);
    /* The strands are independent: the threads take contiguous runs of
     * blocks, so no two write the same cache line but at a run's ends. */
    pelt__workers_run(s->workers, step_range, &work, s->count, PELT__STRAND_BLOCK);
    s->dirty = false;
    if (refresh_gust) {
        s->gust_valid = true;
        s->gust_t0 = gust.t0;
        s->gust_inv_scale = gust.inv_scale;
    } else if (moved) {
        s->gust_valid = false; /* the roots moved without gusts: slices stale */
    }
}

const float *pelt__strands_tip_offsets(const pelt__strands *s) { return s->offsets; }

float *pelt__strands_water_load(pelt__strands *s) { return s ? s->load : NULL; }

void pelt__strands_tip_world(const pelt__strands *s, size_t vertex, float out[3])
{
    v3_store(out, load_soa(s->tip, vertex));
}

void pelt__strands_root_world(const pelt__strands *s, size_t vertex, float out[3])
{
    /* Valid after a step or reset; before that the previous transform's root. */
    v3_store(out, load_soa(s->root, vertex));
}
