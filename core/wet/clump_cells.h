/* Natural wet clumps (docs/wetness.md, Natural clumps): clump cells fixed on
 * the surface. Where water lands, Silva et al.'s Alg. 1 still decides how
 * wet each texel is; which clump a wet texel joins is then its cell's, not
 * the droplet's, so a big droplet makes many small tufts, a small one part
 * of one, and overlapping droplets keep the same clumps. No GL here. */
#ifndef PELT_CORE_WET_CLUMP_CELLS_H
#define PELT_CORE_WET_CLUMP_CELLS_H

#include "core/wet/mask.h"

/* Cells over the mask of one mesh: seeds spread evenly over the surface by
 * area, one per clump_size^2 (world units), relaxed by three Lloyd steps;
 * each mask texel a triangle covers (the atlas check's rule) belongs to the
 * seed nearest its surface point, in 3D, so a cell crosses patch borders
 * and uv seams whole. */
typedef struct pelt__clump_cells pelt__clump_cells;

/* Builds the cells of `mesh` (positions, uvs, indices) over a width x
 * height mask. seed picks the seeds. Allocates O(texels + seeds) from `a`;
 * free with pelt__clump_cells_destroy. clump_size must be positive and
 * finite (PELT_ERR_INVALID_ARGUMENT otherwise); the seeds are at most one
 * per covered texel. The mesh is not copied: it must outlive the cells. */
pelt_status pelt__clump_cells_create(const pelt_mesh *mesh, unsigned width, unsigned height,
                                     float clump_size, uint32_t seed, const pelt_allocator *a,
                                     pelt__clump_cells **out, pelt_error *err);
void pelt__clump_cells_destroy(pelt__clump_cells *cells);

/* The cell of mask texel (x, y), or UINT32_MAX where no triangle covers it. */
uint32_t pelt__clump_cells_of_texel(const pelt__clump_cells *cells, unsigned x, unsigned y);

/* Makes each cell with a texel in rect = {x0, y0, x1, y1} (x1, y1
 * exclusive) one clump again: its wet texels (rho > 0) get the centroid of
 * their surface points as the clump centre, expressed in each texel's own
 * triangle's uv (the point projected on its plane), and as radius the
 * largest distance of them from it, scaled to that triangle's uv, plus
 * half a texel diagonal. Wetness is untouched. The mask's dirty rectangle
 * grows by the cells' texels. Work is proportional to the texels of the
 * rectangle and of its cells. No allocation. */
void pelt__clump_cells_apply(pelt__clump_cells *cells, pelt__wetness *m, const unsigned rect[4]);

#endif
