/* Fur texture synthesis (Lengyel et al. 2001 §2.2): hair strands simulated
 * in a tileable box and sampled into one RGBA slice per shell layer. */
#ifndef PELT_FURTEX_H
#define PELT_FURTEX_H

#include "pelt/base.h"

#include <stdbool.h>

typedef struct pelt__furtex_desc {
    unsigned size;        /* slice width = height in texels */
    unsigned layers;      /* shell layers N; the volume has N + 1 slices */
    uint32_t seed;
    float density;        /* strands per tile */
    float strand_radius;  /* texels at the root */
    float taper;          /* 0..1: radius at the tip = (1 - taper) * root radius */
    /* Curly and wavy hair (Lengyel et al. §2.2): every strand winds with
       its own phase psi, so neighbouring strands are out of step. At height
       z (0..1 of the full height) its centre moves sideways by
       curl_radius * (cos(2 pi curl_turns z + psi), sin(...)) (a helix), or
       by curl_radius * sin(2 pi curl_turns z + psi) along u (a wave). */
    float curl_radius;    /* texels, 0 = straight */
    float curl_turns;     /* turns over the full height */
    bool curl_wave;       /* a planar wave along u instead of a helix */
    /* Ringlets (Silva Eq. 4 strand by strand, docs/method.md): the strand
       at height z also moves by pelt__fur_curl_phase in the texture's axes,
       ringlet_radius z (cos(ringlet_omega z + psi), sin(...)) texels, with
       the same phase psi. */
    float ringlet_radius; /* texels at the full height, 0 = none */
    float ringlet_omega;  /* radians over the full height */
    /* Ringlets in locks: a lock of strands about ringlet_lock texels
       across turns in step; 0 = every strand its own phase. In texels,
       not radii, so the curl levels drawn for wet fur (smaller radii)
       keep the same locks and ids. */
    float ringlet_lock;
} pelt__furtex_desc;

/* One simulated strand of the tile, as the volume and the fin texture draw
 * it: its root (texels), its lean (texels of drift over the full height),
 * length (fraction of the full height), shade, id (grooming's density) and
 * curl phase psi (radians). */
typedef struct pelt__furtex_strand {
    float x, y;
    float lean_x, lean_y;
    float length;
    float shade;
    float id;
    float phase;
} pelt__furtex_strand;

/* The strands of the tile in the order they are drawn: up to `cap` into
 * `out` (may be NULL); returns how many the tile holds. Deterministic for
 * the seed; the same strands for every curl. */
size_t pelt__furtex_strands(const pelt__furtex_desc *d, pelt__furtex_strand *out, size_t cap);

/* The locks along a side of the tile (the ringlets' locks: a lock's
 * strands share their phase up to a little of their own); 0 = none. */
int pelt__furtex_lock_cells(const pelt__furtex_desc *d);

/* The centre (texels, unwrapped) of strand s at height z in [0, 1] of the
 * full height: root, lean, curl and ringlet. */
void pelt__furtex_strand_center(const pelt__furtex_desc *d, const pelt__furtex_strand *s, float z,
                                float out[2]);

/* The coverage one sub-sample of a slice's tall filter adds under a disc
 * of radius r (texels) whose centre moves `step` texels to the next of
 * the slice's `samples`: a strand crossing the slab covers the texels it
 * passes over 1 - 2^-4, straight or curled. */
float pelt__furtex_hit_weight(float step, float r, int samples);

/* Number of bytes of the volume: size * size * (layers + 1) * 4, or 0 when
 * that overflows. */
size_t pelt__furtex_bytes(const pelt__furtex_desc *d);

/* Fills `rgba` (pelt__furtex_bytes(d) bytes) with the volume. Slice 0 is
 * the skin, fully opaque; slice n + 1 holds the hair at the height of
 * shell n, h = (1 + n) / N. Channels, premultiplied by coverage A: R =
 * strand shade (0..1), G = height along the strand relative to its
 * length, B = the strand's id, uniform in [0,1] (grooming's density
 * keeps strands whose id is below it); A = coverage. The volume tiles in both texture axes. Deterministic for a seed. */
void pelt__furtex_generate(const pelt__furtex_desc *d, uint8_t *rgba);

/* The fin texture (Lengyel et al. 2001 §2.2): the same hair, seen from the
 * side. The strands of `hair` whose roots lie in a slab of `slab` texels
 * across the tile are composited sideways: hair.size texels along the fin
 * (tileable), `height` rows from the root (row 0) to the tip. The slab's
 * width sets how dense a fin's hair is. `curl` (texels) and `curl_turns`
 * (turns over the full height) bend each strand into a sine with its own
 * phase: fin hair may be curlier than the shells'. Same channels as the
 * volume, premultiplied. */
typedef struct pelt__fintex_desc {
    pelt__furtex_desc hair; /* layers unused */
    unsigned height;        /* rows */
    float slab;             /* texels, > 0 */
    float curl, curl_turns;
} pelt__fintex_desc;

/* width * height * 4, or 0 when a side is 0 or above 8192. */
size_t pelt__fintex_bytes(const pelt__fintex_desc *f);
void pelt__fintex_generate(const pelt__fintex_desc *f, uint8_t *rgba);

#endif
