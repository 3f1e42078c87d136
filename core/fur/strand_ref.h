/* The strand reference (docs/reference.md, The strand reference): every
 * hair of the fur texture's tile (Lengyel et al. 2001 §2.2, furtex.h),
 * tiled over the surface by the fur uvs as the shells tile it, each along
 * the curve the shells' layers follow at its root (Silva's beta + phi +
 * comb of the three vertex strands around it, vertex_strand.h) plus its
 * own shape in the tile (lean, curl, ringlets). GL-free; the strands pass
 * (gl/strands_pass.c) draws the curves as camera-facing ribbons. */
#ifndef PELT_CORE_FUR_STRAND_REF_H
#define PELT_CORE_FUR_STRAND_REF_H

#include "core/fur/furtex.h"
#include "pelt/fur.h"

#include <stddef.h>

/* Straight pieces along a hair: 8, or 8 a turn of its curls, at most 64
 * (pelt__strand_ref_segments). */
#define PELT__STRAND_SEGMENTS_MIN 8
#define PELT__STRAND_SEGMENTS_MAX 64
/* Pieces a hair has at least where the fur is wet, so that it follows
 * its tuft's bend (pelt__strand_ref_segments). */
#define PELT__STRAND_SEGMENTS_WET 32
/* Texels of 4 floats a hair of S segments: for k = 0 .. S its point
 * (mesh-local, w the radius in mesh units) and unit tangent (w the height
 * along the hair, 0 root .. 1 tip); then the surface normal with the
 * hair's shade in w; then the wetness at its root, the hair's length as
 * a share of the fur's (a point's height in the fur is its height along
 * the hair times this: the light's gamma, as the shells' layers have it)
 * and the hair colour's bytes, two a float (r 256 + g, b 256 + a). A wet
 * hair's points follow its tuft (docs/wetness.md, Tufts). */
#define PELT__STRAND_TEXELS(S) (2 * ((S) + 1) + 2)

/* Segments a hair needs so that its curls stay round: 8 a turn of the
 * curls it has (its own in the tile, ringlets, the vertex curve's phi),
 * between PELT__STRAND_SEGMENTS_MIN and _MAX; at least
 * PELT__STRAND_SEGMENTS_WET where any of the fur is wet, so that a hair
 * follows its tuft's bend. A straight dry hair has the minimum. */
unsigned pelt__strand_ref_segments(const pelt_fur *fur);

/* The tile's strands (pelt__furtex_strands of the fur's texture desc):
 * how many, and into `out` up to `cap` of them. */
size_t pelt__strand_ref_tile(const pelt_fur *fur, pelt__furtex_strand *out, size_t cap);

/* How many hairs the surface holds with every strand kept (grooming's
 * density at 1): room enough for pelt__strand_ref_build. */
size_t pelt__strand_ref_count(const pelt_fur *fur, const pelt__furtex_strand *tile, size_t tile_count);

/* Writes the hairs grooming keeps, PELT__STRAND_TEXELS(segments) * 4
 * floats each, up to `cap` hairs, and returns how many. No allocation.
 * `segments` is in [PELT__STRAND_SEGMENTS_MIN, PELT__STRAND_SEGMENTS_MAX]. */
size_t pelt__strand_ref_build(const pelt_fur *fur, const pelt__furtex_strand *tile, size_t tile_count,
                              unsigned segments, float *out, size_t cap);

#endif
