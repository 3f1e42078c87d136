/* A coarser copy of a mesh (pelt_mesh_simplify): meshoptimizer picks the
 * triangles, pelt_mesh_create drops the vertices they no longer use. */
#include "pelt/mesh.h"

#include "core/base/error.h"

#include <meshoptimizer.h>
#include <stdlib.h>

pelt_status pelt_mesh_simplify(const pelt_mesh *mesh, size_t target_triangles, pelt_mesh **out,
                               pelt_error *err)
{
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_mesh_simplify: out is NULL");
    *out = NULL;
    if (!mesh || target_triangles == 0)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_mesh_simplify: needs a mesh and a target above 0");
    pelt_mesh_data d = pelt_mesh_get_data(mesh);
    size_t n = 3 * d.triangle_count;
    uint32_t *indices = malloc((n ? n : 3) * sizeof *indices);
    if (!indices) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "out of memory simplifying %zu triangles", d.triangle_count);
    size_t target = target_triangles < d.triangle_count ? target_triangles : d.triangle_count;
    d.triangle_count = meshopt_simplify(indices, d.indices, n, d.positions, d.vertex_count, 3 * sizeof(float), 3 * target,
                                        1.0f, meshopt_SimplifyLockBorder, NULL) / 3;
    d.indices = indices;
    pelt_status st = pelt_mesh_create(&d, out, err);
    free(indices);
    return st;
}
