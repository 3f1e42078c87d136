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
