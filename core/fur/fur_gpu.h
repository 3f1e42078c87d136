/* What a renderer uploads from a pelt_fur, read through functions so that
 * gl/ never opens the handle (it must not include fur_internal.h). GL-free:
 * plain pointers, sizes and version counters. Pointers are owned by the fur
 * and stay valid until it is destroyed or the data is replaced (a version
 * change says so). */
#ifndef PELT_CORE_FUR_GPU_H
#define PELT_CORE_FUR_GPU_H

#include "pelt/fur.h"

#include "core/fur/fins.h"
#include "core/fur/lod.h"
#include "core/fur/shadow_map.h" /* the light's maps (gl/shadow_pass.c, renderer.c) */
#include "core/fur/strand_ref.h" /* the strand reference (gl/strands_pass.c) */

/* The posed mesh (pelt_fur_set_pose), 10 floats a vertex: position,
 * normal, tangent; NULL before the first pose. *version changes with it. */
const float *pelt__fur_gpu_pose(const pelt_fur *fur, unsigned *version);

/* A skinned mesh's skin, for skinning in the vertex stage (measured
 * against the CPU pose by pelt bench --animation): per vertex 4 bones and
 * weights and the bind-space position, normal, tangent (10 floats); the
 * bones' matrices of the last pelt_mesh_pose (16 floats a bone). False
 * for a mesh without a skeleton. */
typedef struct pelt__gpu_skin {
    const uint16_t *bones;
    const float *weights;
    const float *bind;
    const float *matrices;
    size_t bone_count;
} pelt__gpu_skin;
bool pelt__fur_gpu_skin(const pelt_fur *fur, pelt__gpu_skin *out);

/* The mesh the fur was made for. */
const pelt_mesh *pelt__fur_gpu_mesh(const pelt_fur *fur);

/* The fur texture volume (Lengyel et al. 2001 §2.2, core/fur/furtex.h):
 * RGBA8, premultiplied, size x size texels by slices (layers + 1, slice 0
 * the opaque skin), slice after slice. */
const uint8_t *pelt__fur_gpu_volume(const pelt_fur *fur, unsigned *size, unsigned *slices);

/* The coarser shell levels' slices (core/fur/lod.h), which follow the
 * volume's in the GPU array; *slices is 0 (and NULL returned) with level
 * of detail off. */
const uint8_t *pelt__fur_gpu_volume_lod(const pelt_fur *fur, unsigned *slices);

/* Ringlets (docs/method.md): how many amplitude levels of the curl the
 * texture holds, 1 without ringlets. With more, the volume and the lod
 * slices above hold that many sets one after the other (level 0 the full
 * curl, the last none), and the GPU array takes them level by level: level
 * k's slice s (volume or lod) at k * (slices + lod slices) + s. */
unsigned pelt__fur_gpu_ringlet_levels(const pelt_fur *fur);

/* Silva's curl radius K_alpha for the shells' vertex stage: 0 when the
 * texture holds the curl as ringlets. */
float pelt__fur_gpu_vertex_curl_radius(const pelt_fur *fur);

/* Fur-texture coordinates in tiles, 2 floats per mesh vertex; and the fur
 * tiles per uv unit along u and v (scales a uv-space clump displacement
 * into fur coordinates). */
const float *pelt__fur_gpu_uvs(const pelt_fur *fur);
void pelt__fur_gpu_per_uv(const pelt_fur *fur, float out[2]);

/* Strand tip offsets p - p_root, mesh-local, 3 floats per vertex; *version
 * changes whenever they change. */
const float *pelt__fur_gpu_tips(const pelt_fur *fur, unsigned *version);

/* The groom (core/fur/groom.h): one pelt__groom_vertex per mesh vertex,
 * *stride bytes apart. */
const void *pelt__fur_gpu_groom(const pelt_fur *fur, size_t *stride);

/* Takes the range of vertices [range[0], range[1]) whose groom changed
 * since the last take; false when nothing changed. */
bool pelt__fur_gpu_take_groom_dirty(pelt_fur *fur, size_t range[2]);

/* Fins (core/fur/fins.h): one per mesh edge, and their texture (RGBA8,
 * premultiplied, width along the fin, row 0 at the root). */
const pelt__fin_edge *pelt__fur_gpu_fins(const pelt_fur *fur, size_t *count);
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
 * rows chosen, see row_error). No allocation. */
size_t pelt__fur_gpu_fin_frame(const pelt_fur *fur, const pelt__fin_frame_desc *d, uint32_t *fins,
                               float *vertices, unsigned *rows);

/* The shell geometry levels (core/fur/lod.h), level 0 the full mesh in
 * vertex-cache order, each level with its fins. */
const pelt__lod_chain *pelt__fur_gpu_lod(const pelt_fur *fur);
const uint8_t *pelt__fur_gpu_fin_texture(const pelt_fur *fur, unsigned *width, unsigned *height);

/* Lengyel et al.'s §2.4 hair lighting table for the fur's material
 * (core/fur/shading.h: pelt__lengyel_table): 32x32 texels of (diffuse,
 * specular). */
#define PELT__FUR_GPU_LIGHT_TABLE 32
void pelt__fur_gpu_light_table(const pelt_fur *fur, float *out);

/* The colour texture, RGBA8 width x height, or NULL when none was set;
 * *version changes whenever it is set. */
const uint8_t *pelt__fur_gpu_color(const pelt_fur *fur, unsigned *width, unsigned *height,
                                   unsigned *version);

/* The wetness mask (Silva et al. §3.1, core/wet/mask.h): width x height
 * texels of 4 floats (clump centre, radius, wetness), row 0 at v = 0. */
const float *pelt__fur_gpu_mask(const pelt_fur *fur, unsigned *width, unsigned *height);

/* False when every texel of the mask is dry: the shells then need no
 * clump lookups (the shell pass's dry variant). */
bool pelt__fur_gpu_any_wet(const pelt_fur *fur);

/* Takes the rectangle of mask texels changed since the last take,
 * rect = {x0, y0, x1, y1} (x1, y1 exclusive); false when nothing changed. */
bool pelt__fur_gpu_take_mask_dirty(pelt_fur *fur, unsigned rect[4]);

#endif
