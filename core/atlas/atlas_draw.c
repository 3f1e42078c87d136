/* Drawing of an atlas for `pelt atlas`: patches, borders and the direction field (Lengyel §2.1, §3). */
#include "core/atlas/atlas_internal.h"

#include "core/base/error.h"
#include "core/base/hooks.h"
#include "core/base/rng.h"
#include "core/base/vec.h"

#include <math.h>
#include <stdlib.h>

static void put_pixel(uint8_t *rgba, unsigned w, unsigned h, long x, long y, const uint8_t c[3])
{
    if (x < 0 || y < 0 || x >= (long)w || y >= (long)h) return;
    uint8_t *p = rgba + 4 * ((size_t)y * w + (size_t)x);
    p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
}

static void draw_line(uint8_t *rgba, unsigned w, unsigned h, double x0, double y0, double x1,
                      double y1, const uint8_t c[3])
{
    double dx = x1 - x0, dy = y1 - y0;
    double steps = ceil(fmax(fabs(dx), fabs(dy)));
    if (steps < 1) steps = 1;
    if (steps > 4.0 * (w + h)) steps = 4.0 * (w + h);
    for (double i = 0; i <= steps; i++)
        put_pixel(rgba, w, h, (long)floor(x0 + dx * i / steps), (long)floor(y0 + dy * i / steps), c);
}


pelt_status pelt_atlas_draw(const pelt_atlas *a, uint8_t *rgba, unsigned width, unsigned height,
                            uint32_t seed, pelt_error *err)
{
    if (!a || !a->mesh || !rgba || width == 0 || height == 0)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT,
                          "pelt_atlas_draw: needs an atlas that still holds its mesh and a %ux%u buffer",
                          width, height);
    const pelt_mesh_data md = pelt_mesh_get_data(a->mesh), *m = &md;
    size_t tc = m->triangle_count;
    for (size_t i = 0; i < (size_t)width * height; i++) {
        rgba[4 * i] = rgba[4 * i + 1] = rgba[4 * i + 2] = 24;
        rgba[4 * i + 3] = 255;
    }
    uint64_t *edges = pelt__calloc(tc, 3 * sizeof(uint64_t));
    uint8_t *cell = pelt__calloc(((size_t)width / 8 + 1) * ((size_t)height / 8 + 1), 1);
    if (!edges || !cell) {
        free(edges);
        free(cell);
        return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "pelt_atlas_draw: out of memory");
    }
    /* Patches filled, one random colour each. */
    for (size_t t = 0; t < tc; t++) {
        pelt__rng r = pelt__rng_seed(seed, a->triangle_patch[t] + 1u);
        uint8_t c[3];
        for (int k = 0; k < 3; k++) c[k] = (uint8_t)(80 + pelt__rng_next(&r) % 176);
        double x[3], y[3];
        for (int k = 0; k < 3; k++) {
            x[k] = m->uvs[2 * m->indices[3 * t + k]] * width;
            y[k] = m->uvs[2 * m->indices[3 * t + k] + 1] * height;
        }
        double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
        if (area == 0) continue;
        long x0 = (long)floor(fmin(x[0], fmin(x[1], x[2]))), x1 = (long)ceil(fmax(x[0], fmax(x[1], x[2])));
        long y0 = (long)floor(fmin(y[0], fmin(y[1], y[2]))), y1 = (long)ceil(fmax(y[0], fmax(y[1], y[2])));
        if (x0 < 0) x0 = 0;
        if (y0 < 0) y0 = 0;
        if (x1 > (long)width) x1 = (long)width;
        if (y1 > (long)height) y1 = (long)height;
        for (long py = y0; py < y1; py++)
            for (long px = x0; px < x1; px++) {
                double sx = px + 0.5, sy = py + 0.5, e[3];
                for (int k = 0; k < 3; k++) {
                    int j = (k + 1) % 3;
                    e[k] = ((x[j] - x[k]) * (sy - y[k]) - (y[j] - y[k]) * (sx - x[k])) / area;
                }
                if (e[0] >= 0 && e[1] >= 0 && e[2] >= 0) put_pixel(rgba, width, height, px, py, c);
            }
        for (int k = 0; k < 3; k++) {
            uint64_t p = m->indices[3 * t + k], q = m->indices[3 * t + (k + 1) % 3];
            edges[3 * t + k] = p < q ? (p << 32 | q) : (q << 32 | p);
        }
    }
    /* Borders darker: an edge of split vertices that only one triangle uses. */
    qsort(edges, 3 * tc, sizeof(uint64_t), pelt__atlas_compare_u64);
    for (size_t i = 0; i < 3 * tc; i++) {
        bool twice = (i + 1 < 3 * tc && edges[i + 1] == edges[i]) || (i > 0 && edges[i - 1] == edges[i]);
        if (twice) continue;
        uint32_t p = (uint32_t)(edges[i] >> 32), q = (uint32_t)edges[i];
        const uint8_t dark[3] = {10, 10, 10};
        draw_line(rgba, width, height, m->uvs[2 * p] * width, m->uvs[2 * p + 1] * height,
                  m->uvs[2 * q] * width, m->uvs[2 * q + 1] * height, dark);
    }
    /* The direction field: a short line per triangle (one per 8x8 cell),
     * mapped into atlas space through the triangle's own map. */
    for (size_t t = 0; t < tc; t++) {
        const uint32_t *tri = m->indices + 3 * t;
        pelt_vec3 p0 = v3_load(m->positions + 3 * tri[0]);
        pelt_vec3 e1 = v3_sub(v3_load(m->positions + 3 * tri[1]), p0);
        pelt_vec3 e2 = v3_sub(v3_load(m->positions + 3 * tri[2]), p0);
        pelt_vec3 fl = v3(0, 0, 0);
        float wsum = 0;
        for (int k = 0; k < 3; k++) {
            fl = v3_mad(fl, v3_load(a->directions + 3 * tri[k]), a->weights[tri[k]]);
            wsum += a->weights[tri[k]] / 3.0f;
        }
        double cx = 0, cy = 0;
        for (int k = 0; k < 3; k++) cx += m->uvs[2 * tri[k]] * width / 3.0, cy += m->uvs[2 * tri[k] + 1] * height / 3.0;
        long gx = (long)cx / 8, gy = (long)cy / 8;
        if (cx < 0 || cy < 0 || gx > (long)width / 8 || gy > (long)height / 8) continue;
        uint8_t *used = cell + (size_t)gy * (width / 8 + 1) + (size_t)gx;
        if (*used) continue;
        /* Solve fl = a e1 + b e2 in the least-squares sense, then map a, b. */
        double g11 = v3_dot(e1, e1), g12 = v3_dot(e1, e2), g22 = v3_dot(e2, e2);
        double r1 = v3_dot(fl, e1), r2 = v3_dot(fl, e2), det = g11 * g22 - g12 * g12;
        if (!(det > 0)) continue;
        double ca = (r1 * g22 - r2 * g12) / det, cb = (r2 * g11 - r1 * g12) / det;
        double du = ca * (m->uvs[2 * tri[1]] - m->uvs[2 * tri[0]]) + cb * (m->uvs[2 * tri[2]] - m->uvs[2 * tri[0]]);
        double dv = ca * (m->uvs[2 * tri[1] + 1] - m->uvs[2 * tri[0] + 1]) + cb * (m->uvs[2 * tri[2] + 1] - m->uvs[2 * tri[0] + 1]);
        double len = sqrt(du * du * width * width + dv * dv * height * height);
        *used = 1;
        const uint8_t white[3] = {255, 255, 255}, root[3] = {0, 0, 0};
        if (len > 0 && wsum > 0.05f) {
            double sc = 6.0 * wsum / len;
            draw_line(rgba, width, height, cx, cy, cx + du * width * sc, cy + dv * height * sc, white);
        }
        put_pixel(rgba, width, height, (long)cx, (long)cy, root);
    }
    free(edges);
    free(cell);
    return PELT_OK;
}

