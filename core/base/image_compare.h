/* The measures of pelt/compare.h, one function each, over RGBA8 pictures
 * (rows top first). pelt_compare_images calls them; the tests call them
 * with synthetic pictures. */
#ifndef PELT_BASE_IMAGE_COMPARE_H
#define PELT_BASE_IMAGE_COMPARE_H

#include "pelt/compare.h"

/* A pixel "differs from the background" when one of its R, G, B channels
 * is more than this many levels from it: the coverage of the silhouette
 * profile, the skin's mask, the subject whose luminance is measured. */
#define PELT__COVERAGE_THRESHOLD 8

/* No skin pixel in the picture: what pelt__distance_outside writes. */
#define PELT__FAR 1e30f
#define PELT__NO_PIXEL UINT32_MAX

/* Luminance of an RGB pixel, 0..255 (ITU-R BT.601 weights, as Wang et
 * al.'s reference code converts colour to grey). */
double pelt__luma(const uint8_t *px);

bool pelt__pixel_differs(const uint8_t *px, const uint8_t background[3]);

/* Mean SSIM of two pictures' luminance at half resolution (Wang et al.
 * 2004): NaN when the half-size picture is smaller than the 11x11 window,
 * or when the scratch cannot be allocated (*out_of_memory set then). */
double pelt__image_ssim(const uint8_t *a, const uint8_t *b, unsigned w, unsigned h,
                        const pelt_allocator *alloc, bool *out_of_memory);

/* Mean absolute difference over the R, G and B channels, 0..255. */
double pelt__image_mae(const uint8_t *a, const uint8_t *b, unsigned w, unsigned h);

/* The Euclidean distance of every pixel centre to the nearest pixel of
 * `mask` (non-zero bytes, w*h), 0 on the mask, PELT__FAR without a mask
 * pixel; `nearest` (may be NULL) gets that pixel's index y*w+x, or
 * PELT__NO_PIXEL. False when the scratch cannot be allocated. */
bool pelt__distance_outside(const uint8_t *mask, unsigned w, unsigned h, float *dist,
                            uint32_t *nearest, const pelt_allocator *alloc);

/* Fraction of the pixels of each distance band (pelt/compare.h) that
 * differ from the background; NaN for a band with no pixel. */
void pelt__silhouette_profile(const uint8_t *rgba, unsigned w, unsigned h, const float *dist,
                              const uint8_t background[3],
                              double coverage[PELT_COMPARE_BANDS]);

/* How far the fur reaches past the outline, in whole pixels: the last d
 * such that at each distance [1, 2), ..., [d, d + 1) at least half of the
 * pixels differ from the background; 0 when [1, 2) is not covered so, or
 * when no band below PELT__MAX_FUR_PX falls below one half. */
#define PELT__MAX_FUR_PX 1024
float pelt__fur_extent(const uint8_t *rgba, unsigned w, unsigned h, const float *dist,
                       const uint8_t background[3]);

/* The stripe energy: the power of the luminance along the outline's
 * normals across the grazing rim, between `low` and 0.5 cycles per pixel,
 * averaged over the normals. Each profile runs from fur_px pixels outside
 * the outline, through its nearest skin pixel, to fur_px pixels inside
 * (where the fur is seen at a grazing angle and shells show as rows), its
 * least-squares line removed, under a Hann window; its periodogram's bins
 * k / (2 fur_px) in [low, 0.5] are summed (never below two cycles over the
 * profile). NaN when fur_px < 4, low is outside [0, 0.5] or no profile
 * fits in the picture. */
double pelt__stripe_energy(const uint8_t *rgba, unsigned w, unsigned h, const float *dist,
                           const uint32_t *nearest, float fur_px, double low);

/* The outline's grain: the mean step in luminance from each pixel of the
 * band outside the outline (distance 1 to fur_px) to the next pixel along
 * the outline (across its normal to the nearest skin pixel): hairs that
 * cross the outline side by side step from hair to gap, a smooth band
 * does not. *band_luminance and *along_normal (either may be NULL) get
 * the band's mean luminance and its mean step to the next pixel outward,
 * along the normal. NaN (all three) when fur_px < 1 or no pixel of the
 * band fits. */
double pelt__outline_grain(const uint8_t *rgba, unsigned w, unsigned h, const float *dist,
                           const uint32_t *nearest, float fur_px, double *band_luminance,
                           double *along_normal);

/* Mean luminance of the pixels where mask (w*h bytes) is non-zero; the
 * whole picture for a NULL mask; NaN for an empty mask. */
double pelt__mean_luminance(const uint8_t *rgba, unsigned w, unsigned h, const uint8_t *mask);

#endif
