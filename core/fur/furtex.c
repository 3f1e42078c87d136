/* Lengyel et al. 2001 §2.2: shell textures from geometric hair. Each strand
 * grows from a random root with a random lean, length and shade; each slice
 * integrates the strands over its slab of height (a tall filter: several
 * sub-heights per slice) with a soft-edged disc whose radius tapers towards
 * the tip. Toroidal in x and y so the texture tiles. */
#include "core/fur/furtex.h"

#include "core/base/rng.h"
#include "core/fur/fur_shape.h"

#include <math.h>
#include <string.h>

size_t pelt__furtex_bytes(const pelt__furtex_desc *d)
{
    size_t s = d->size, slices = (size_t)d->layers + 1;
    if (s == 0 || s > 8192 || slices > 1025) return 0;
    return s * s * slices * 4;
}

typedef pelt__furtex_strand strand;

enum { SUBSAMPLES = 4 };

/* The strands of a tile, the same sequence for every slice and for the
 * fin texture: seeded streams for the strand and its id (drawn apart so
 * the strands stay what they were before ids existed); the phase of its
 * curl follows from the id. */
typedef struct strand_stream {
    pelt__rng shape, id;
    float size, radius;
    int locks;        /* lock cells along a side, 0 = no locks */
    uint32_t lock_key;
} strand_stream;

/* Curly hair gathers in locks (docs/method.md, Ringlets): neighbours
 * curl in step, a lock a few curl radii across, so a few large curls make
 * large locks and many small ones small locks. The locks are the cells of
 * a toroidal grid (so the texture still tiles), each with one jittered
 * seed; a strand belongs to the seed nearest its root. */
int pelt__furtex_lock_cells(const pelt__furtex_desc *d)
{
    if (!(d->ringlet_lock > 0.0f)) return 0;
    float n = floorf((float)d->size / d->ringlet_lock + 0.5f);
    return n < 1.0f ? 1 : n > 4096.0f ? 4096 : (int)n;
}

static uint32_t lock_hash(const strand_stream *s, int cx, int cy)
{
    int n = s->locks;
    cx = ((cx % n) + n) % n, cy = ((cy % n) + n) % n;
    return pelt__hash_axis(pelt__hash_axis(s->lock_key, cx, 0x9e3779b1u), cy, 0x85ebca77u);
}

/* The lock of a root at (x, y) texels: its phase fraction in [0, 1). */
static float lock_phase(const strand_stream *s, float x, float y)
{
    float cs = s->size / (float)s->locks;
    int cx = (int)floorf(x / cs), cy = (int)floorf(y / cs);
    float best = 1e30f, f = 0.0f;
    for (int j = -1; j <= 1; j++)
        for (int i = -1; i <= 1; i++) {
            uint32_t h = lock_hash(s, cx + i, cy + j);
            float sx = ((float)(cx + i) + (float)(h & 0xffffu) / 65536.0f) * cs;
            float sy = ((float)(cy + j) + (float)(h >> 16) / 65536.0f) * cs;
            float d2 = (sx - x) * (sx - x) + (sy - y) * (sy - y);
            if (d2 < best) best = d2, f = (float)(pelt__hash32(h) >> 8) / 16777216.0f;
        }
    return f;
}

static strand_stream strands_begin(const pelt__furtex_desc *d)
{
    strand_stream s = {pelt__rng_seed(d->seed, 0x73747261ULL), pelt__rng_seed(d->seed, 0x69647321ULL),
                       (float)d->size, d->strand_radius, pelt__furtex_lock_cells(d),
                       (uint32_t)(d->seed * 0x2545f491u + 0x6c6f636bu)};
    return s;
}

/* density is strands per tile at every texture size: a larger texture
 * holds the same hairs in more texels. */
static size_t strand_count(const pelt__furtex_desc *d)
{
    return (size_t)(d->density + 0.5f);
}

static strand strands_next(strand_stream *s)
{
    strand st;
    st.x = pelt__rng_float(&s->shape) * s->size;
    st.y = pelt__rng_float(&s->shape) * s->size;
    st.lean_x = pelt__rng_range(&s->shape, -1.0f, 1.0f) * s->radius * 2.0f;
    st.lean_y = pelt__rng_range(&s->shape, -1.0f, 1.0f) * s->radius * 2.0f;
    st.length = pelt__rng_range(&s->shape, 0.6f, 1.0f);
    st.shade = pelt__rng_range(&s->shape, 0.4f, 1.0f);
    st.id = pelt__rng_float(&s->id);
    if (s->locks) {
        /* In a lock: the lock's phase, a little of the strand's own, and
         * one of the id's three cycles (pelt__ringlet_phase) at random, so
         * the ids stay spread over [0, 1] for grooming's density. */
        float own = (st.id - 0.5f) * 0.08f;
        float cycle = floorf(pelt__rng_float(&s->id) * 3.0f);
        float f = lock_phase(s, st.x, st.y) + own + cycle + 3.0f;
        st.id = (f - 3.0f * floorf(f / 3.0f)) / 3.0f;
    }
    /* The phase of its curl follows the id as the texture stores it (a
     * byte), so the shells can light the curl (pelt__ringlet_phase). */
    st.phase = pelt__ringlet_phase(floorf(st.id * 255.0f + 0.5f) / 255.0f);
    return st;
}

size_t pelt__furtex_strands(const pelt__furtex_desc *d, pelt__furtex_strand *out, size_t cap)
{
    size_t count = strand_count(d);
    strand_stream stream = strands_begin(d);
    for (size_t i = 0; i < count && i < cap && out; i++) out[i] = strands_next(&stream);
    return count;
}

/* Lengyel §2.2, curly and wavy hair: the strand's own curl at height z. */
void pelt__furtex_strand_center(const pelt__furtex_desc *d, const pelt__furtex_strand *s, float z,
                                float out[2])
{
    out[0] = s->x + s->lean_x * z;
    out[1] = s->y + s->lean_y * z;
    if (d->curl_radius > 0.0f) {
        float a = 6.2831853f * d->curl_turns * z + s->phase;
        if (d->curl_wave) {
            out[0] += d->curl_radius * sinf(a);
        } else {
            out[0] += d->curl_radius * cosf(a);
            out[1] += d->curl_radius * sinf(a);
        }
    }
    if (d->ringlet_radius > 0.0f) {
        pelt_vec3 r = pelt__fur_curl_phase(v3(1.0f, 0.0f, 0.0f), v3(0.0f, 1.0f, 0.0f), d->ringlet_omega,
                                           d->ringlet_radius, 0.0f, z, s->phase);
        out[0] += r.x;
        out[1] += r.y;
    }
}

/* Sub-samples of the tall filter per slice: 4, or enough that a curled
 * strand moves at most about a texel between two of them. */
static int subsamples(const pelt__furtex_desc *d)
{
    if (!(d->curl_radius > 0.0f) && !(d->ringlet_radius > 0.0f)) return SUBSAMPLES;
    /* How fast the centre moves sideways per unit height, at most. */
    float speed = 6.2831853f * fmaxf(d->curl_radius, 0.0f) * fabsf(d->curl_turns) +
                  fmaxf(d->ringlet_radius, 0.0f) * (1.0f + fabsf(d->ringlet_omega));
    float arc = speed / (float)d->layers;
    float n = ceilf(arc / 0.75f);
    return n < SUBSAMPLES ? SUBSAMPLES : n > 64.0f ? 64 : (int)n;
}

/* The share one sub-sample of the tall filter adds under its disc. A
 * texel that a strand crosses all the way through the slab is hit by
 * the m sub-samples whose discs cover it, and is covered 1 - 2^-4 (as
 * four hits of a half cover it): a hair is opaque, however it runs. A
 * straight strand stands over the same texels at every sub-sample (m =
 * samples); a curled one sweeps past, m = (2 r + 1) / step, so each of
 * its few hits must add more. One share for every hit, 2 / samples,
 * made curled hair a third as opaque as straight hair (curls read as
 * felt). A strand that ends inside the slab makes fewer hits: partial. */
float pelt__furtex_hit_weight(float step, float r, int samples)
{
    float m = (2.0f * r + 1.0f) / fmaxf(step, 1e-6f);
    if (m > (float)samples) m = (float)samples;
    if (m < 1.0f) m = 1.0f;
    return 1.0f - exp2f(-(float)SUBSAMPLES / m);
}

/* Adds a soft-edged disc of radius r at (cx, cy) to a w x h image, wrapping
 * in x, and in y when wrap_y (else clipped). Coverage is accumulated as a
 * union in the alpha byte; the strand covering a texel most sets its shade,
 * height along the strand and id (red, green, blue). */
static void splat(uint8_t *img, unsigned w, unsigned h, bool wrap_y, float cx, float cy, float r,
                  float weight, float shade, float along, float id)
{
    int x0 = (int)floorf(cx - r - 1.0f), x1 = (int)ceilf(cx + r + 1.0f);
    int y0 = (int)floorf(cy - r - 1.0f), y1 = (int)ceilf(cy + r + 1.0f);
    int nw = (int)w, nh = (int)h;
    for (int y = y0; y <= y1; y++) {
        if (!wrap_y && (y < 0 || y >= nh)) continue;
        for (int x = x0; x <= x1; x++) {
            float dx = (float)x + 0.5f - cx, dy = (float)y + 0.5f - cy;
            float c = r + 0.5f - sqrtf(dx * dx + dy * dy);
            if (c <= 0.0f) continue;
            c = (c > 1.0f ? 1.0f : c) * weight;
            int wx = ((x % nw) + nw) % nw, wy = ((y % nh) + nh) % nh;
            uint8_t *t = img + ((size_t)wy * w + (size_t)wx) * 4;
            float old = t[3] / 255.0f;
            if (c >= old) {
                t[0] = (uint8_t)(shade * 255.0f + 0.5f);
                t[1] = (uint8_t)(along * 255.0f + 0.5f);
                t[2] = (uint8_t)(id * 255.0f + 0.5f);
            }
            t[3] = (uint8_t)((old + c * (1.0f - old)) * 255.0f + 0.5f);
        }
    }
}

/* Premultiply by coverage so mipmaps average colour correctly (a
 * straight-alpha average would mix in the black of empty texels). */
static void premultiply(uint8_t *img, size_t texels)
{
    for (size_t i = 0; i < texels; i++) {
        uint8_t *t = img + i * 4;
        t[0] = (uint8_t)((t[0] * t[3] + 127) / 255);
        t[1] = (uint8_t)((t[1] * t[3] + 127) / 255);
        t[2] = (uint8_t)((t[2] * t[3] + 127) / 255);
    }
}

void pelt__furtex_generate(const pelt__furtex_desc *d, uint8_t *rgba)
{
    size_t texels = (size_t)d->size * d->size;
    size_t bytes = pelt__furtex_bytes(d);
    if (bytes == 0) return;
    memset(rgba, 0, bytes);

    pelt__rng rng = pelt__rng_seed(d->seed, 0x6675722dULL);
    size_t count = strand_count(d);
    int samples = subsamples(d);

    /* Skin: opaque, dark roots with a little noise. */
    for (size_t i = 0; i < texels; i++) {
        rgba[i * 4 + 0] = (uint8_t)(90 + (pelt__rng_next(&rng) & 31));
        rgba[i * 4 + 1] = 0;
        rgba[i * 4 + 2] = 255;
        rgba[i * 4 + 3] = 255;
    }

    for (unsigned layer = 0; layer < d->layers; layer++) {
        uint8_t *slice = rgba + (size_t)(layer + 1) * texels * 4;
        /* The slab of this shell spans heights (n/N, (n+1)/N]. */
        float z_lo = (float)layer / (float)d->layers;
        float z_hi = (float)(layer + 1) / (float)d->layers;
        /* The same strands for every slice. */
        strand_stream stream = strands_begin(d);
        for (size_t s = 0; s < count; s++) {
            strand st = strands_next(&stream);
            if (z_lo >= st.length) continue;
            float dz = (z_hi - z_lo) / (float)samples, c[2], next[2];
            pelt__furtex_strand_center(d, &st, z_lo + 0.5f * dz, next);
            for (int k = 0; k < samples; k++) {
                float z = z_lo + dz * ((float)k + 0.5f);
                if (z > st.length) break;
                float along = z / st.length;
                float r = d->strand_radius * (1.0f - d->taper * along);
                if (r < 0.15f) r = 0.15f;
                c[0] = next[0];
                c[1] = next[1];
                pelt__furtex_strand_center(d, &st, z + dz, next);
                /* Thin discs still cover a fraction of a texel. */
                float weight = r < 0.5f ? r * 2.0f : 1.0f;
                splat(slice, d->size, d->size, true, c[0], c[1], r,
                      weight * pelt__furtex_hit_weight(hypotf(next[0] - c[0], next[1] - c[1]), r, samples),
                      st.shade, along, st.id);
            }
        }
        premultiply(slice, texels);
    }
}

size_t pelt__fintex_bytes(const pelt__fintex_desc *f)
{
    size_t w = f->hair.size, h = f->height;
    if (w == 0 || w > 8192 || h == 0 || h > 8192) return 0;
    return w * h * 4;
}

/* Lengyel et al. §2.2, the fin texture: the strands rooted in a slab of
 * the tile (root y in [0, slab)) seen from the side, x along the fin and
 * the height up the image (row 0 at the root). Curl adds a sideways sine
 * with a phase per strand, so fin hair can be curlier than shell hair. */
void pelt__fintex_generate(const pelt__fintex_desc *f, uint8_t *rgba)
{
    size_t bytes = pelt__fintex_bytes(f);
    if (bytes == 0) return;
    memset(rgba, 0, bytes);
    const pelt__furtex_desc *d = &f->hair;
    unsigned w = d->size, h = f->height;
    float slab = f->slab > 0.0f ? fminf(f->slab, (float)d->size) : 1.0f;
    size_t count = strand_count(d);
    strand_stream stream = strands_begin(d);
    pelt__rng phase = pelt__rng_seed(d->seed, 0x66696e21ULL);
    /* Steps of half a texel up the strand; the radius in texels of the fin
     * is the shell's (both textures tile the same world width). */
    for (size_t s = 0; s < count; s++) {
        strand st = strands_next(&stream);
        float ph = pelt__rng_float(&phase) * 6.2831853f;
        if (st.y >= slab) continue;
        /* Half a texel up the strand, or finer where its curl sweeps it
         * sideways faster than it climbs. */
        float sweep = 6.2831853f * (d->curl_radius * fabsf(d->curl_turns) + f->curl * fabsf(f->curl_turns)) +
                      d->ringlet_radius * (1.0f + fabsf(d->ringlet_omega));
        int steps = (int)ceilf(st.length * fmaxf((float)h, sweep) * 2.0f);
        for (int k = 0; k <= steps; k++) {
            float z = st.length * (float)k / (float)(steps > 0 ? steps : 1);
            float along = z / st.length;
            float r = d->strand_radius * (1.0f - d->taper * along);
            if (r < 0.15f) r = 0.15f;
            float c[2];
            pelt__furtex_strand_center(d, &st, z, c);
            float cx = c[0] + f->curl * sinf(f->curl_turns * 6.2831853f * z + ph);
            float weight = r < 0.5f ? r * 2.0f : 1.0f;
            splat(rgba, w, h, false, cx, z * (float)h, r, weight * 0.5f, st.shade, along, st.id);
        }
    }
    premultiply(rgba, (size_t)w * h);
}
