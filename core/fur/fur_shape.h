/* C references of the fur shape of Silva et al. §3.2 (Eq. 1 and 4), as
 * docs/method.md reads them; gl/shaders/fur_shape.glsl holds the same formulas
 * with the same argument order, and a parity test compares the two.
 *
 * h in [0, 1] is the normalised height along the strand (layer n of N sits
 * at h = (1 + n) / N). The displaced point at height h is
 *   p(h) = p_root + v_offset(h),  v_offset(h) = beta(h) + phi(h)   (Eq. 1). */
#ifndef PELT_FUR_SHAPE_H
#define PELT_FUR_SHAPE_H

#include "core/base/vec.h"

#include <stdbool.h>

/* beta(h), Silva Eq. 1: the quadratic Bezier from the root (0) through the
 * control point n * L0 / 2 to `tip` (= p - p_root, the strand state):
 *   B(h) = 2h(1-h) (n L0 / 2) + h^2 tip.
 * At rest (tip = L0 n) B(h) = h L0 n exactly: evenly spaced layers. */
pelt_vec3 pelt__fur_bend(pelt_vec3 n, float L0, pelt_vec3 tip, float h);

/* phi(h), Silva Eq. 4: alpha(h) (cos(omega h) u + sin(omega h) v) with
 * alpha(h) = (1 - rho) K h; u, v the unit tangent frame, omega in radians
 * over the full length, K the curl radius at the tip (world units), rho the
 * wetness in [0, 1] (wet fur loses its curl). */
pelt_vec3 pelt__fur_curl(pelt_vec3 u, pelt_vec3 v, float omega, float K, float rho, float h);

/* phi(h) of one strand with its own phase psi (ringlets, beyond Silva Eq.
 * 4; docs/method.md, Ringlets): alpha(h) (cos(omega h + psi) u +
 * sin(omega h + psi) v). pelt__fur_curl is psi = 0. The fur texture draws
 * it strand by strand (core/fur/furtex.c) in the texture's axes. */
pelt_vec3 pelt__fur_curl_phase(pelt_vec3 u, pelt_vec3 v, float omega, float K, float rho, float h,
                               float psi);

/* A ringlet's phase from its strand's id (the fur texture's blue channel,
 * a byte): 2 pi fract(3 id), so the shells can work out the phase of the
 * hair they draw and light it along its own curl. Three cycles over the
 * ids keep every phase where grooming thins the hair by id; the phase
 * moves smoothly with id, so a filtered id at a hair's edge is off by
 * little. Mirrors ringlet_phase in fur_shape.glsl. */
float pelt__ringlet_phase(float id);

/* The unit tangent of a ringlet: the hair's own unit tangent t plus the
 * derivative over h of the curl k h (cos(omega h + psi) u + sin(...) v),
 * with k the curl radius at the tip over the hair's length (the curve's
 * h runs over the length, so its axis has length 1 per unit h). Lights a
 * curly hair along its curl (docs/method.md, Ringlets). Mirrors
 * ringlet_tangent in fur_shape.glsl. */
pelt_vec3 pelt__ringlet_tangent(pelt_vec3 t, pelt_vec3 u, pelt_vec3 v, float k, float omega, float h,
                                float psi);

/* The slope of the fur texture's own curl (Lengyel §2.2, look.strand_curl;
 * pelt__furtex_strand_center) along (u, v) per unit of the hair's length at
 * height h: `radius` the curl's radius over the hair's length, omega = 2 pi
 * turns, psi the strand's phase: a helix winds as radius (cos, sin)(omega h
 * + psi), so out = radius omega (-sin, cos); a wave (wave true) runs along
 * u alone, out = (radius omega cos, 0). Mirrors strand_curl_slope in
 * fur_shape.glsl. */
void pelt__strand_curl_slope(float radius, float omega, bool wave, float h, float psi, float out[2]);

/* pelt__ringlet_tangent's T, plus a further slope `extra` along (u, v)
 * (the texture's own curl, pelt__strand_curl_slope), dotted with two
 * directions a and b, from the frame's unit vectors dotted with them,
 * ta = (t.a, u.a, v.a) and tb = (t.b, u.b, v.b), and with each other,
 * gram = (t.u, t.v, u.v): out = (T.a, T.b). The shells' and fins' fragment
 * stages light a dry curl so, from dots the vertex stage interpolates,
 * where it normalised the frame's three vectors and the tangent per
 * fragment. Mirrors ringlet_dots in fur_shape.glsl. */
void pelt__ringlet_dots(const float ta[3], const float tb[3], const float gram[3], float k, float omega, float h,
                        float psi, const float extra[2], float out[2]);

/* Shading tangent T(h): the unit derivative d/dh (beta + phi) of the whole
 * displaced curve, so highlights follow bends and curls (Silva Fig. 6);
 * n when that derivative vanishes. */
pelt_vec3 pelt__fur_tangent(pelt_vec3 n, float L0, pelt_vec3 tip, pelt_vec3 u, pelt_vec3 v,
                            float omega, float K, float rho, float h);

/* Combing (Lengyel et al. §3, hair direction): the shells sheared along
 * the comb direction u (tangent; unit, or shorter where the direction
 * field fades), slant = tan of the slant angle: offset h L0 slant u. */
pelt_vec3 pelt__fur_comb(pelt_vec3 u, float L0, float slant, float h);

/* T(h) of the strand combed along `comb`: the unit derivative of
 * beta + phi + pelt__fur_comb(comb, ...). */
pelt_vec3 pelt__fur_tangent_combed(pelt_vec3 n, float L0, pelt_vec3 tip, pelt_vec3 u, pelt_vec3 v,
                                   pelt_vec3 comb, float omega, float K, float rho, float slant,
                                   float h);

/* Grooming (Lengyel et al. §3): the shear per unit length of a groomed
 * strand, the comb direction times the global slant plus the groomed lean
 * (lean[0], lean[1]) along the vertex's tangent frame (u, v). The shells
 * then take pelt__fur_comb(shear, L, 1, h) with L = L0 times the vertex's
 * length scale s, and the strand's tip and curl radius scale by s too (a
 * short strand is a scaled-down long one). */
pelt_vec3 pelt__fur_groom_shear(pelt_vec3 comb, float slant, pelt_vec3 u, pelt_vec3 v,
                                const float lean[2]);

/* Wet fur lies along its grain (docs/wetness.md, Wet fur lies down): the
 * comb's slant (tan of its angle) at wetness rho, its angle raised by
 * lie * rho radians, at most PELT__WET_LIE_MAX; the slant itself where
 * lie * rho is 0. Mirrors wet_slant. */
#define PELT__WET_LIE_MAX 1.3089969f /* 75 degrees */
float pelt__fur_wet_slant(float slant, float lie, float rho);

/* The four looks of Silva Fig. 7 by name: "straight", "wavy",
 * "few-large-curls", "many-small-curls".
 * omega in radians over the full length, radius as a fraction of L0
 * (K = radius_fraction * L0). Returns false, leaving the outputs untouched,
 * for an unknown or NULL name. */
bool pelt__curl_preset(const char *name, float *omega, float *radius_fraction);

#endif
