/* The rows of pelt_fur_desc (pelt/params.h): name, field, default, range.
 * pelt__fur_desc_defaults fills zeros from them and check_desc (fur.c)
 * checks every field against them; the scene's keys and the command line
 * point here instead of repeating a default or a range. */
#include "core/fur/fur_params.h"
#include "core/fur/lod.h"

#include <float.h>
#include <stddef.h>

#define FMAX ((double)FLT_MAX)
#define OPEN PELT_PARAM_MIN_OPEN
#define OFF(f) offsetof(pelt_fur_desc, f)
#define UINT_(n, f, lo, hi, d) {n, PELT_PARAM_UINT, OFF(f), 1, lo, hi, 0, {d, 0, 0}, NULL, NULL}
#define FLT(n, f, lo, hi, fl, d) {n, PELT_PARAM_FLOAT, OFF(f), 1, lo, hi, fl, {d, 0, 0}, NULL, NULL}
#define DERIVED(n, f, lo, hi, fl, why) {n, PELT_PARAM_FLOAT, OFF(f), 1, lo, hi, fl, {0, 0, 0}, why, NULL}
#define RGB(n, f, hi, r, g, b) {n, PELT_PARAM_FLOAT, OFF(f), 3, 0, hi, 0, {r, g, b}, NULL, NULL}
#define ENUM(n, f, names) {n, PELT_PARAM_ENUM, OFF(f), 1, 0, 0, 0, {0, 0, 0}, NULL, names}

static const char *const strand_curl_shapes[] = {"helix", "wave", NULL};
static const char *const curl_phases[] = {"ringlets", "coherent", "strands", NULL};
static const char *const shadings[] = {"kajiya-kay", "lengyel-table", "marschner", NULL};
static const char *const lod_modes[] = {"auto", "off", "fixed", NULL};
static const char *const wet_clumps[] = {"natural", "droplet", NULL};

/* The ranges are what the library can draw; the defaults are the papers'
 * (Silva Table 1: a 256 x 256 texture and mask, 16 layers where the fur is
 * seen face-on: 32 drawn edge-on, where 16 alias into stripes). */
static const pelt_param fur_params[] = {
    UINT_("layers", layers, 1, 256, 32),
    FLT("layers_per_turn", layers_per_turn, 0, 256, OPEN, 13),
    DERIVED("length", length, 0, FMAX, OPEN, "3% of the mesh's bounding-box diagonal"),
    {"seed", PELT_PARAM_SEED, OFF(seed), 1, 0, 4294967295.0, 0, {1, 0, 0}, NULL, NULL},
    UINT_("look.texture_size", look.texture_size, 8, 4096, 256),
    FLT("look.density", look.density, 0, 1e6, OPEN, 3000),
    DERIVED("look.strand_radius", look.strand_radius, 0, 64, OPEN, "1.6 texels of a 256-texel texture: 1.6 texture_size / 256"),
    FLT("look.taper", look.taper, 0, 1, 0, 0.8),
    FLT("look.strand_curl", look.strand_curl, 0, 64, 0, 0),
    FLT("look.strand_curl_turns", look.strand_curl_turns, 0, 32, OPEN, 2),
    ENUM("look.strand_curl_shape", look.strand_curl_shape, strand_curl_shapes),
    DERIVED("look.tiling", look.tiling, 0, FMAX, OPEN, "5 / the mesh's bounding-box diagonal"),
    RGB("look.color", look.color, 1, 0.55, 0.34, 0.18),
    RGB("look.tip_color", look.tip_color, 1, 1.0, 0.82, 0.58),
    RGB("look.skin_color", look.skin_color, 1, 0.78, 0.56, 0.47),
    FLT("look.color_scale", look.color_scale, 0, FMAX, OPEN, 1),
    RGB("look.specular", look.specular, FMAX, 0.9, 0.85, 0.8),
    FLT("look.shininess", look.shininess, 0, FMAX, OPEN, 20),
    FLT("look.shadow", look.shadow, 1, FMAX, 0, 2),
    FLT("look.curl_frequency", look.curl_frequency, -FMAX, FMAX, 0, 0),
    FLT("look.curl_radius", look.curl_radius, 0, FMAX, 0, 0),
    ENUM("look.curl_phase", look.curl_phase, curl_phases),
    FLT("look.curl_lock", look.curl_lock, 0, 64, OPEN, 2),
    {"look.inter_shadow", PELT_PARAM_BOOL, OFF(look.inter_shadow), 1, 0, 1, 0, {0, 0, 0}, NULL, NULL},
    FLT("look.inter_shadow_offset", look.inter_shadow_offset, 0, 64, OPEN, 4),
    FLT("look.inter_shadow_darkness", look.inter_shadow_darkness, 0, 1, OPEN, 0.8),
    ENUM("look.shading", look.shading, shadings),
    FLT("look.diffuse_power", look.diffuse_power, 0, 256, OPEN, 1),
    FLT("dynamics.mass", dynamics.mass, 0, FMAX, OPEN, 1),
    DERIVED("dynamics.spring_k", dynamics.spring_k, 0, FMAX, OPEN, "mass * 9.81 / (0.4 * length)"),
    DERIVED("dynamics.damping", dynamics.damping, 0, FMAX, 0, "0.5 * sqrt(spring_k * mass)"),
    UINT_("dynamics.threads", dynamics.threads, 0, 16, 0),
    UINT_("wet.mask_size", wet.mask_size, 1, 8192, 256),
    FLT("wet.clump_blend", wet.clump_blend, 0, 1, 0, 0.5),
    FLT("wet.clump_tightness", wet.clump_tightness, 0, 1, OPEN, 0.9),
    FLT("wet.darken", wet.darken, 0, 1, PELT_PARAM_MAX_OPEN, 0.5),
    FLT("wet.strays", wet.strays, 0, 1, 0, 0.1),
    ENUM("wet.clumps", wet.clumps, wet_clumps),
    DERIVED("wet.clump_size", wet.clump_size, 0, FMAX, OPEN,
            "the fur's length, kept between 20 and 100 hairs a tuft"),
    FLT("wet.gloss", wet.gloss, 1, 16, 0, 2),
    FLT("wet.gloss_sharpness", wet.gloss_sharpness, 1, 64, 0, 8),
    FLT("wet.weight", wet.weight, 0, 16, 0, 1),
    FLT("wet.clump_lean", wet.clump_lean, 0, 1, 0, 0.3),
    FLT("wet.lie", wet.lie, 0, 60, 0, 0),
    FLT("comb.slant", comb.slant, 0, 60, 0, 0),
    FLT("fins.length", fins.length, 0, 8, OPEN, 1),
    DERIVED("fins.density", fins.density, 0, 4096, OPEN, "look.texture_size / 16, at most look.texture_size"),
    FLT("fins.curl", fins.curl, 0, 64, 0, 0),
    FLT("fins.curl_turns", fins.curl_turns, 0, 64, OPEN, 2),
    FLT("fins.hairs", fins.hairs, 0, 16, 0, 0.5),
    ENUM("lod.mode", lod.mode, lod_modes),
    UINT_("lod.shell_level", lod.shell_level, 0, 8, 0),
    UINT_("lod.mesh_level", lod.mesh_level, 0, 11, 0),
    UINT_("lod.texture_taps", lod.texture_taps, 1, 8, 1),
    FLT("lod.texture_aniso", lod.texture_aniso, 1, 16, 0, PELT__FUR_TEXTURE_ANISO),
    FLT("lod.edge_depth", lod.edge_depth, 1, 64, 0, 16),
    UINT_("lod.sub_shells", lod.sub_shells, 1, 8, 4),
    FLT("lod.shell_pixels", lod.shell_pixels, 0, 64, OPEN, 0.5),
    FLT("lod.mesh_error_pixels", lod.mesh_error_pixels, 0, 64, OPEN, 0.5),
    FLT("lod.mesh_edge_pixels", lod.mesh_edge_pixels, 0, 1024, OPEN, 8),
    FLT("lod.back_reach", lod.back_reach, 0, 1, 0, 0.3),
};

#define FUR_PARAM_COUNT (sizeof fur_params / sizeof fur_params[0])

const pelt_param *pelt_fur_params(size_t *count)
{
    if (count) *count = FUR_PARAM_COUNT;
    return fur_params;
}

const pelt_param *pelt_fur_param(const char *name)
{
    return pelt__params_find(fur_params, FUR_PARAM_COUNT, name);
}

