/* Each texel centre a mesh triangle covers in uv, with the surface point
 * there: the exact fixed-point rasterization of core/base/raster.h (the
 * atlas check's top-left rule, so neighbours never both claim a texel),
 * shared by the surface droplets and the clump cells. */
#ifndef PELT_TEXEL_RASTER_H
#define PELT_TEXEL_RASTER_H

#include "core/base/raster.h"
#include "core/base/vec.h"
#include "pelt/mesh.h"

#include <stddef.h>
#include <stdint.h>

/* Calls visit(user, px, py, X) for each texel (px, py) of a width x height
 * grid whose centre triangle t covers, X its point on the surface (the
 * triangle's positions weighted as its uvs place the centre). Nothing for
 * a triangle of zero uv area. Inline, so the visitor inlines too. */
static inline void pelt__raster_surface_points(const pelt_mesh_data *mesh, size_t t, unsigned width, unsigned height,
                                               void (*visit)(void *user, size_t px, size_t py, pelt_vec3 X),
                                               void *user)
{
    const int64_t SUB = PELT__RASTER_SUB;
    uint32_t vi[3];
    int64_t x[3], y[3];
    for (int k = 0; k < 3; k++) {
        vi[k] = mesh->indices[3 * t + k];
        x[k] = pelt__raster_fixed(mesh->uvs[(size_t)vi[k] * 2], width);
        y[k] = pelt__raster_fixed(mesh->uvs[(size_t)vi[k] * 2 + 1], height);
    }
    int64_t area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    if (area == 0) return;
    if (area < 0) { /* counter-clockwise order for the edge tests */
        int64_t tx = x[1], ty = y[1];
        uint32_t tv = vi[1];
        x[1] = x[2], y[1] = y[2], vi[1] = vi[2];
        x[2] = tx, y[2] = ty, vi[2] = tv;
        area = -area;
    }
    int64_t minx = x[0], maxx = x[0], miny = y[0], maxy = y[0];
    for (int k = 1; k < 3; k++) {
        minx = x[k] < minx ? x[k] : minx, maxx = x[k] > maxx ? x[k] : maxx;
        miny = y[k] < miny ? y[k] : miny, maxy = y[k] > maxy ? y[k] : maxy;
    }
    /* Texel (px, py) has its centre at (px*SUB + SUB/2, py*SUB + SUB/2). */
    int64_t px0 = minx - SUB / 2 < 0 ? 0 : (minx - SUB / 2 + SUB - 1) / SUB;
    int64_t py0 = miny - SUB / 2 < 0 ? 0 : (miny - SUB / 2 + SUB - 1) / SUB;
    int64_t px1 = maxx - SUB / 2 < 0 ? -1 : (maxx - SUB / 2) / SUB;
    int64_t py1 = maxy - SUB / 2 < 0 ? -1 : (maxy - SUB / 2) / SUB;
    if (px1 > (int64_t)width - 1) px1 = (int64_t)width - 1;
    if (py1 > (int64_t)height - 1) py1 = (int64_t)height - 1;
    bool tl[3];
    for (int k = 0; k < 3; k++) tl[k] = pelt__raster_top_left(x[(k + 1) % 3] - x[k], y[(k + 1) % 3] - y[k]);
    pelt_vec3 q[3];
    for (int k = 0; k < 3; k++) q[k] = v3_load(mesh->positions + (size_t)vi[k] * 3);
    double inv_area = 1.0 / (double)area;
    for (int64_t py = py0; py <= py1; py++) {
        int64_t sy = py * SUB + SUB / 2;
        for (int64_t px = px0; px <= px1; px++) {
            int64_t sx = px * SUB + SUB / 2;
            int64_t e[3];
            bool inside = true;
            for (int k = 0; k < 3 && inside; k++) {
                int j = (k + 1) % 3;
                e[k] = (x[j] - x[k]) * (sy - y[k]) - (y[j] - y[k]) * (sx - x[k]);
                inside = e[k] > 0 || (e[k] == 0 && tl[k]);
            }
            if (!inside) continue;
            /* Edge k is opposite vertex (k + 2) % 3: its weight. */
            float w0 = (float)((double)e[1] * inv_area), w1 = (float)((double)e[2] * inv_area);
            pelt_vec3 X = v3_add(v3_scale(q[0], w0), v3_add(v3_scale(q[1], w1), v3_scale(q[2], 1.0f - w0 - w1)));
            visit(user, (size_t)px, (size_t)py, X);
        }
    }
}

#endif
