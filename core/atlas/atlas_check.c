/* Validation of a uv set as a mask atlas: flipped triangles and texels claimed twice (Lengyel §2.1, Silva §3.1). */
#include "core/atlas/atlas_internal.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/raster.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SUB PELT__RASTER_SUB

size_t pelt__raster_overlaps(const float *uvs, const uint32_t *indices, size_t triangle_count,
                             unsigned res, uint8_t *claims, size_t *covered)
{
    size_t overlaps = 0, cover = 0;
    memset(claims, 0, (size_t)res * res);
    for (size_t t = 0; t < triangle_count; t++) {
        int64_t x[3], y[3];
        for (int k = 0; k < 3; k++) {
            x[k] = pelt__raster_fixed(uvs[2 * indices[3 * t + k]], res);
            y[k] = pelt__raster_fixed(uvs[2 * indices[3 * t + k] + 1], res);
        }
        int64_t area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
        if (area == 0) continue;
        if (area < 0) { /* rasterize flipped triangles too: their overlap is real */
            int64_t tx = x[1], ty = y[1];
            x[1] = x[2], y[1] = y[2];
            x[2] = tx, y[2] = ty;
        }
        int64_t minx = x[0], maxx = x[0], miny = y[0], maxy = y[0];
        for (int k = 1; k < 3; k++) {
            if (x[k] < minx) minx = x[k];
            if (x[k] > maxx) maxx = x[k];
            if (y[k] < miny) miny = y[k];
            if (y[k] > maxy) maxy = y[k];
        }
        /* Texel px has its centre at px*SUB + SUB/2. */
        int64_t px0 = (minx - SUB / 2 + SUB - 1) / SUB, px1 = (maxx - SUB / 2) / SUB;
        int64_t py0 = (miny - SUB / 2 + SUB - 1) / SUB, py1 = (maxy - SUB / 2) / SUB;
        if (minx - SUB / 2 < 0) px0 = 0;
        if (miny - SUB / 2 < 0) py0 = 0;
        if (px1 > (int64_t)res - 1) px1 = (int64_t)res - 1;
        if (py1 > (int64_t)res - 1) py1 = (int64_t)res - 1;
        int tl[3];
        for (int k = 0; k < 3; k++) {
            int j = (k + 1) % 3;
            tl[k] = pelt__raster_top_left(x[j] - x[k], y[j] - y[k]);
        }
        for (int64_t py = py0; py <= py1; py++) {
            int64_t sy = py * SUB + SUB / 2;
            for (int64_t px = px0; px <= px1; px++) {
                int64_t sx = px * SUB + SUB / 2;
                int inside = 1;
                for (int k = 0; k < 3 && inside; k++) {
                    int j = (k + 1) % 3;
                    int64_t e = (x[j] - x[k]) * (sy - y[k]) - (y[j] - y[k]) * (sx - x[k]);
                    inside = e > 0 || (e == 0 && tl[k]);
                }
                if (!inside) continue;
                uint8_t *c = claims + (size_t)py * res + (size_t)px;
                if (*c == 0) cover++;
                if (*c == 1) overlaps++;
                if (*c < 255) (*c)++;
            }
        }
    }
    if (covered) *covered = cover;
    return overlaps;
}

pelt_status pelt_atlas_check_uvs(const pelt_mesh *mesh, unsigned resolution,
                                 pelt_atlas_check *result, pelt_error *err)
{
    if (!mesh || !result)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "pelt_atlas_check_uvs: mesh and result are required");
    if (resolution == 0 || resolution > 16384)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "pelt_atlas_check_uvs: resolution %u outside 1..16384", resolution);
    memset(result, 0, sizeof *result);
    const pelt_mesh_data m = pelt_mesh_get_data(mesh);
    result->triangle_count = m.triangle_count;
    size_t pos = 0, neg = 0;
    const float *uv = m.uvs;
    for (size_t t = 0; t < m.triangle_count; t++) {
        const uint32_t *tri = m.indices + 3 * t;
        double u0 = uv[2 * tri[0]], v0 = uv[2 * tri[0] + 1];
        double a = (uv[2 * tri[1]] - u0) * (uv[2 * tri[2] + 1] - v0) -
                   (uv[2 * tri[2]] - u0) * (uv[2 * tri[1] + 1] - v0);
        if (a > 0) pos++;
        else if (a < 0) neg++;
        else result->degenerate++;
        int out = 0;
        for (int k = 0; k < 3; k++)
            for (int c = 0; c < 2; c++) {
                float x = uv[2 * tri[k] + c];
                if (!(x >= 0.0f && x <= 1.0f)) out = 1;
            }
        result->outside += (size_t)out;
    }
    result->orientation = neg > pos ? -1 : 1;
    result->flipped = neg > pos ? pos : neg;
    uint8_t *claims = pelt__calloc((size_t)resolution * resolution, 1);
    if (!claims)
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "pelt_atlas_check_uvs: %u^2 texels", resolution);
    result->overlap_texels = pelt__raster_overlaps(uv, m.indices, m.triangle_count,
                                                   resolution, claims, &result->covered_texels);
    free(claims);
    return PELT_OK;
}
