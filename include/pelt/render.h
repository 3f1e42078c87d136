/* pelt — the OpenGL renderer. Every call here needs the caller's OpenGL
 * 3.3+ core context current on the calling thread. */
#ifndef PELT_RENDER_H
#define PELT_RENDER_H

#include "pelt/base.h"
#include "pelt/camera.h"
#include "pelt/fur.h"
#include "pelt/mesh.h"
#include "pelt/shadow.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pelt_renderer pelt_renderer;

/* What is fixed when the renderer is made. Zero-initialised (or a NULL
 * desc) means malloc/free and no logger. */
typedef struct pelt_renderer_desc {
    /* The renderer allocates itself and its temporary vertex array through
     * hooks.allocator (both functions set, or neither) and frees through
     * it; shader compile and link errors also go to hooks.logger. */
    pelt_hooks hooks;
} pelt_renderer_desc;

/* What draws the fur (pelt_draw_desc.mode). */
typedef enum pelt_draw_mode {
    PELT_DRAW_SHELLS = 0, /* shells and fins (Lengyel et al. 2001), the default */
    /* The strand reference (docs/reference.md): every hair of the fur
       texture as opaque geometry along the curve the shells follow at its
       root; seconds a frame on llvmpipe, for stills. Hairs are thinner
       than a pixel: draw into a framebuffer several times the output's
       size (or multisampled) and downsample for coverage. */
    PELT_DRAW_STRANDS = 1
} pelt_draw_mode;

/* The tone curve between the linear light the hair is lit in and the
 * picture (docs/shading.md): both end in the sRGB encoding. */
typedef enum pelt_tone {
    /* A filmic curve (Narkowicz's ACES fit): a toe and a shoulder,
       highlights roll off below white instead of clipping. The default. */
    PELT_TONE_FILMIC = 0,
    PELT_TONE_NONE = 1 /* the exposed colour clamped to [0, 1] */
} pelt_tone;

/* Per-frame choices of one pelt_renderer_draw. Zero-initialised (or a NULL
 * pointer) draws everything. */
/* Switches for measuring and inspecting (pelt bench, the tests, the
 * viewer's toggles): documented but not a stable part of the API, so that
 * a new measurement needs no new field in pelt_draw_desc itself. Zero is
 * the normal frame. */
typedef struct pelt_draw_debug {
    bool no_shells;       /* skip the shells */
    bool no_inter_shadow; /* skip the fur's inter-fur shadows */
    /* Back-facing shells of a closed mesh (level of detail, docs/lod.md):
     * 0 = culled when the fins are drawn to carry the silhouette (default),
     * 1 = culled even without fins (for measuring the fins alone),
     * -1 = never culled. On an open mesh 0 and 1 leave out, where the skin
     * is drawn, the shells far round the back (lod.back_reach) that the
     * patch's own skin hides; -1 draws them all. */
    int cull_shells;
    /* pelt bench --floor: the shells with a one-fetch shader, the fur's
     * coverage against a 0.05 threshold in a constant colour, over the same
     * geometry and levels of detail. */
    bool floor_shader;
    /* pelt bench --plain: the classic shell renderer in place of the
     * shells, as a yardstick: every layer extruded along the vertex normal
     * over the full mesh (no strand shape, no level of detail, no culling),
     * one fetch of the fur texture blended in the fur's unlit colour, no
     * discard. Fins are the caller's to switch off. */
    bool plain_shells;
    /* Draw every triangle's shells with the wet shader while any fur is
     * wet, as before wet and dry were drawn apart (for measuring it). */
    bool no_wet_split;
    /* Draw every triangle's shells with the program that reads the fur
     * texture across the gap where the surface is seen from the side, as
     * before the view split drew the others without it (for measuring). */
    bool no_view_split;
    /* Draw each layer once, even where tufts gather their hairs (no wet
       sub shells, docs/wetness.md) or the shells stand far apart close up
       (lod.sub_shells, docs/lod.md), for measuring what they buy. */
    bool no_sub_shells;
    /* Composite every shell's coverage whole, as if each held other hairs,
       where a ray of sight that runs along a hair crosses it in several
       shells (docs/reference.md), for measuring what each shell's share
       changes. */
    bool no_overcount;
    /* Skip the light's shadow maps this frame, as if they were off
       (pelt_renderer_set_shadows turns them on). */
    bool no_shadows;
    /* pelt bench --animation: a skinned mesh's shells blend its bones per
       vertex and layer in the vertex stage, from the bind pose and the bones
       of the last pelt_mesh_pose, instead of reading the pose made once on
       the CPU (pelt_fur_set_pose). */
    bool skin_in_vertex_stage;
    /* The same shell count everywhere: no view budget (fewer shells where
       the fur is seen face-on, docs/lod.md), for measuring what it buys. */
    bool flat_shells;
    /* Drawn as fur.lod = "off" draws it: every shell over the full mesh,
       nothing culled, no view budget (pelt bench --lod-off). */
    bool lod_off;
    /* Shell fragments blended without writing depth, as before the shells
       wrote it: fur seen through the hole of a torus laid its outer shells
       over the fur in front of it (docs/reference.md, The near lip: fur
       in front hides fur behind), for measuring what the depth costs. */
    bool no_shell_depth;
    /* Wet fur drawn as if it were dry: the dry shaders everywhere, no
       tufts, the same geometry and state (pelt bench --clumps: the wet
       frame against the dry one, alternated in one run). */
    bool as_dry;
    /* Every wet layer drawn with the tufts' program, even below the tufts'
       base where a clump leaves its hairs in place (docs/wetness.md, Tuft
       light), for measuring what the lean program there saves. */
    bool no_tuft_base;
} pelt_draw_debug;

typedef struct pelt_draw_desc {
    bool no_skin;   /* skip the opaque skin pass */
    bool no_fins;   /* skip the fins (Lengyel et al. §2.3; drawn by default) */
    bool fins_unfaded; /* draw every fin at full opacity (Lengyel Fig. 4e) */
    bool no_outline_hairs; /* the fin texture alone: no outline hairs in its
                              place (pelt_fur_fins.hairs, docs/reference.md) */
    /* Draw only shells first_layer .. first_layer + layer_count - 1
     * (layer_count 0 = through the outermost): for inspecting one height
     * of the fur, and for level of detail. Still one instanced draw. */
    unsigned first_layer, layer_count;
    /* Shells and fins (0, the default) or the strand reference, which
       draws every hair in place of both (no_fins and debug.no_shells unused). */
    pelt_draw_mode mode;
    /* The picture from the linear light: the colour times `exposure`
       (0 means 1, the default; at most 64), then the tone curve, then sRGB. */
    float exposure;
    pelt_tone tone;
    pelt_draw_debug debug; /* measuring and inspecting; unstable */
} pelt_draw_desc;

/* What the last pelt_renderer_draw did. */
typedef struct pelt_render_stats {
    unsigned skin_draw_calls;  /* 1 when the skin was drawn, else 0 */
    unsigned shell_draw_calls; /* 1 when shells were drawn: all in one instanced draw
                                  (a shell at a time, two draws each, where wet and
                                  dry or face-on and side-on are drawn apart) */
    size_t face_on_triangles;  /* of mesh_triangles, those the view split drew
                                  without the read across the gap (docs/lod.md);
                                  0: not split */
    unsigned shell_instances;  /* shell layers that draw covered */
    unsigned sub_shells;       /* wet shells drawn beyond one a layer, where
                                  tufts gather their hairs (docs/wetness.md,
                                  Sub shells) */
    unsigned layer_shells;     /* close up, the shells every layer was drawn
                                  as (lod.sub_shells, docs/lod.md); 1: one */
    unsigned fin_draw_calls;   /* instanced fin draws: 1, or 2 where wet and dry fins are drawn apart */
    unsigned shadow_draw_calls; /* the light's maps: 2 (skin depth, all shells'
                                   opacity in one instanced draw), else 0 */
    unsigned ground_draw_calls; /* 1 when the ground was drawn */
    unsigned strand_draw_calls; /* 1 when the strand reference was drawn */
    unsigned strand_failures;  /* 1 when the strand reference was asked for and
                                  could not be drawn: its program did not build,
                                  its hairs did not fit in memory, or the context
                                  has no buffer textures (WebGL2); the logger says
                                  which. A fur with no hair draws nothing and
                                  fails nothing */
    size_t strands;            /* hairs the strand reference drew */
    size_t fins;               /* fins (mesh edges) that draw submitted; the
                                  faded-out ones collapse in the vertex stage */
    size_t outline_hairs;      /* the outline's hairs drawn (fur fins.hairs),
                                  in one instanced draw after the shells */
    unsigned fin_rows;         /* quads up each fin: as few as follow the bent
                                  and curled strands to within a pixel */
    size_t triangles;          /* triangles submitted by all passes, every shell
                                  layer counted */
    unsigned mesh_level;       /* the shells' geometric level of detail (0: the
                                  full mesh) */
    size_t mesh_triangles;     /* triangles of that level */
    unsigned shell_level;      /* Lengyel §2.4: ceil(layers / 2^shell_level) shells */
    float shell_blend;         /* how far towards the next shell level (0..1) */
    bool culled;               /* back-facing shells were culled */
    size_t upload_bytes;       /* bytes sent to GL for this frame: pelt_renderer_upload
                                  calls since the previous draw and the draw's own
                                  (strand tips, colour texture, changed mask
                                  rectangle, uniform blocks, the fins a view shows
                                  and their strands) */
    unsigned fin_level;        /* the fins' geometric level: mesh_level, or
                                  coarser where that level's fins would stand
                                  closer than the fin texture's slab */
} pelt_render_stats;

/* GL state contract of pelt_renderer_create, pelt_renderer_upload and
 * pelt_renderer_draw (tests/gl/test_render.c checks it).
 *
 * Needs: for draw, the target framebuffer bound to GL_DRAW_FRAMEBUFFER
 * (with a depth buffer: the skin writes depth, the shells test against it
 * and write the depth of every hair fragment they draw, so after draw the
 * depth buffer holds the skin's and the fur's nearest hair)
 * and glViewport set to the part of it to draw into. Draw does not clear.
 * Used as found, never changed: framebuffer bindings, viewport, scissor,
 * stencil, clear values, colour write mask, polygon mode and offset,
 * glCullFace/glFrontFace (culling itself is off), multisampling, sRGB,
 * primitive restart, pixel pack state, texture units 10 and up. With the
 * light's shadows on, draw renders its maps into its own framebuffers
 * first and puts back the framebuffer bindings, viewport, scissor test and
 * colour mask it found (read with glGet).
 * Set by each call for itself, so what it finds there does not matter,
 * and left at GL's initial values afterwards:
 *   - program 0, vertex array 0, GL_ARRAY_BUFFER 0;
 *   - GL_UNIFORM_BUFFER 0, and 0 on uniform buffer binding points 0 and 1;
 *   - texture units 0 to 9 with texture 0 on GL_TEXTURE_2D and
 *     GL_TEXTURE_2D_ARRAY; GL_ACTIVE_TEXTURE GL_TEXTURE0;
 *   - GL_DEPTH_TEST off, glDepthFunc(GL_LESS), glDepthMask(GL_TRUE);
 *   - GL_BLEND off, glBlendFunc(GL_ONE, GL_ZERO), glBlendEquation(GL_FUNC_ADD);
 *   - GL_CULL_FACE off;
 *   - GL_PIXEL_UNPACK_BUFFER 0, GL_UNPACK_ALIGNMENT 4, GL_UNPACK_ROW_LENGTH,
 *     _SKIP_ROWS, _SKIP_PIXELS, _IMAGE_HEIGHT and _SKIP_IMAGES 0.
 * pelt_renderer_destroy deletes its objects (GL unbinds what was bound). */

/* Compiles the shaders and uploads mesh and fur. The mesh and fur must
 * outlive the renderer. desc may be NULL. Free with pelt_renderer_destroy
 * (context current). */
pelt_status pelt_renderer_create(const pelt_mesh *mesh, pelt_fur *fur,
                                 const pelt_renderer_desc *desc,
                                 pelt_renderer **out, pelt_error *err);
void pelt_renderer_destroy(pelt_renderer *renderer);

/* Uploads what changed in the fur since the last upload (strand tips,
 * colour texture, the changed rectangle of the wetness mask, the look).
 * Draw calls it too; call it first to time uploads apart from drawing. */
void pelt_renderer_upload(pelt_renderer *renderer);

/* Draws skin then all shells (one instanced draw call) into the currently
 * bound framebuffer with the camera and light of `view`. draw may be NULL
 * (everything). No allocation, no file I/O. */
void pelt_renderer_draw(pelt_renderer *renderer, const pelt_view *view,
                        const pelt_draw_desc *draw);

/* The light's shadows (pelt/shadow.h, docs/shadows.md): off until set.
 * Makes or remakes the maps when their size changes (never in a draw).
 * PELT_ERR_INVALID_ARGUMENT for a size or slice count out of range,
 * PELT_ERR_GL when the maps cannot be drawn into; the shadows are then off. */
pelt_status pelt_renderer_set_shadows(pelt_renderer *renderer, const pelt_shadow_desc *shadows,
                                      pelt_error *err);
/* The ground plane under the mesh (pelt/shadow.h): off until set. */
void pelt_renderer_set_ground(pelt_renderer *renderer, const pelt_ground_desc *ground);

/* What the last pelt_renderer_draw did (all zero before the first). */
pelt_render_stats pelt_renderer_get_stats(const pelt_renderer *renderer);

#ifdef __cplusplus
}
#endif
#endif
