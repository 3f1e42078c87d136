/* Wetness mask: texels, droplets blended by Silva et al. Alg. 1 (§3.1), drying, dirty rect. */
/* Alg. 1 as docs/wetness.md reads it. Painting from an image is core/wet/paint.h, the
 * picture of the mask core/wet/picture.h, rain core/wet/rain.h. No GL here; the
 * renderer uploads the dirty rectangle as RGBA32F. */
#ifndef PELT_CORE_WET_MASK_H
#define PELT_CORE_WET_MASK_H

#include "pelt/wetness.h"

#include <string.h>

/* Default mask resolution (the paper's Table 1 set-up). */
#define PELT__WETNESS_DEFAULT_SIZE 256u

/* Mask layout: width * height texels, row-major, 4 floats each
 * (R, G) = clump centre c in mask uv, B = clump radius r in uv units,
 * A = wetness rho in [0,1]. Texel (i, j) covers uv [i/W,(i+1)/W] x
 * [j/H,(j+1)/H]; row 0 is v = 0, as glTexImage2D takes it. A texel is
 * dry when rho == 0 (its c and r are then stale and ignored). */
typedef struct pelt__wetness {
    pelt_allocator alloc;  /* the owner's; texels and this struct come from it */
    unsigned width, height;
    float *texels;
    /* Bounding box of the wet texels, [x0, x1) x [y0, y1); empty when
     * x0 >= x1. Drying visits only this box. */
    unsigned wet[4];
    /* Union of changed texels since the last pelt__wetness_take_dirty. */
    unsigned dirty[4];
} pelt__wetness;

/* Rectangles of texels {x0, y0, x1, y1}, x1 and y1 exclusive, empty when
 * x0 >= x1 or y0 >= y1: the wet box and the dirty rectangle of a mask. */
static inline void pelt__rect_clear(unsigned r[4]) { r[0] = r[1] = r[2] = r[3] = 0; }
static inline bool pelt__rect_empty(const unsigned r[4]) { return r[0] >= r[2] || r[1] >= r[3]; }

/* r grows to hold add. */
static inline void pelt__rect_union(unsigned r[4], const unsigned add[4])
{
    if (pelt__rect_empty(add)) return;
    if (pelt__rect_empty(r)) {
        memcpy(r, add, 4 * sizeof r[0]);
        return;
    }
    if (add[0] < r[0]) r[0] = add[0];
    if (add[1] < r[1]) r[1] = add[1];
    if (add[2] > r[2]) r[2] = add[2];
    if (add[3] > r[3]) r[3] = add[3];
}

/* r grows to hold texel (x, y). */
static inline void pelt__rect_add_texel(unsigned r[4], unsigned x, unsigned y)
{
    unsigned one[4] = {x, y, x + 1, y + 1};
    pelt__rect_union(r, one);
}

/* Makes a dry mask of width x height texels (0 means 256). The caller frees
 * it with pelt__wetness_destroy. */
pelt_status pelt__wetness_create(unsigned width, unsigned height,
                                 const pelt_allocator *a, pelt__wetness **out, pelt_error *err);
void pelt__wetness_destroy(pelt__wetness *m);

/* Dries every texel (marks the wet box dirty). */
void pelt__wetness_clear(pelt__wetness *m);

/* Blends one droplet into the mask (Alg. 1 as pelt reads it, see
 * docs/wetness.md): every texel whose centre lies within d->radius of
 * d->center (uv distance) is updated; work is proportional to the
 * droplet's bounding box, never to the mask size. wetness is clamped to
 * [-1, 1]; negative droplets only dry. Non-finite fields or a negative
 * radius give PELT_ERR_INVALID_ARGUMENT and leave the mask unchanged.
 * No allocation. */
pelt_status pelt__wetness_add_droplet(pelt__wetness *m, const pelt_droplet *d,
                                      pelt_error *err);

/* As pelt__wetness_add_droplet for n droplets in order, faster for many:
 * the memory of later droplets is fetched while earlier ones blend. All are
 * checked first; a bad one gives PELT_ERR_INVALID_ARGUMENT and changes
 * nothing. No allocation. */
pelt_status pelt__wetness_add_droplets(pelt__wetness *m, const pelt_droplet *d, size_t n,
                                       pelt_error *err);

/* Silva Alg. 1 for one texel t (RGBA as above) and a droplet with centre
 * cd, radius rd and clamped non-zero wetness wd, as docs/wetness.md reads
 * it; returns whether the texel changed. The droplet functions here and in
 * core/wet/surface_droplet.c share it. */
bool pelt__wetness_blend_texel(float *t, const float cd[2], float rd, float wd);

/* Lowers every wet texel's rho by rate * dt (clamped at 0), visiting only
 * the wet bounding box, which then shrinks to the texels still wet.
 * Non-positive or non-finite rate * dt does nothing. No allocation. */
void pelt__wetness_dry(pelt__wetness *m, float rate, float dt);

/* Takes the rectangle of texels changed since the last call:
 * rect = {x0, y0, x1, y1} with x1, y1 exclusive. Returns false (rect
 * untouched) when nothing changed. Resets the dirty rectangle. */
bool pelt__wetness_take_dirty(pelt__wetness *m, unsigned rect[4]);

#endif
