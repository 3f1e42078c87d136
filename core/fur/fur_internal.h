/* Private layout of pelt_fur, shared by core/ and gl/ (not installed). */
#ifndef PELT_FUR_INTERNAL_H
#define PELT_FUR_INTERNAL_H

#include "pelt/fur.h"

#include "core/mesh/raycast.h"
#include "core/base/rng.h"
#include "core/fur/strand.h"
#include "core/wet/surface_droplet.h"
#include "core/wet/wetness.h"

struct pelt_fur {
    pelt_fur_desc desc;      /* every default filled in */
    const pelt_mesh *mesh;
    uint8_t *texture;        /* fur volume, see core/furtex.h */
    unsigned texture_slices; /* layers + 1 */
    float *fur_uvs;          /* 2 per vertex: fur-texture coordinates in tiles */
    const float *tips;       /* 3 per vertex: tip offset p - p_root, mesh-local,
                                owned by strands */
    uint8_t *color_texture;  /* RGBA8 or NULL */
    unsigned color_width, color_height;
    unsigned color_version;  /* bumped when the colour texture changes */
    unsigned tips_version;   /* bumped when tips change */
    pelt__strands *strands;  /* one mass-spring strand per vertex */
    float time;              /* seconds stepped since creation or reset */
    float fur_per_uv[2];     /* fur tiles per uv unit along u and v */
    pelt__wetness *wetness;  /* the wetness mask over the uvs */
    pelt__surface_index *surface; /* droplets by distance on the surface */
    pelt__bvh *bvh;          /* droplets by a ray */
    pelt_rain rain;
    pelt__rng rain_rng;
    double rain_carry;       /* fraction of a drop carried to the next step */
    float *area_cdf;         /* cumulative triangle areas, for random drops */
    float world_per_uv;      /* mean world length of one mask-uv unit */
    float dry_rate;
};

/* Rain and random drops (core/fur_rain.c). */
pelt_status pelt__fur_rain_init(pelt_fur *fur, pelt_error *err);
void pelt__fur_rain_step(pelt_fur *fur, float dt);

/* Fills the zero fields of `d` with defaults for `mesh`. */
void pelt__fur_desc_defaults(pelt_fur_desc *d, const pelt_mesh *mesh);

#endif
