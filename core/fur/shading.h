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

/* Wet skin's sheen (docs/wetness.md, Wet optics): the film of water on
 * the skin between the tufts is a smooth mirror, lit as Blinn-Phong at the
 * wet hair's exponent times `sharpness` (the film on the skin is flatter
 * than the one round a hair) and the wet hair's gain (pelt__wet_shine),
 * over the film's cover r = clamp(rho, 0, 1): r gain clamp(n.h, 0, 1)^(p'
 * sharpness), with n.h the skin normal dotted with the half vector; 0 on
 * dry skin. GLSL: wet_skin_sheen. */
float pelt__wet_skin_sheen(float n_dot_h, float rho, float p, float sharpness, float gloss);

/* Wet hair's colour (docs/wetness.md, Wet optics), linear light: with r =
 * clamp(rho, 0, 1) and m the largest channel of c, each channel becomes
 * m (c / m)^(1 + PELT__WET_SATURATION r) (1 - darken r): darker and more
 * saturated, the brightest channel keeping its share. GLSL: wet_color. */
#define PELT__WET_SATURATION 0.8f
pelt_vec3 pelt__wet_color(pelt_vec3 c, float rho, float darken);

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

/* How much of Kenwright's shadow a shell draws where the eye sees the
 * surface at n_dot_v: all of it face-on (|N.V| from
 * PELT__INTER_SHADOW_FACE_ON), none from the side (up to
 * PELT__INTER_SHADOW_SIDE_ON), smoothstep between. Seen from the side, a
 * ray crosses many shells, and each shell's shadow lies under its own
 * hairs, not under the hairs in front of it on the ray: the shadows add
 * up to rows across the outline (docs/reference.md, Kenwright's shadows
 * seen from the side). Mirrors inter_shadow_view_fade() in shading.glsl. */
#define PELT__INTER_SHADOW_SIDE_ON 0.3f
#define PELT__INTER_SHADOW_FACE_ON 0.7f
float pelt__inter_shadow_view_fade(float n_dot_v);

/* Grooming (Lengyel et al. §3): the hair colour c (sRGB, decoded; weight c[3]) over
 * the look's root colour, and the tip colour brightened by the look's own
 * tip / root ratio (per channel, root at least 0.01, result at most 1). */
pelt_vec3 pelt__groom_root_color(pelt_vec3 color, const float c[4]);
pelt_vec3 pelt__groom_tip_color(pelt_vec3 color, pelt_vec3 tip, const float c[4]);

/* Grooming's density keeps a strand of the fur volume when its id is below
 * the density (all of them at density 1). */
bool pelt__groom_keeps(float id, float density);

/* Linear light (docs/shading.md). Colours are given as sRGB (IEC 61966-2-1)
 * and lit in linear light; the lit colour is exposed, tone mapped and
 * encoded back to sRGB for the 8-bit image. Per channel: */
float pelt__srgb_decode(float c); /* c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055)^2.4 */
/* l clamped to [0, 1]; l <= 0.0031308 ? 12.92 l : 1.055 l^(1 / 2.4) - 0.055,
 * its power replaced by I. Taylor's fit in square roots ("sRGB
 * approximations for HLSL", 2012): with s1 = sqrt(l), s2 = sqrt(s1),
 * s3 = sqrt(s2), 0.662002687 s1 + 0.684122060 s2 - 0.323583601 s3
 * - 0.0225411470 l, within 0.25 / 255 of the power; three square roots
 * cost llvmpipe a fraction of one power, on every fragment. */
float pelt__srgb_encode(float l);
/* The strand's shade in the fur texture (a brightness in [0.4, 1]),
 * decoded per fragment by Taylor's cubic fit of the sRGB curve,
 * c (c (0.305306011 c + 0.682171111) + 0.012522878): within 0.002 of
 * pelt__srgb_decode, and three multiply-adds. */
float pelt__shade_decode(float c);
pelt_vec3 pelt__srgb_decode3(pelt_vec3 c);

/* The tone curves (pelt_tone, pelt/render.h): PELT_TONE_FILMIC is
 * Narkowicz's fit of the ACES filmic curve (K. Narkowicz, "ACES Filmic Tone
 * Mapping Curve", 2015), its input scaled by his 0.6:
 *   f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14),
 *   tone(x) = clamp(f(PELT__TONE_BIAS x), 0, 1),
 * which reaches 1 only at x = 7.24 / 0.6 = 12.1 (far above the brightest
 * the hair models give at exposure 1, tests/core/test_shading.c).
 * PELT_TONE_NONE clamps x to [0, 1]. `exposure` multiplies x first. */
#define PELT__TONE_BIAS 0.6f
float pelt__aces(float x);
float pelt__tone(float x, float exposure, int tone);
/* What a pixel's channel shows: the sRGB encoding of pelt__tone(x, ...),
 * fitted whole for each tone curve, as the shaders map every fragment
 * (display_color): with s = sqrt(clamp(exposure x, 0, v_max)),
 *   P(s) / Q(s), P = p1 s + ... + p5 s^5, Q = 1 + q1 s + ... + q4 s^4,
 * clamped to [0, 1], where v_max is the exposed value the curve reaches
 * white at (12.07 filmic, 1 none). One square root and one division a
 * channel, where the curve and then the encoding took a division and three
 * square roots (llvmpipe's frame about 6% shorter on a close-up); within
 * 0.22 / 255 of the curve's exact encoding and monotone
 * (tests/core/test_shading.c). Fitted by scripts/display_fit.c. */
float pelt__display(float x, float exposure, int tone);

/* Hair shading beyond Kajiya-Kay: Scheuermann's real-time reading of
 * Marschner et al. (T. Scheuermann, "Hair Rendering and Shading", GDC
 * 2004; Marschner et al., "Light Scattering from Human Hair Fibers",
 * SIGGRAPH 2003). The tangent T is tilted along the surface normal N:
 * T' = normalize(T + shift N); a positive shift moves the highlight towards
 * the tip, a negative one towards the root. */
pelt_vec3 pelt__shift_tangent(pelt_vec3 t, pelt_vec3 n, float shift);

/* A strand's highlight about the half vector H (unit): with u = T.H,
 *   smoothstep(-1, 0, u) * (1 - u^2)^(p / 2). */
float pelt__strand_specular(pelt_vec3 t, pelt_vec3 h, float p);

/* Transmission (Marschner's TT lobe): light from behind the hair passes
 * through it and goes on forwards. On the cone of Kajiya-Kay's highlight,
 *   cone = max(0, (T.L)(T.E) + |T x L||T x E|)^p,
 * times the azimuth that peaks when L and E (from the eye towards the
 * point) project onto the plane across the hair in the same direction:
 *   cos phi = (L.E - (T.L)(T.E)) / max(|T x L||T x E|, 1e-4),
 *   azimuth = max(0, cos phi)^PELT__HAIR_TT_AZIMUTH (2: a broad forward lobe). */
#define PELT__HAIR_TT_AZIMUTH 2.0f
float pelt__hair_transmission(pelt_vec3 t, pelt_vec3 l, pelt_vec3 e, float p);

/* The model's constants (gl/shaders/shading.glsl has the same): the
 * primary highlight (light-coloured) shifted towards the tip, the secondary
 * (tinted by the hair colour, broader: exponent p times WIDTH) towards the
 * root, as Marschner's R and TRT lobes are by the cuticle's tilt (about
 * 3 degrees, the secondary 1.5 times as far); their gains, and that of
 * the transmission (its exponent p times TT_WIDTH). */
#define PELT__HAIR_SHIFT_PRIMARY 0.1f
#define PELT__HAIR_SHIFT_SECONDARY -0.15f
#define PELT__HAIR_SECONDARY_WIDTH 0.5f
#define PELT__HAIR_SECONDARY_GAIN 0.5f
#define PELT__HAIR_TT_WIDTH 0.5f
#define PELT__HAIR_TT_GAIN 1.5f
/* The body's shadow on the direct light is clamp(0.8 n.L + 0.35, 0, 1)
 * (gl/shaders/fur_light.glsl); on the transmission, clamp(0.8 n.L + REACH,
 * 0, 1): light from behind reaches the hair standing clear of the body up
 * to the silhouette. */
#define PELT__HAIR_TT_REACH 0.8f

/* The model's four factors for tangent T, surface normal N, L towards the
 * light, E from the eye towards the point (all unit), exponent p:
 * out[0] diffuse |T x L| (Kajiya-Kay's), out[1] the primary highlight,
 * out[2] the secondary, out[3] the transmission. */
void pelt__hair_lobes(pelt_vec3 t, pelt_vec3 n, pelt_vec3 l, pelt_vec3 e, float p, float out[4]);

/* Occlusion from the fur's own density: light reaching height h in [0, 1]
 * of the fur crosses the hair above it, exp(-depth (1 - h)). */
float pelt__fur_occlusion(float depth, float h);
/* The fur's optical depth from its look: a slice of the fur texture is
 * covered to c = density pi r^2 / size^2 (strands of radius r texels on a
 * size^2 tile, at most 0.95), and light crosses PELT__OCCLUSION_SLICES
 * such slices on its way to the roots: depth = -SLICES ln(1 - c). At the
 * default look the roots get 0.5, as Silva's gamma(0) at K_shadow = 2. */
#define PELT__OCCLUSION_SLICES 1.5f
float pelt__occlusion_depth(float density, float strand_radius, unsigned texture_size);

#endif
