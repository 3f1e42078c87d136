/* The wetness mask as an RGBA8 picture (Silva et al. Fig. 11 insets). */
#ifndef PELT_CORE_WET_PICTURE_H
#define PELT_CORE_WET_PICTURE_H

#include "core/wet/mask.h"

/* Writes the mask as an RGBA8 picture like the insets of Silva Fig. 11
 * into rgba (width * height * 4 bytes, caller-owned), row 0 at the TOP
 * (v = 1): dry = black, wet = blue with intensity rho, shaded brighter
 * toward each clump centre so clumps show as blobs. */
void pelt__wetness_to_rgba8(const pelt__wetness *m, uint8_t *rgba);

#endif
