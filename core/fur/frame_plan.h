/* One frame's plan, decided without GL: the levels of detail for the view,
 * the light's frame, the ground disc, the shell shader's features and which
 * passes run. gl/renderer.c uploads, plans with pelt__frame_plan_make, runs
 * its passes in order and resets GL state; everything it decides lives
 * here, where the core tests reach it. */
#ifndef PELT_FRAME_PLAN_H
#define PELT_FRAME_PLAN_H

#include "pelt/camera.h"
#include "pelt/fur.h"
#include "pelt/shadow.h"

#include <stdbool.h>

/* The levels of detail of one frame (core/fur/lod.h). */
typedef struct pelt__frame_lod {
    bool full_mesh;       /* level of detail off: the mesh's own triangles */
    unsigned mesh_level;  /* else this geometric level's triangles ... */
    unsigned fin_level;   /* ... and this one's fins: mesh_level or coarser
                             (pelt__lod_pick_fins) */
    unsigned shell_level; /* Lengyel §2.4: ceil(N / 2^level) shells ... */
    float shell_blend;    /* ... blending this far towards the next level */
    /* The view's shell budget (pelt__lod_view_blend, the shells' u_shell_view):
       [0] the level's spacing seen side-on, pixels x clip w per unit of groom
       length (0: off), [1] the spacing aimed at, pixels. */
    float shell_view[2];
    /* Back-facing shells drawn within the fur's reach of the silhouette:
       where N.V >= -back_reach (pelt__lod_back_hidden); negative: all. */
    float back_reach;
    float fin_row_error;  /* the chord error a fin's rows may show, mesh units
                             (0: always PELT_FIN_ROWS rows) */
    /* Wet shells drawn in sub shells where a tuft gathers its hairs
       (pelt__clump_sub_shells): [0] the tufts' profile blend w, [1] how
       far the pull moves a hair at a mean tuft's rim over the whole
       profile, pixels at the vertex in view nearest the eye (0: dry, no
       sub shells). */
    float tuft_pull[2];
    /* Close up, every layer drawn as this many shells, evenly down to the
       one below (pelt__lod_sub_shells; 1: one a layer). The wet shells
       take the larger of this and their own. */
    unsigned sub_shells;
    /* ... and how far each vertex needs them (pelt__lod_sub_shell_need):
       the level's spacing seen side-on, pixels x clip w per unit of groom
       length (0: every vertex needs them all). */
    float sub_side;
    /* The fur's length on screen at the bounding sphere's point nearest the
       eye, pixels (infinity from inside it, or where levels are not
       picked by the view): no vertex shows it longer. */
    float fur_px;
    bool cull;            /* back-facing shells culled (closed meshes) */
    bool cull_skin;       /* back-facing skin culled: a closed mesh hides it */
    bool front_cw;        /* the mesh winds its outside faces clockwise */
    unsigned texture_taps; /* the most fur-texture fetches a shell fragment
                              takes (lod.texture_taps, at least 1) */
    float texture_aniso;   /* lod.texture_aniso, at least 1 */
    float edge_depth;      /* lod.edge_depth, at least 1 */
} pelt__frame_lod;

/* The frame block's shadow fields (gl/shaders/blocks.glsl). */
typedef struct pelt__frame_shadow {
    float light_matrix[16];
    float map[4], slab[4];
} pelt__frame_shadow;

/* What the light pass draws (docs/shadows.md). */
typedef struct pelt__shadow_frame {
    unsigned mesh_level;  /* the geometric level drawn from the light */
    unsigned shell_level; /* and the shell level */
    bool full_mesh;       /* level of detail off */
    bool cull;            /* back faces (from the light) culled */
    bool front_cw;
    unsigned features;    /* the shells' PELT__SHELL_WET | _RINGLETS bits */
} pelt__shadow_frame;

/* What the shell fragment shader compiles in (gl/shaders/shell_fs.glsl): a
 * frame uses the variant with only the features it needs. */
enum {
    PELT__SHELL_WET = 1 << 0,           /* clumps and wet darkening */
    PELT__SHELL_INTER_SHADOW = 1 << 1,  /* Kenwright's inter-fur shadows */
    PELT__SHELL_LOD_BLEND = 1 << 2,     /* a second fetch: the next shell level */
    PELT__SHELL_COLOR_TEXTURE = 1 << 3, /* the fur has a colour texture */
    PELT__SHELL_KAJIYA_KAY = 1 << 4,    /* the hair lighting models: one of these, */
    PELT__SHELL_LIGHT_TABLE = 1 << 5,   /* neither (Scheuermann-Marschner) or both (any) */
    PELT__SHELL_SHADOW_MAP = 1 << 6,    /* the light's shadow maps darken the direct light */
    PELT__SHELL_RINGLETS = 1 << 7,      /* curly hair (ringlets or the texture's own curl):
                                           each hair lit along its curl; with _WET
                                           two ringlet levels blended */
    PELT__SHELL_FUR_TAPS = 1 << 8,      /* lod.texture_taps > 1: fetches along the footprint */
    PELT__SHELL_GENERIC = (1 << 9) - 1, /* everything, chosen per fragment */
    PELT__SHELL_LIGHT_PASS = 1 << 9,    /* drawn from the light into its opacity slices */
    PELT__SHELL_GPU_SKIN = 1 << 10,     /* skinned in the vertex stage (for measuring) */
    PELT__SHELL_NO_GAP = 1 << 11,       /* no second read across the gap: the triangles the
                                           view split finds face-on (pelt__fur_gpu_view_split) */
    PELT__SHELL_TUFT_BASE = 1 << 12,    /* with _WET: a wet layer below the tufts' base
                                           (pelt__clump_below_tufts): darkened, its
                                           hair where it grew, no clump lookup */
    PELT__SHELL_VARIANTS = 1 << 13
};

/* What the caller asks of this frame (pelt_draw_desc, read by the renderer). */
typedef struct pelt__frame_switches {
    bool skin, fins, shells;
    bool inter_shadow;  /* the fur's inter-fur shadows, when its look has them */
    bool shadows;       /* the light's maps, when they are on */
    int cull_shells;    /* pelt_draw_desc's: 0 with the fins, 1 always, -1 never */
    bool one_height;    /* a range of layers is inspected: the finest shells */
    bool gpu_skin;      /* skin the shells in the vertex stage */
    bool strands;       /* the strand reference in place of fins and shells */
    bool flat_shells;   /* no view budget: the level's shells everywhere */
    bool lod_off;       /* as fur.lod = off, whatever the fur's mode */
    bool sub_shells;    /* wet layers in sub shells where tufts gather (pelt__clump_sub_shells) */
    bool as_dry;        /* wet fur drawn with the dry shaders (pelt_draw_debug.as_dry) */
} pelt__frame_switches;

/* The renderer's state the plan reads. */
typedef struct pelt__frame_setup {
    pelt_shadow_desc shadow;  /* resolved (pelt__shadow_resolved) */
    unsigned shadow_map_size; /* texels a side of the maps made, 0: none */
    pelt_ground_desc ground;  /* resolved (pelt__ground_resolved) */
    bool skinned_mesh;        /* the mesh has bones to skin with */
} pelt__frame_setup;

/* The lowest world height of the mesh for a model's y row, kept between
 * frames: the vertices are scanned again only when the row turns. */
typedef struct pelt__ground_cache {
    float row[3];
    float low;
    bool valid;
} pelt__ground_cache;

typedef struct pelt__frame_plan {
    pelt__frame_lod lod;
    pelt__frame_shadow shadow;     /* always filled: the frame block carries it */
    bool light_maps;               /* the light pass runs */
    pelt__shadow_frame light_pass;
    bool ground;                   /* the ground pass runs, on this disc: */
    float disc[4];                 /* centre x, plane height, centre z, radius */
    unsigned shell_features;       /* PELT__SHELL_* of the shells and fins */
    bool skin, fins, shells;       /* the passes that run */
    bool strands;                  /* the strand reference (docs/reference.md) */
    bool gpu_skin;                 /* the shells skin in the vertex stage */
} pelt__frame_plan;

/* Plans one frame of `fur` seen through `view`. No allocation; the ground
 * cache scans the mesh's vertices when the model's y row changes. */
void pelt__frame_plan_make(const pelt_fur *fur, const pelt_view *view, const pelt__frame_switches *sw,
                           const pelt__frame_setup *setup, pelt__ground_cache *cache, pelt__frame_plan *out);

#endif
