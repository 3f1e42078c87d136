/* pelt — fur over a mesh: parameters, texture synthesis, per-frame state. */
#ifndef PELT_FUR_H
#define PELT_FUR_H

#include "pelt/base.h"
#include "pelt/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pelt_fur pelt_fur;

/* Procedural colour patterns, multiplied with the hair colour (0 = none). */
typedef enum pelt_color_pattern {
    PELT_COLOR_PATTERN_NONE = 0,
    PELT_COLOR_PATTERN_SPOTS,
    PELT_COLOR_PATTERN_STRIPES,
    PELT_COLOR_PATTERN_NOISE
} pelt_color_pattern;

/* The hair lighting model: Kajiya-Kay evaluated per fragment (Silva et
 * al. Eq. 6), or Lengyel et al.'s §2.4 table K_a + K_d (1 - u^2)^(P_d/2) +
 * K_s (1 - v^2)^(P_s/2), u = T.L, v = T.H, read from a 32x32 texture. */
typedef enum pelt_shading_model {
    PELT_SHADING_KAJIYA_KAY = 0,
    PELT_SHADING_LENGYEL_TABLE,
    /* Scheuermann's real-time reading of Marschner et al.: two highlights
       shifted along the strand, transmission, occlusion from the fur's
       density (docs/shading.md) */
    PELT_SHADING_MARSCHNER
} pelt_shading_model;

/* The shape of the strands simulated into the fur texture (Lengyel et
 * al. 2001 §2.2), when they curl (look.strand_curl > 0). */
typedef enum pelt_strand_curl_shape {
    PELT_STRAND_CURL_HELIX = 0, /* a corkscrew round the strand's axis: curly hair */
    PELT_STRAND_CURL_WAVE       /* a sine along the texture's u: wavy hair */
} pelt_strand_curl_shape;

/* Whose phase Silva's curl phi(h) (Eq. 4) turns with. */
typedef enum pelt_curl_phase {
    /* Ringlets (beyond Silva, docs/method.md): the strands of the fur
       texture gather in locks a few curl radii across (look.curl_lock);
       a lock's strands turn in step, out of step with the next lock's.
       The curl is drawn into the texture strand by strand, at full, half
       and no amplitude; the shells blend the two levels around
       1 - wetness, so water still takes the curl out. Default. */
    PELT_CURL_RINGLETS = 0,
    /* Eq. 4 as printed: one phase for all, the shells move as a whole at
       each vertex, so curls read as waves across a region. */
    PELT_CURL_COHERENT,
    /* Ringlets without locks: every strand turns with its own phase, out
       of step with its neighbours. */
    PELT_CURL_STRANDS
} pelt_curl_phase;

/* How the fur looks: the synthesized hair volume (Lengyel et al. 2001
 * §2.2), its tiling, the colours and Kajiya-Kay shading (Silva et al. Eq. 6)
 * and curl (Silva Eq. 4). A zero field means its default. */
typedef struct pelt_fur_look {
    unsigned texture_size;   /* fur texture width = height, default 256 */
    float density;           /* strands per texture tile, default 3000 */
    float strand_radius;     /* strand radius at the root in texels, default
                                1.6 texture_size / 256: the same hair at every
                                texture size */
    float taper;             /* 0 = cylinder, 1 = tip ends in a point, default 0.8 */
    /* Curly and wavy hair in the texture itself (Lengyel et al. §2.2): every
       simulated strand winds with its own phase, out of step with its
       neighbours. Water does not undo it (Silva's curl below is the one
       that wetness takes out). */
    float strand_curl;       /* curl radius in texels, 0..64, default 0 (straight) */
    float strand_curl_turns; /* turns over the full height, (0, 32], default 2 */
    pelt_strand_curl_shape strand_curl_shape; /* default PELT_STRAND_CURL_HELIX */
    float tiling;            /* fur-texture tiles per world unit, default
                                5 / the mesh's bounding-box diagonal */
    float color[3];          /* base hair colour (sRGB, lit in linear light), default (0.55, 0.34, 0.18) */
    float tip_color[3];      /* colour at the tips, default (1, 0.82, 0.58) */
    float skin_color[3];     /* bare skin where grooming thins the hair
                                (pelt/groom.h density), default (0.78, 0.56, 0.47) */
    float color_scale;       /* colour texture repeats per uv unit, default 1 */
    float specular[3];       /* Kajiya-Kay K_s, default (0.9, 0.85, 0.8) */
    float shininess;         /* Kajiya-Kay exponent p, default 20 */
    float shadow;            /* K_shadow >= 1 of Silva Eq. 6, default 2 */
    float curl_frequency;    /* omega of Silva Eq. 4 (radians over the length), default 0 */
    float curl_radius;       /* K_alpha of Silva Eq. 4 in world units, default 0 */
    pelt_curl_phase curl_phase; /* default PELT_CURL_RINGLETS */
    float curl_lock;         /* ringlets' locks across, in curl radii, default 2 */
    /* Kenwright's inter-fur shadows: where a shell has no hair but the hair
       a small step towards the light does, that hair's shadow darkens what
       lies below. Off by default. */
    bool inter_shadow;
    float inter_shadow_offset;   /* the step in fur-texture texels, default 4 */
    float inter_shadow_darkness; /* opacity of the shadow, (0, 1], default 0.8 */
    pelt_shading_model shading;  /* default PELT_SHADING_KAJIYA_KAY */
    float diffuse_power;         /* P_d of Lengyel's table, default 1 (= Kajiya-Kay's
                                    diffuse); its P_s is `shininess` */
} pelt_fur_look;

/* Strand dynamics (Silva et al. §3.2.1, Eq. 2): tip mass, spring constant
 * and drag. The defaults scale with the length so gravity sags a strand by
 * 0.4 L0 at every size, with a damping ratio of 0.25. */
typedef struct pelt_fur_dynamics {
    float mass;              /* default 1 */
    float spring_k;          /* default mass * 9.81 / (0.4 * length) */
    float damping;           /* default 0.5 * sqrt(spring_k * mass) */
    unsigned threads;        /* threads the strand step runs on, the caller's
                                included: 0 (default) = one per core, at most
                                16; 1 = the caller's thread alone. The fur
                                starts them at creation; the result is the
                                same whatever the count */
} pelt_fur_dynamics;

/* How wet fur splits into clumps (pelt_fur_wet.clumps). */
typedef enum pelt_wet_clumps {
    PELT_CLUMPS_NATURAL = 0, /* tufts of varied size, cells fixed on the surface */
    PELT_CLUMPS_DROPLET      /* one clump per droplet (Silva et al. Alg. 1) */
} pelt_wet_clumps;

/* Wet fur (Silva et al. §3.1, §3.3; docs/wetness.md). */
typedef struct pelt_fur_wet {
    unsigned mask_size;      /* wetness mask width = height, default 256, at most 8192 */
    float clump_blend;       /* w of Silva Eq. 5 in [0,1], default 0.5 */
    float clump_tightness;   /* s in (0,1]: 1 = tips meet at the clump centre, default 0.9 */
    float darken;            /* brightness fully wet fur loses, [0,1), default 0.5 */
    float strays;            /* share of hairs that stays out of the tufts,
                                [0, 1], default 0.1 */
    /* How wet fur splits into clumps (docs/wetness.md, Natural clumps):
       PELT_CLUMPS_NATURAL (default), tufts of varied size from cells fixed
       on the surface (Bruderlin's clump size), so a big droplet makes many
       tufts and overlapping droplets keep the same ones; or
       PELT_CLUMPS_DROPLET, one clump per droplet as Silva et al.'s Alg. 1. */
    pelt_wet_clumps clumps;
    float clump_size;        /* natural clumps' mean width in world units,
                                default as long as the fur, kept between 20
                                and 100 hairs a tuft */
    /* Wet fur shines (Silva §4 points to Gupta and Magnenat-Thalmann 2007:
       water on a hair makes its surface a smooth film): the Kajiya-Kay
       highlight grows sharper and stronger with the wetness rho, the
       exponent by 1 + (gloss_sharpness - 1) rho and the specular colour by
       1 + (gloss - 1) rho (docs/wetness.md, Wet shine). */
    float gloss;             /* specular strength of fully wet fur, a multiple
                                of look.specular in [1, 16], default 2 */
    float gloss_sharpness;   /* Kajiya-Kay exponent of fully wet fur, a multiple
                                of look.shininess in [1, 64], default 8 */
    /* Water is heavy (docs/dynamics.md, Wet fur hangs): a strand at
       wetness rho carries weight * rho times its tip's mass in water, so
       wet fur hangs further under gravity and swings slower. */
    float clump_lean;        /* natural tufts lean: each tuft's tip stands off
                                its centre by up to this share of its radius
                                along each axis, [0, 1], default 0.3 */
    float weight;            /* water on soaked fur, a multiple of
                                dynamics.mass in [0, 16], default 1: a
                                soaked strand is twice as heavy; 0: the
                                water weighs nothing */
    float lie;               /* wet fur lies along its grain: soaked fur is
                                combed this many more degrees along the comb
                                direction (the atlas's direction field, or
                                the fur texture's u) than dry fur, the angle
                                growing with the wetness, [0, 60], default 0
                                (docs/wetness.md, Wet fur lies down) */
} pelt_fur_wet;

/* Combing (Lengyel et al. §3). */
typedef struct pelt_fur_comb {
    float slant;             /* comb angle in degrees, 0..60, along the mesh's
                                comb directions (pelt_mesh_data.comb), else
                                along the fur texture's u axis; default 0 */
} pelt_fur_comb;

/* Fins (Lengyel et al. §2.2-2.3): quads on the mesh edges near the
 * silhouette, textured with the same hair seen from the side. */
typedef struct pelt_fur_fins {
    float length;            /* fin hair height as a multiple of the fur
                                length, default 1 (Lengyel Fig. 5 used longer) */
    float density;           /* width in texels of the slab of hair composited
                                into the fin texture: wider = denser fins,
                                default texture_size / 16 */
    float curl;              /* sideways sine amplitude of fin hair in texels,
                                default 0 (curlier than the shells when > 0) */
    float curl_turns;        /* turns of that sine over the height, default 2 */
    float hairs;             /* the outline's hairs: the share of the hairs a
                                fin near the silhouette stands for (its
                                slab's) that it draws as geometry where the
                                fur is a few pixels to a few tens long on
                                screen, so that single hairs cross the
                                outline (the fin texture's quads elsewhere),
                                default 0.5; pelt_draw_desc.no_outline_hairs
                                leaves them out */
} pelt_fur_fins;

/* Level of detail (Lengyel et al. §2.4 and beyond it, docs/lod.md): fewer
 * shells as the fur shrinks on screen, blended so nothing pops; simplified
 * shell geometry as triangles shrink; back-facing shells culled on closed
 * meshes, where the fins carry the silhouette. */
typedef enum pelt_lod_mode {
    PELT_LOD_AUTO = 0, /* the levels follow the view (default) */
    PELT_LOD_OFF,      /* every shell over the full mesh, nothing culled */
    PELT_LOD_FIXED     /* shell_level and mesh_level below, whatever the view */
} pelt_lod_mode;

typedef struct pelt_fur_lod {
    pelt_lod_mode mode;
    unsigned shell_level;    /* FIXED: ceil(layers / 2^shell_level) shells */
    unsigned mesh_level;     /* FIXED: simplified mesh level, 0 = full (clamped
                                to the levels the mesh has) */
    float shell_pixels;      /* AUTO: the finest shell level whose spacing on
                                screen, seen side-on, is at least this many
                                pixels; where the fur is seen face-on each
                                vertex blends towards the next level as far
                                as its foreshortened spacing stays within it
                                (the view's budget, docs/lod.md); default 0.5 */
    float mesh_error_pixels; /* AUTO: the coarsest mesh level whose error on
                                screen stays within this, default 0.5 ... */
    float mesh_edge_pixels;  /* ... and whose mean edge on screen within this
                                (strands, groom and light are per vertex),
                                default 8 */
    float back_reach;        /* a closed mesh drawn without fins: its
                                back-facing shells carry the silhouette
                                where N.V >= -back_reach (further round the
                                back the skin hides them), default 0.3 */
    unsigned texture_taps;   /* the most fetches a shell fragment takes of the
                                fur texture along its footprint's longer
                                side, 1..8: where the fur is seen at a
                                grazing angle one fetch blurs its hairs
                                across the view, n fetches n times less
                                (docs/shading.md). Default 1 */
    float texture_aniso;     /* how many texels of the footprint's longer
                                side one fetch may take to a pixel where
                                the shells lie within 0.7 px of each other
                                on screen, 1..16: fur seen at a grazing
                                angle stays sharp across the view, at the
                                price of aliasing along it (docs/shading.md).
                                Default 4; 1 reads at the long side's level */
    float edge_depth;        /* where the surface is seen edge-on, a shell may
                                stand for up to this many crossings of a
                                hair (1..64): the outer shells above a lip's
                                outline cover the ray as the hairs' sides do
                                (docs/reference.md). Default 16; 1 is
                                off (each shell one crossing) */
    unsigned sub_shells;     /* close up, where the shells stand further apart
                                on screen than 1.4 pixels (seen side-on,
                                at the fur nearest the eye), each layer is
                                drawn as up to this many sub shells down to
                                the one below (1..8), so that the rows an
                                edge-on view shows close and the fur
                                texture is read as sharp as the nearer
                                spacing allows (docs/lod.md). Default 4;
                                1 is off (one shell a layer) */
} pelt_fur_lod;

/* Fur parameters, one home each. A zero field means its documented
 * default; the defaults are the paper's Table 1 set-up (256x256 fur
 * texture and wetness mask; its 16 layers where the fur is seen face-on,
 * twice that edge-on). These are the only defaults: the strands
 * and the texture synthesis take them resolved, and test_fur_defaults
 * checks every default stated here against pelt_fur_get_desc. */
typedef struct pelt_fur_desc {
    unsigned layers;         /* shells N where the fur is seen edge-on (half of
                                them face-on, lod.shell_pixels), default 32,
                                at most 256; curled hair takes more
                                (layers_per_turn), and pelt_fur_get_desc
                                gives the count the fur has */
    float layers_per_turn;   /* shells a turn of the hair's curl takes at least
                                (Silva's look.curl_* and the texture's
                                look.strand_curl_*, their turns added): a
                                curl of T turns over the length gets
                                max(layers, ceil(T layers_per_turn)) shells,
                                at most 256. Fewer draw a helix as flat rings
                                (docs/method.md). Default 13; 1 keeps
                                `layers` for any curl of fewer turns */
    float length;            /* fur length L0 in world units, default 3% of
                                the mesh's bounding-box diagonal */
    uint32_t seed;           /* texture and dynamics seed, default 1 */
    pelt_fur_look look;
    pelt_fur_dynamics dynamics;
    pelt_fur_wet wet;
    pelt_fur_comb comb;
    pelt_fur_fins fins;
    pelt_fur_lod lod;
    pelt_hooks hooks;        /* allocator and logger, kept by the fur: every
                                block it owns (texture, strands, mask, BVH,
                                surface index, rain, colour) and its scratch
                                comes from the allocator and goes back to it
                                at pelt_fur_destroy; an allocator with only one
                                of alloc/free is PELT_ERR_INVALID_ARGUMENT */
} pelt_fur_desc;

/* One of the curl looks of Silva et al. Fig. 7 by name ("straight",
 * "wavy", "few-large-curls", "many-small-curls"; also spelt "large_curls",
 * "small_curls"): its omega (radians over the length) and radius as a
 * fraction of the fur length. False for an unknown name. */
bool pelt_fur_curl_look(const char *name, float *omega, float *radius_fraction);

/* Fills look.curl_frequency and look.curl_radius of `d` from one of the
 * curl looks of Silva et al. Fig. 7: "straight", "wavy", "few-large-curls",
 * "many-small-curls", unless they are already non-zero. The radius is a
 * fraction of the fur length (d->length, or its default for `mesh`). */
pelt_status pelt_fur_desc_curl_preset(pelt_fur_desc *d, const pelt_mesh *mesh, const char *name,
                                      pelt_error *err);

/* Synthesizes the fur texture (Lengyel et al. 2001 §2.2) and the strand
 * state for `mesh`. The mesh must outlive the fur. Free with
 * pelt_fur_destroy. */
pelt_status pelt_fur_create(const pelt_mesh *mesh, const pelt_fur_desc *desc,
                            pelt_fur **out, pelt_error *err);
void pelt_fur_destroy(pelt_fur *fur);

/* The desc with every default filled in. */
pelt_fur_desc pelt_fur_get_desc(const pelt_fur *fur);

/* Where a ray (mesh-local origin and direction) first meets the mesh:
 * the point into hit (may be NULL). False on a miss or non-finite input.
 * No allocation: cheap enough to run under a moving cursor. */
bool pelt_fur_pick(const pelt_fur *fur, const float origin[3], const float direction[3],
                   float hit[3]);

/* A colour texture that modulates the hair colour (uv space of the mesh).
 * RGBA8, width * height * 4 bytes, copied. */
pelt_status pelt_fur_set_color_texture(pelt_fur *fur, const uint8_t *rgba,
                                       unsigned width, unsigned height,
                                       pelt_error *err);

/* Makes a seeded, tileable 512x512 pattern the colour texture (NONE
 * removes the colour texture). */
pelt_status pelt_fur_set_color_pattern(pelt_fur *fur, pelt_color_pattern pattern, uint32_t seed,
                                       pelt_error *err);

#ifdef __cplusplus
}
#endif
#endif
