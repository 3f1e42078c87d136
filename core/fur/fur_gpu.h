/* What a renderer uploads from a pelt_fur: one snapshot struct filled by
 * one call, so that gl/ never opens the handle (it must not include
 * fur_internal.h), plus the few calls that take or compute. GL-free: plain
 * pointers, sizes and version counters. Pointers are owned by the fur and
 * stay valid until it is destroyed or the data is replaced (a version
 * change says so). */
#ifndef PELT_CORE_FUR_GPU_H
#define PELT_CORE_FUR_GPU_H

#include "pelt/fur.h"

#include "core/fur/fins.h" /* the fins and the outline's hairs (gl/fin_pass.c) */
#include "core/fur/lod.h"
#include "core/fur/shadow_map.h" /* the light's maps (gl/shadow_pass.c, renderer.c) */
#include "core/fur/strand_ref.h" /* the strand reference (gl/strands_pass.c) */
#include "core/wet/clump.h"        /* the wet shells' sub shells (gl/shell_pass.c) */
#include "core/wet/wet_split.h"    /* wet and dry triangles drawn apart (gl/gpu_mesh.c) */

/* A skinned mesh's skin, for skinning in the vertex stage (measured
 * against the CPU pose by pelt bench --animation): per vertex 4 bones and
 * weights and the bind-space position, normal, tangent (10 floats); the
 * bones' matrices of the last pelt_mesh_pose (16 floats a bone). */
typedef struct pelt__gpu_skin {
    const uint16_t *bones;
    const float *weights;
    const float *bind;
    const float *matrices;
    size_t bone_count;
} pelt__gpu_skin;

/* Everything a renderer reads of a fur, in one struct that one call fills
 * (pelt__fur_gpu_snapshot): plain pointers owned by the fur, sizes and
 * version counters that change with the data. */
typedef struct pelt__fur_snapshot {
    const pelt_mesh *mesh;      /* the mesh the fur was made for */
    const pelt__lod_chain *lod; /* shell geometry levels, level 0 the full
                                   mesh in vertex-cache order, each with its fins */
    /* The fur texture volume (Lengyel et al. 2001 §2.2, core/fur/furtex.h):
       RGBA8, premultiplied, volume_size^2 texels by volume_slices (layers +
       1, slice 0 the opaque skin), slice after slice; then the coarser
       shell levels' lod_slices (0, volume_lod NULL, with level of detail
       off), which follow the volume's in the GPU array. */
    const uint8_t *volume;
    unsigned volume_size, volume_slices;
    const uint8_t *volume_lod;
    unsigned lod_slices;
    /* Ringlets (docs/method.md): the curl's amplitude levels the texture
       holds, 1 without ringlets. With more, the volume and the lod slices
       hold that many sets one after the other (level 0 the full curl), and
       the GPU array takes level k's slice s at k * (slices + lod slices) + s. */
    unsigned ringlet_levels;
    float occlusion_depth;    /* the fur's optical depth for the hair model's
                                 occlusion (pelt__occlusion_depth) */
    float clump_lean;         /* how far the tufts lean (pelt__fur_clump_lean) */
    float wet_lie;            /* wet.lie in radians (pelt__fur_wet_lie) */
    float vertex_curl_radius; /* Silva's K_alpha for the shells' vertex stage,
                                 0 when the texture holds the curl */
    const float *fur_uvs;     /* fur-texture coordinates in tiles, 2 a vertex */
    float fur_per_uv[2];      /* fur tiles per uv unit along u and v */
    const float *tips;        /* strand tip offsets p - p_root, mesh-local, 3 a vertex */
    unsigned tips_version;
    const float *pose;        /* pelt_fur_set_pose: position, normal, tangent,
                                 10 floats a vertex; NULL before the first */
    unsigned pose_version;
    bool skinned;             /* the mesh has a skeleton: `skin` is set */
    pelt__gpu_skin skin;
    const void *groom;        /* one pelt__groom_vertex a vertex (core/fur/groom.h), */
    size_t groom_stride;      /* this many bytes apart */
    const uint8_t *fin_texture; /* RGBA8, premultiplied, row 0 at the root;
                                 one fin_width x fin_height image per ringlet level */
    unsigned fin_width, fin_height;
    const uint8_t *color;     /* the colour texture, RGBA8, or NULL */
    unsigned color_width, color_height, color_version;
    /* The wetness mask (Silva et al. §3.1, core/wet/mask.h): texels of 4
       floats (clump centre, radius, wetness), row 0 at v = 0. */
    const float *mask;
    unsigned mask_width, mask_height;
    bool any_wet;             /* false: every texel dry, the shells' dry variant */
} pelt__fur_snapshot;

/* A colour as the renderer's blocks and uniforms take it: sRGB decoded to
 * linear light (pelt__srgb_decode, core/fur/shading.h). */
void pelt__fur_gpu_linear_rgb(const float srgb[3], float out[3]);

/* Fills *out from the fur; cheap (no copy of any array), once a frame or
 * wherever a renderer needs it. */
void pelt__fur_gpu_snapshot(const pelt_fur *fur, pelt__fur_snapshot *out);

/* Takes the range of vertices [range[0], range[1]) whose groom changed
 * since the last take; false when nothing changed. */
bool pelt__fur_gpu_take_groom_dirty(pelt_fur *fur, size_t range[2]);

/* One frame of fins (core/fur/fin_frame.c), drawn from a table of fins
 * and a table of the vertices they stand on. A fin: 4 words, its ends as
 * indices into the level's fin_vertices, the bits of its texture start and
 * of its fade (Lengyel's max(0, 2|p| - 1) for view_dir, in mesh space; 1
 * when unfaded). A vertex: PELT__FIN_VERTEX_TEXELS texels of 4 floats: for
 * h = r / rows, r = 0 .. rows, the displaced strand's point (w 1) and unit
 * tangent (w 0), mesh-local, as shell_vs.glsl displaces it (with the fins'
 * length multiple); then the normal with the density in w; then the uv
 * and the hair colour's bytes, two a float (r 256 + g, b 256 + a). */
#define PELT__FIN_HEIGHTS 4 /* rows + 1 at most */
#define PELT__FIN_VERTEX_TEXELS (2 * PELT__FIN_HEIGHTS + 2)
typedef struct pelt__fin_frame_desc {
    unsigned level; /* the level of detail whose fins (lod.h) */
    unsigned rows;  /* quads up a fin at most, 1 .. PELT__FIN_HEIGHTS - 1 */
    /* The chord error a fin may show, mesh units: the fewest rows (1, 2 or
       `rows`) whose straight quads stay within it of every strand's curve
       are used. 0: always `rows`. */
    float row_error;
    float view_dir[3];
    bool unfaded;   /* every fin at full opacity (Lengyel Fig. 4e) */
    /* A closed mesh whose skin hides its far side: fins whose two ends
       face away from the viewer (their normals' component along view_dir
       above PELT__FIN_BACK) are left out too. */
    bool hidden_back;
    /* The full mesh's level only: per mesh vertex, 1 where a triangle at it
       holds water (pelt__wet_split's vertex_wet), or NULL. The fins with
       both ends dry come first in the table, then the others. */
    const uint8_t *vertex_wet;
    /* Every fin's opacity times this, where the view fades them (0: 1).
       Close up the shells stand in sub shells k to a layer and hold the
       hair across the outline the fins stood for: 1 / k (gl/fin_pass.c,
       docs/lod.md). */
    float opacity;
} pelt__fin_frame_desc;

/* How far past the silhouette a fin's ends may face away and still be
 * drawn when the back is hidden: the cosine's bound, about 15 degrees past
 * the silhouette, where a fin as tall as a quarter of the local radius
 * stops reaching past the outline. */
#define PELT__FIN_BACK 0.25f

/* A fin whose view fade, max(0, 2|p| - 1), is below this is left out; its
 * spacing's opacity does not count (close fins add up). */
#define PELT__FIN_CUT 0.05f

/* Writes the fins the view shows (view fade below PELT__FIN_CUT left out, and those
 * behind a closed mesh when hidden_back) into `fins`
 * (4 words each, room for the level's fin_count) and returns how many;
 * when any, writes all the level's fin vertices (fin_vertex_count of them)
 * into `vertices`, their strands at h = r / *rows for r = 0 .. *rows (the
 * rows chosen, see row_error). *dry: how many of them come first with both
 * ends dry (all of them without vertex_wet). No allocation. */
size_t pelt__fur_gpu_fin_frame(const pelt_fur *fur, const pelt__fin_frame_desc *d, uint32_t *fins,
                               float *vertices, unsigned *rows, size_t *dry);

/* Shell triangles drawn apart by the view (gl/shell_pass.c, docs/lod.md).
 * The shell fragment reads the fur texture a second time where the eye
 * sees the surface from the side (shell_gap's weight, shell_lod.glsl:
 * above 0 only for |N.V| between PELT__SHELL_GAP_OUTLINE_NONE and
 * PELT__SHELL_GAP_NONE), and llvmpipe runs a read behind a branch on
 * every fragment of a program that has it. */
typedef struct pelt__view_split_desc {
    unsigned level;      /* the level of detail whose triangles (lod.h) */
    bool full_mesh;      /* the mesh's own triangles instead (lod off) */
    float model[16];     /* the mesh's placement, column-major (pelt_view) */
    float model_scale;   /* its scale, as the vertex stage takes it: |model x| */
    float eye[3];        /* world */
    float margin;        /* widens the band on both sides (|N.V| units) */
    /* The shells' spacing side-on on screen, as the vertex stage gates the
     * read by it (u_shell_view.x: pixels times clip w per unit of groom
     * length; 0: not known, no gate), and the clip w row of the view and
     * projection (column-major: w = dot(w_row, (world, 1))). */
    float shell_spacing;
    float w_row[4];
    /* The triangles to split (3 indices each, triangle_count of them), of
     * the level's or the mesh's own (the wet split's dry or wet part); NULL:
     * all of the level's. */
    const uint32_t *triangles;
    size_t triangle_count;
} pelt__view_split_desc;

/* The margin the renderer takes: the vertex stage's normal and ray, in
 * float, against these in C. */
#define PELT__VIEW_SPLIT_MARGIN 0.02f

/* Writes the drawn triangles (3 indices each) into `indices`: first those
 * none of whose vertices may see the surface from the side, then the
 * others, each part in the given order; returns how many come first and
 * sets *total. A vertex may when |N.V| lies within the band widened by the
 * margin and by twice its hair's length over its distance to the eye (the
 * vertex stage takes V at the shell's vertex, and a coarse level's fitted
 * normal, as here), and, where the spacing is known, when its shells stand
 * at least PELT__SHELL_GAP_PX_NONE apart on screen less the margin's share
 * (sub shells only bring them closer). vertex_side: scratch of a byte per
 * mesh vertex. No allocation. */
size_t pelt__fur_gpu_view_split(const pelt_fur *fur, const pelt__view_split_desc *d, uint8_t *vertex_side,
                                uint32_t *indices, size_t *total);

/* One mip level of a hair texture's slice (the fur volume, the fin
 * texture) from the level above it (w x h texels,
 * premultiplied as the volume is; an odd side of 1 kept): each 2 x 2
 * block's mean, rounded up so a thin hair's faint edge lasts down the
 * chain (glGenerateMipmap on Mesa's llvmpipe rounds likewise, within
 * 0.1/255 on average), except the id. A mean of several hairs' ids is an
 * id none of them has: the ringlets' phase (the fins') and grooming's
 * density test read it. So the id is that of the block's texel with the
 * most coverage, premultiplied by the block's coverage: a read at any
 * level finds a real hair's id. (The shells' ringlets still read theirs
 * at the finest level: the bilinear read blends up to four texels' ids.)
 * Writes max(w/2,1) x max(h/2,1) texels to `down`. */
void pelt__fur_gpu_mip_down(const uint8_t *up, unsigned w, unsigned h, uint8_t *down);

/* Lengyel et al.'s §2.4 hair lighting table for the fur's material
 * (core/fur/shading.h: pelt__lengyel_table): 32x32 texels of (diffuse,
 * specular). */
#define PELT__FUR_GPU_LIGHT_TABLE 32
void pelt__fur_gpu_light_table(const pelt_fur *fur, float *out);

/* Takes the rectangle of mask texels changed since the last take,
 * rect = {x0, y0, x1, y1} (x1, y1 exclusive); false when nothing changed. */
bool pelt__fur_gpu_take_mask_dirty(pelt_fur *fur, unsigned rect[4]);

#endif
