/* Wetness painted from a greyscale image, cut into clumps (Silva et al. Fig. 12c). */
#ifndef PELT_CORE_WET_PAINT_H
#define PELT_CORE_WET_PAINT_H

#include "core/wet/mask.h"

/* How a greyscale image becomes clumps. Zero fields mean the defaults. */
typedef struct pelt__paint_desc {
    float clump_size; /* spacing of clump centres in uv units, default 0.03 */
    float threshold;  /* grey level (0..1) below which a texel is dry,
                         default 0.1 */
    uint32_t seed;    /* jitter of the clump grid, default 1 */
} pelt__paint_desc;

/* Replaces the mask with wetness painted from an 8-bit greyscale image
 * (grey, w x h, row 0 at the TOP, i.e. at v = 1, as a picture is viewed),
 * bilinearly resampled onto the mask: rho = grey / 255 where it exceeds the
 * threshold. Wet texels are split into clumps: a jittered grid of clump
 * seeds (spacing clump_size) cuts each connected wet region into cells;
 * each (cell, region) piece becomes one clump centred on its centroid with
 * the radius that covers it, so a stroke of a word renders as clumps along
 * the stroke. Allocates temporary memory (freed before return). */
pelt_status pelt__wetness_paint_image(pelt__wetness *m, const uint8_t *grey,
                                      unsigned w, unsigned h,
                                      const pelt__paint_desc *desc,
                                      pelt_error *err);

#endif
