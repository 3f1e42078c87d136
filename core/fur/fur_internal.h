/* Private layout of pelt_fur, shared by core/ and gl/ (not installed). */
#ifndef PELT_FUR_INTERNAL_H
#define PELT_FUR_INTERNAL_H

#include "pelt/fur.h"

#include "core/mesh/raycast.h"
#include "core/fur/fins.h"
#include "core/fur/furtex.h"
#include "core/fur/groom.h"
#include "core/fur/lod.h"
#include "core/fur/strand.h"
#include "core/wet/mask.h"
#include "core/wet/water.h"

struct pelt_fur {
    pelt_fur_desc desc;      /* every default filled in */
    const pelt_mesh *mesh;
    uint8_t *texture;        /* fur volume, see core/fur/furtex.h: ringlet_levels
                                volumes of texture_slices slices, one after
                                the other */
    unsigned texture_slices; /* layers + 1 */
    unsigned ringlet_levels; /* PELT__RINGLET_LEVELS with ringlets, else 1;
                                lod_slices holds as many sets */
    float *fur_uvs;          /* 2 per vertex: fur-texture coordinates in tiles */
    const float *tips;       /* 3 per vertex: tip offset p - p_root, mesh-local,
                                owned by strands */
    uint8_t *color_texture;  /* RGBA8 or NULL */
    unsigned color_width, color_height;
    unsigned color_version;  /* bumped when the colour texture changes */
    unsigned tips_version;   /* bumped when tips change */
    pelt__strands *strands;  /* one mass-spring strand per vertex */
    bool water_loaded;       /* the strands carry water (water_load, fur.c) */
    struct pelt__workers *workers; /* threads of the per-frame CPU work
                                (dynamics.threads; core/base/workers.h) */
    float time;              /* seconds stepped since creation or reset */
    float fur_per_uv[2];     /* fur tiles per uv unit along u and v */
    pelt__water *water;      /* mask, clump cells, droplets, rain (core/wet/water.h) */
    pelt__bvh *bvh;          /* the triangles for rays and brushes */
    pelt__groom groom;       /* per-vertex colour, length, density, lean */
    pelt__lod_chain lod;     /* shell geometry levels, each with its fins
                                (Lengyel §2.3); level 0 is the full mesh */
    uint8_t *lod_slices;     /* the coarser shell levels' slices (Lengyel
                                §2.4, core/fur/lod.h), NULL with lod off */
    unsigned lod_slice_count;
    float *pose;             /* NULL, or the mesh posed (pelt_fur_set_pose): 10
                                floats a vertex, position, normal, tangent */
    unsigned pose_version;   /* bumped when the pose changes */
    uint8_t *fin_texture;    /* RGBA8 fin texture, see pelt__fintex_generate,
                                one image a ringlet level as `texture` */
    unsigned fin_width, fin_height;
};

/* The fur texture's strands as the fur draws them (full ringlet amplitude). */
pelt__furtex_desc pelt__fur_texture_desc(const pelt_fur_desc *d);

/* Fills the zero fields of `d` with defaults for `mesh`. */
void pelt__fur_desc_defaults(pelt_fur_desc *d, const pelt_mesh *mesh);

/* Ringlets (docs/method.md): Silva's curl is drawn into the fur texture
 * strand by strand at this many amplitudes (full, half, none) instead of
 * moving the shells. */
#define PELT__RINGLET_LEVELS 3u

/* Whether d's curl is ringlets: a curl radius and PELT_CURL_RINGLETS or
 * PELT_CURL_STRANDS. */
bool pelt__fur_has_ringlets(const pelt_fur_desc *d);
/* The turns the hair's curl makes over its length: Silva's (look.curl_*)
 * and the texture's own (look.strand_curl_*) added. */
float pelt__fur_curl_turns(const pelt_fur_desc *d);
/* The shells the fur takes: `layers`, or layers_per_turn for every turn
 * of its curl where that is more (at most 256). */
unsigned pelt__fur_curl_layers(const pelt_fur_desc *d);

/* The curl radius the shells' vertex stage (and the fins' strands) move
 * by: look.curl_radius, or 0 when the texture holds the curl as ringlets. */
float pelt__fur_vertex_curl_radius(const pelt_fur_desc *d);

/* How far the tufts lean (pelt__clump_lean's amount): wet.clump_lean for
 * natural clumps, whose radii carry their cell's byte; 0 for one clump
 * per droplet. */
float pelt__fur_clump_lean(const pelt_fur_desc *d);

/* wet.lie in radians: pelt__fur_wet_slant's `lie`, the shells' u_wet_lie. */
float pelt__fur_wet_lie(const pelt_fur_desc *d);

#endif
