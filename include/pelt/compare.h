/* pelt — how far a shell picture is from the strand reference: structural
 * similarity, mean error, the silhouette profile, the stripe energy, the
 * outline's grain and the luminance of two RGBA8 pictures of the same
 * view (`pelt compare`, docs/reference.md). Plain C over pixels, no
 * OpenGL. */
#ifndef PELT_COMPARE_H
#define PELT_COMPARE_H

#include "pelt/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An RGBA8 picture, rows top first (what pelt_headless_read_rgba8 gives). */
typedef struct pelt_image {
    const uint8_t *rgba;
    unsigned width, height;
} pelt_image;

/* The silhouette profile's distance bands: band k holds the pixels whose
 * distance d outside the skin's outline is in (2^(k-1), 2^k] pixels
 * (band 0: (0, 1]), so the bands end at 1, 2, 4, ..., 32 pixels. */
#define PELT_COMPARE_BANDS 6

typedef struct pelt_compare_desc {
    pelt_image shells;      /* the shell picture */
    pelt_image strands;     /* the reference: the same hairs as geometry */
    /* The same view with the skin alone (no fur): its pixels that differ
     * from the background are the skin's mask. rgba NULL: no silhouette
     * profile and no stripe energy (NaN in the result). */
    pelt_image skin;
    uint8_t background[3];  /* the clear colour, 0..255 */
    /* How far the fur reaches past the outline in pixels, and the shell
     * count: the shells' spacing is fur_px / layers pixels. fur_px 0: where
     * the strand picture's coverage outside the skin falls below one half. */
    float fur_px;
    unsigned layers;
    pelt_allocator allocator; /* scratch inside the call; zero = malloc/free */
} pelt_compare_desc;

/* Every figure; NaN where it cannot be measured (an empty band, no skin
 * picture, shells closer together than the pixels can show). */
typedef struct pelt_compare_result {
    double ssim;  /* mean SSIM of luminance at half resolution, 1 = the same */
    double mae;   /* mean absolute R, G, B difference, 0..255 */
    float silhouette_px[PELT_COMPARE_BANDS];         /* each band's outer edge, pixels */
    double silhouette_shells[PELT_COMPARE_BANDS];    /* coverage in each band, 0..1 */
    double silhouette_strands[PELT_COMPARE_BANDS];
    float fur_px;              /* the fur_px used (given or measured; 0: none) */
    /* Each picture's own reach past the outline, measured as fur_px 0 is
     * (the last whole distance where at least half the pixels are fur):
     * the two agree on the fur's extent when these are close. */
    float extent_shells_px, extent_strands_px;
    /* The stripe band's low edge, cycles per pixel: the shells' spacing
     * layers / fur_px folded into [0, 0.5], or 0.25 if that is lower. */
    double stripe_frequency;
    double stripe_shells, stripe_strands; /* power in [stripe_frequency, 0.5] across the rim */
    double stripe_energy_ratio;           /* stripe_shells / stripe_strands */
    double luminance_shells, luminance_strands; /* mean luminance of the subject, 0..255 */
    /* The band outside the outline, 1 to fur_px pixels: the mean step in
     * luminance from pixel to pixel along the outline (hairs crossing it
     * side by side against a smooth band) and the band's mean luminance. */
    double outline_grain_shells, outline_grain_strands;
    double outline_grain_ratio; /* outline_grain_shells / outline_grain_strands */
    double outline_luminance_shells, outline_luminance_strands;
    /* The same step outward, along the line to the nearest skin pixel:
       little along a hair that crosses the outline, more across rows. */
    double outline_radial_shells, outline_radial_strands;
} pelt_compare_result;

/* Measures desc->shells against desc->strands. PELT_ERR_INVALID_ARGUMENT
 * when a picture is missing, the sizes differ or a picture is smaller than
 * 22x22 pixels (SSIM's 11x11 window at half resolution);
 * PELT_ERR_OUT_OF_MEMORY when the scratch cannot be allocated (freed
 * before the call returns). */
pelt_status pelt_compare_images(const pelt_compare_desc *desc, pelt_compare_result *out,
                                pelt_error *err);

#ifdef __cplusplus
}
#endif
#endif
