/* C references of the shading formulas that run in the fur shaders; the
 * parity test renders the GLSL versions (gl/shaders/shading.glsl) into a
 * float target and compares them with these. */
#ifndef PELT_SHADING_H
#define PELT_SHADING_H

#include "core/base/vec.h"

#include <stdbool.h>

/* Silva et al. Eq. 6, Kajiya-Kay: T strand tangent, L towards the light,
 * E camera direction (from the eye towards the point), all unit.
 * Returns (C_d, C_s) factors: diffuse = |T x L|, specular =
 * max(0, (T.L)(T.E) + |T x L||T x E|)^p. */
void pelt__kajiya_kay(pelt_vec3 t, pelt_vec3 l, pelt_vec3 e, float p, float *diffuse,
                      float *specular);

/* Wet fur's highlight (Silva §4 points to Gupta and Magnenat-Thalmann 2007
 * for wet hair; pelt's reading, docs/wetness.md): a film of water makes a
 * hair a smoother, stronger mirror, so the Kajiya-Kay exponent p and the
 * specular colour grow with the wetness rho in [0, 1] (clamped):
 *   p' = p (1 + (sharpness - 1) rho),  gain = 1 + (gloss - 1) rho.
 * gloss = sqrt(sharpness) keeps the light the lobe reflects about the same
 * (the cone's width falls as 1 / sqrt(p)); pelt's defaults are 2 and 4. */
void pelt__wet_shine(float rho, float p, float sharpness, float gloss, float *p_wet, float *gain);

/* Silva et al. Eq. 6 shadow factor gamma = (K - 1 + h) / K, K >= 1. */
float pelt__shadow_factor(float k_shadow, float h);

/* Lengyel et al. §2.4 hair lighting: (1 - u^2)^(P_d/2) and (1 - v^2)^(P_s/2)
 * for u = T.L, v = T.H (K_a, K_d, K_s are applied by the caller). */
void pelt__lengyel_lighting(float u, float v, float pd, float ps, float *diffuse, float *specular);

/* The 32x32 table of it (PELT__LIGHT_TABLE texels a side, 2 floats each:
 * diffuse, specular), texel (i, j) at u = 2 (i + 0.5) / 32 - 1, v likewise:
 * the shaders read it with bilinear filtering at (u, v) * 0.5 + 0.5. */
#define PELT__LIGHT_TABLE 32
void pelt__lengyel_table(float pd, float ps, float out[PELT__LIGHT_TABLE * PELT__LIGHT_TABLE * 2]);

/* Kenwright's inter-fur shadow: the fur-texture offset (in tiles) towards
 * the light L in the tangent frame (u, v), `step` tiles long at full
 * tangency. */
void pelt__inter_shadow_offset(pelt_vec3 l, pelt_vec3 u, pelt_vec3 v, float step, float out[2]);

/* Grooming (Lengyel et al. §3): the hair colour c (rgb, weight c[3]) over
 * the look's root colour, and the tip colour brightened by the look's own
 * tip / root ratio (per channel, root at least 0.01, result at most 1). */
pelt_vec3 pelt__groom_root_color(pelt_vec3 color, const float c[4]);
pelt_vec3 pelt__groom_tip_color(pelt_vec3 color, pelt_vec3 tip, const float c[4]);

/* Grooming's density keeps a strand of the fur volume when its id is below
 * the density (all of them at density 1). */
bool pelt__groom_keeps(float id, float density);

#endif
