/* pelt — shadows from the light and a ground that receives them: plain
 * settings, no OpenGL (pelt/render.h draws them; docs/shadows.md).
 *
 * The light's shadows are deep opacity maps (Yuksel and Keyser 2008, after
 * Kim and Neumann's opacity shadow maps): from the light, the skin's depth,
 * and the fur's accumulated opacity in a few slices that start a slab in
 * front of that skin. Skin, fins, shells and the ground multiply the
 * light's direct term by the transmittance at their point. */
#ifndef PELT_SHADOW_H
#define PELT_SHADOW_H

#include "pelt/base.h"

#ifdef __cplusplus
extern "C" {
#endif

#define PELT_SHADOW_MAX_SLICES 8u
#define PELT_SHADOW_MAX_MAP_SIZE 4096u

/* Zero-initialised means off; the zero of every other field picks its
 * default. */
typedef struct pelt_shadow_desc {
    bool enabled;
    unsigned map_size;  /* texels per side of the light's maps, 0 = 512
                           (16 .. PELT_SHADOW_MAX_MAP_SIZE) */
    unsigned slices;    /* opacity slices, 0 = 4 (1 .. PELT_SHADOW_MAX_SLICES) */
    float softness;     /* filter radius in map texels, default 0 = 1.0;
                           negative = hard (one tap) */
    float depth;        /* the slices span this many fur lengths in front
                           of the skin, 0 = 2 */
    float density;      /* scales the fur's opacity, 0 = 1 */
    bool keep_gamma;    /* also Silva's height darkening gamma(h); off, the
                           map replaces it (gamma is its cheap stand-in) */
} pelt_shadow_desc;

/* A ground plane under the mesh that receives the shadows: a disc at the
 * mesh's lowest point (world +Y up), centred under it. */
typedef struct pelt_ground_desc {
    bool enabled;
    float color[3]; /* sRGB (lit in linear light); all zero = (0.42, 0.40, 0.36) */
    float size;     /* radius in bounding-sphere radii, 0 = 4 */
} pelt_ground_desc;

#ifdef __cplusplus
}
#endif
#endif
