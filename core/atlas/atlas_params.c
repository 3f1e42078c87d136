/* The rows of pelt_atlas_desc (pelt/params.h): name, field, default, range.
 * pelt_atlas_create checks a desc against them; the scene's atlas.* keys
 * read them. */
#include "pelt/atlas.h"
#include "pelt/params.h"

#include "core/base/params.h"

#include <float.h>
#include <stddef.h>

#define FMAX ((double)FLT_MAX)
#define OFF(f) offsetof(pelt_atlas_desc, f)

static const char *const modes[] = {"auto", "mesh-uvs", "patches", NULL};

static const pelt_param atlas_params[] = {
    {"mask_size", PELT_PARAM_UINT, OFF(mask_size), 1, 1, 16384, 0, {0, 0, 0},
     "the smallest power of two >= max(256, sqrt(triangles)), at most 4096", NULL},
    {"texel_density", PELT_PARAM_FLOAT, OFF(texel_density), 1, 0, FMAX, PELT_PARAM_MIN_OPEN, {0, 0, 0},
     "8 / the mesh's bounding-box diagonal", NULL},
    {"direction", PELT_PARAM_FLOAT, OFF(direction), 3, -FMAX, FMAX, 0, {0, 0, 0},
     "(0, -1, 0) while all three are 0: combed down", NULL},
    {"seed", PELT_PARAM_SEED, OFF(seed), 1, 0, 4294967295.0, 0, {0, 0, 0}, NULL, NULL},
    {"max_stretch", PELT_PARAM_FLOAT, OFF(max_stretch), 1, 1.1, FMAX, 0, {2, 0, 0}, NULL, NULL},
    {"mode", PELT_PARAM_ENUM, OFF(mode), 1, 0, 0, 0, {0, 0, 0}, NULL, modes},
    {"max_patch_faces", PELT_PARAM_UINT, OFF(max_patch_faces), 1, 1, 1000000, 0, {1500, 0, 0}, NULL, NULL},
    {"smoothing_iterations", PELT_PARAM_UINT, OFF(smoothing_iterations), 1, 1, 1000, 0, {4, 0, 0}, NULL, NULL},
};

#define ATLAS_PARAM_COUNT (sizeof atlas_params / sizeof atlas_params[0])

const pelt_param *pelt_atlas_params(size_t *count)
{
    if (count) *count = ATLAS_PARAM_COUNT;
    return atlas_params;
}

const pelt_param *pelt_atlas_param(const char *name)
{
    return pelt__params_find(atlas_params, ATLAS_PARAM_COUNT, name);
}
