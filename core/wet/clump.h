/* Clump displacement reference (Silva et al. Eq. 5 and Alg. 2 as docs/wetness.md
 * reads them). gl/shaders/clump.glsl is the same maths in GLSL; keep them
 * in step. No GL here. */
#ifndef PELT_CORE_CLUMP_H
#define PELT_CORE_CLUMP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Outcome of Alg. 2 for one fragment; the values match the GLSL constants
 * CLUMP_KEEP, CLUMP_DISPLACED, CLUMP_DISCARD. */
typedef enum pelt__clump_result {
    PELT__CLUMP_KEEP = 0,      /* dry texel: draw at p, undisplaced */
    PELT__CLUMP_DISPLACED = 1, /* draw the hair rooted at q (d = q - p) */
    PELT__CLUMP_DISCARD = 2    /* another clump's texel, or q is dry */
} pelt__clump_result;

/* Ringlets (docs/method.md): the fur volume holds Silva's curl drawn
 * strand by strand at `levels` amplitudes, from full (level 0) down to none
 * (the last), each level `stride` slices after the one before. At wetness
 * rho the curl is 1 - rho of full (Eq. 4's alpha), t = clamp(rho, 0, 1)
 * (levels - 1): out = (slice offset of level floor(t), of the next level,
 * the weight of the next), the last pair at t = levels - 1. levels <= 1
 * gives (0, 0, 0). The shells' fragment stage blends the two levels. */
void pelt__ringlet_levels(float rho, float levels, float stride, float out[3]);

/* s * rho * f is clamped to [0, this] so the inverse mapping stays finite. */
#define PELT__CLUMP_MAX_PULL 0.95f

/* Eq. 5 profile at normalised height h = (1+n)/N:
 *   f = (1-w) h' + w (1 + ln h / ln N),  h' = (h - 1/N) / (1 - 1/N),
 * clamped to [0,1]: 0 at the first layer and 1 at the tip for any w in
 * [0,1]; N <= 1 gives 1. */
float pelt__clump_profile(float h, float w, float n_layers);

/* Where a tuft starts to gather its hairs, as a share of their height:
 * below it the hairs of a clump stand as dry hairs do, so the roots stay
 * spread over the skin and no lower layer loses its hair inside a clump;
 * the gaps between tufts open above it (docs/wetness.md, Tufts). */
#define PELT__CLUMP_BASE 0.25f

/* The tuft's profile: Eq. 5's f over the height above PELT__CLUMP_BASE,
 * f(1/N + (1 - 1/N) t) with t = clamp((h - base) / (1 - base), 0, 1):
 * 0 up to the base, 1 at the tip, rising as Eq. 5 between. */
float pelt__clump_tuft_profile(float h, float w, float n_layers);

/* How fast the tuft's profile rises at h per unit of height: its change
 * over one layer spacing 1/N centred on h, times N. */
float pelt__clump_tuft_slope(float h, float w, float n_layers);

/* Whether a layer at h stands wholly below the tufts' base: its profile
 * and its slope (over the half spacing above it) are 0 for any blend w,
 * so a clump leaves its hairs where they grew and lights them as free
 * hairs. The shells draw such wet layers with a program that does no
 * clump lookup (PELT__SHELL_TUFT_BASE, gl/shell_pass.c). */
bool pelt__clump_below_tufts(float h, float n_layers);

/* The dots (T.L, T.E) of a hair in a tuft (docs/wetness.md, Tuft light),
 * T the hair's own unit tangent t plus du to_centre[0] + dv to_centre[1]
 * times slope, normalised, where to_centre = c - q in mask uv, du and dv
 * are the world vectors of one mask-uv unit divided by the hair's length,
 * and slope is d(pull)/dh = s rho pelt__clump_tuft_slope; from the dots
 * l = (t.L, du.L, dv.L), e = (t.E, du.E, dv.E), g = (t.du, t.dv, du.du,
 * dv.dv) and m = du.dv. t's dots (l[0], e[0]) where the sum vanishes. */
void pelt__tuft_dots(const float l[3], const float e[3], const float g[4], float m, const float to_centre[2],
                     float slope, float out[2]);

/* Strays (docs/wetness.md, Tufts): a share of the hairs, picked by the
 * strand's id in [0, 1] (the fur texture's blue channel), stays out of
 * the tufts and stands where it grew: fract(7.31 id) < share. */
bool pelt__clump_stray(float id, float share);

/* Texel of a width x height RGBA32F mask (4 floats per texel, row 0 at
 * v = 0) that GL's NEAREST filter with CLAMP_TO_EDGE picks at uv:
 * index = clamp(floor(uv * size), 0, size - 1). */
const float *pelt__clump_texel(const float *mask, unsigned width,
                               unsigned height, const float uv[2]);

/* A tuft's lean (docs/wetness.md, Tufts lean): a natural clump carries a
 * byte of its cell's hash in the lowest 8 bits of its radius's float
 * (pelt__clump_tag; the radius moves by less than 2^-15 of itself), the
 * same byte on every texel of the clump, across patch borders. Its tuft's
 * tip stands off the centre by a r (x, y) in mask uv, x and y in [-1, 1]
 * from the byte's two halves (16 steps each), a = amount. amount 0 (one
 * clump per droplet, whose radius carries no tag) gives (0, 0). */
float pelt__clump_tag(float r, uint32_t key);
void pelt__clump_lean(const float texel[4], float amount, float out[2]);

/* Alg. 2 with the inverse mapping: the fragment at mask point p with texel
 * (c, r, rho) at layer height h samples the root
 *   q = c + (p - c) / (1 - min(s rho f(h), 0.95)),
 * f the tuft's profile (pelt__clump_tuft_profile).
 * Dry texel -> KEEP (q = p); |p - c| > r -> DISCARD; the texel at q dry ->
 * DISCARD; else DISPLACED. q is always written (p when KEEP). The caller
 * adds d = q - p to the colour uv and d * fur_tiling to the fur uv, and
 * discards where the fur texture holds no hair. */
pelt__clump_result pelt__clump_lookup(const float *mask, unsigned width,
                                      unsigned height, const float p[2],
                                      float h, float w, float n_layers,
                                      float s, float q[2]);

/* The same for a tuft that leans by `lean` (pelt__clump_lean) at its tip:
 * a hair rooted at q is seen at height h at c + (q - c)(1 - pull) + pull
 * lean, so p samples q = c + (p - pull lean - c) / (1 - pull). */
pelt__clump_result pelt__clump_lookup_lean(const float *mask, unsigned width, unsigned height,
                                           const float p[2], float h, float w, float n_layers, float s,
                                           const float lean[2], float q[2]);

/* Coverage of strands squeezed by a factor k in (0, 1] towards the clump
 * centre: the texture's coverage a, as independent strands, seen through
 * a bundle 1/k times as dense: 1 - (1 - a)^(1 / k). An extension of Silva
 * Alg. 2, which samples a minified texture and so thins the tuft to a
 * haze; see docs/wetness.md. */
float pelt__clump_coverage(float a, float k);

/* The squeeze k that pelt__clump_coverage raises a tuft's coverage by,
 * where the squeezed texture read stands at mip level `lod`: 1 (none)
 * where it still resolves the hairs, lod at most PELT__CLUMP_RESOLVED_LOD
 * (a pixel spans at most 2 texels), and each hair is drawn where the tuft
 * gathers it; `squeeze` a level above, where the mip averages the bundle's
 * hairs and only its density says how many a ray meets; linear between.
 * docs/wetness.md, Tuft coverage. */
#define PELT__CLUMP_RESOLVED_LOD 1.0f
float pelt__clump_bundle_squeeze(float squeeze, float lod);

/* Sub shells (docs/wetness.md, Sub shells): a tuft gathers its hairs
 * within a few layers above its base, where a hair at the tuft's rim moves
 * several of its widths from one layer to the next and the shells draw it
 * as a dotted line. The wet shells of such a layer are drawn as k sub
 * shells spread over the step below it, so that the hair moves at most
 * PELT__CLUMP_SUB_PX pixels from one to the next: k = ceil(the profile's
 * rise over the step x sweep_px / PELT__CLUMP_SUB_PX), between 1 and
 * PELT__CLUMP_SUB_MAX, where sweep_px is how far the whole profile moves
 * it on screen. h_below and h are the heights of the layer below and of
 * the layer; w and n_layers as pelt__clump_tuft_profile's. */
#define PELT__CLUMP_SUB_PX 2.0f
#define PELT__CLUMP_SUB_MAX 6u
unsigned pelt__clump_sub_shells(float h_below, float h, float w, float n_layers, float sweep_px);

/* Sub shell `part` (0 the innermost) of k drawn for `layer`, whose level
 * steps `step` layers: its layer, evenly below the layer down to the one
 * below (exclusive). Mirrors sub_shell_layer (gl/shaders/clump.glsl). */
float pelt__sub_shell_layer(float layer, float part, float k, float step);

/* The coverage each of k sub shells draws so that the k of them over one
 * another cover a: 1 - (1 - a)^(1/k). Mirrors sub_shell_alpha. */
float pelt__sub_shell_alpha(float a, float k);

/* A fin shows the hair rooted along its edge from the side (docs/wetness.md,
 * Tufts on the outline): the hair a tuft pulls from q = p + d lies along
 * the fin by d's component along the edge. `dir` is the edge's mask uv per
 * unit of the fin texture's u (uv_b - uv_a over the edge's length in fur
 * tiles); the result is that component in fin-texture units,
 * dot(d, dir) / dot(dir, dir), and 0 where dir has no length. */
float pelt__clump_fin_shift(const float d[2], const float dir[2]);

#endif
