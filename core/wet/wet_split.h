/* Wet and dry triangles drawn apart: which triangles' footprint in the
 * wetness mask holds water, and their indices partitioned, dry first. A
 * dry triangle's shells read rho = 0 everywhere, so the dry shell shader
 * draws them as the wet one would, without its mask lookups (docs/lod.md).
 * The flags follow the mask's changed rectangle; nothing is allocated
 * after pelt__wet_split_init. No GL here. */
#ifndef PELT_CORE_WET_WET_SPLIT_H
#define PELT_CORE_WET_WET_SPLIT_H

#include "pelt/base.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct pelt__wet_split {
    pelt_allocator alloc;
    size_t triangle_count;
    uint32_t *source;        /* the triangles split, 3 indices each (a copy) */
    uint16_t *box;           /* per triangle: texels x0, y0, x1, y1 (inclusive) it can read */
    uint8_t *wet;            /* per triangle: 1 when its box holds water */
    uint32_t *indices;       /* the triangles again, the dry ones first */
    size_t dry_count;        /* triangles in indices before the wet ones */
    uint8_t *vertex_wet;     /* per vertex: 1 when a triangle at it is wet, so
                                the fins know theirs (a fin's edge lies in the
                                box of every triangle it borders) */
    size_t vertex_count;     /* the highest index in the triangles, plus 1 */
    unsigned mask_width, mask_height;
} pelt__wet_split;

/* Boxes for a mask of width x height texels (at most 65,536 a side) from
 * the triangles' vertex uvs (2 floats a vertex, the mask's uv); every
 * triangle dry. False when out of memory (*s then frees cleanly). */
bool pelt__wet_split_init(pelt__wet_split *s, const uint32_t *indices, size_t triangle_count,
                          const float *uvs, unsigned width, unsigned height, const pelt_allocator *alloc);
void pelt__wet_split_free(pelt__wet_split *s);

/* Looks again at the triangles whose box meets rect (texels {x0, y0, x1,
 * y1}, x1 and y1 exclusive) in the mask's texels (4 floats each, rho in
 * the fourth) and, when a flag changed, partitions the indices anew and
 * marks the vertices again. True when the partition changed. */
bool pelt__wet_split_update(pelt__wet_split *s, const float *texels, const unsigned rect[4]);

#endif
