/* Procedural meshes with analytic normals and uvs in [0,1]^2. The torus is
 * the default scene (Lengyel et al. 2001 §2 and the Table 1 set-up of
 * Silva Table 1: 78 x 60 segments = 9,360 triangles). */
#include "core/mesh/mesh_internal.h"

#include "core/base/error.h"
#include "core/base/vec.h"

#include <math.h>

#define PELT__TWO_PI 6.28318530717958647692

/* Upper bound on segments per direction: keeps vertex counts far from the
 * 32-bit index limit and allocations sane. */
#define PELT__MAX_SEGMENTS 16384u

static pelt_status check_size(const char *fn, const char *name, float value, pelt_error *err)
{
    if (!(isfinite(value) && value > 0.0f))
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s: %s %g must be finite and > 0", fn,
                          name, (double)value);
    return PELT_OK;
}

static pelt_status check_segments(const char *fn, const char *name, unsigned value, unsigned min,
                                  pelt_error *err)
{
    if (value < min || value > PELT__MAX_SEGMENTS)
        return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s: %s %u is outside [%u, %u]", fn, name,
                          value, min, PELT__MAX_SEGMENTS);
    return PELT_OK;
}

/* cos and sin of 2*pi*i/n with i taken modulo n, so the seam column (i = n)
 * repeats column 0 bit for bit and the duplicated vertices weld exactly. */
static void angle(unsigned i, unsigned n, double scale, float *c, float *s)
{
    double a = scale * (double)(i % n) / (double)n;
    *c = (float)cos(a);
    *s = (float)sin(a);
}

/* Two triangles per cell of a grid of (ni + 1) x (nj + 1) vertices stored
 * i-major: (a, b, c) steps +j then +i, so the triangles are counter-clockwise
 * seen from where d(P)/dj x d(P)/di points. */
static void grid_triangles(uint32_t *idx, unsigned ni, unsigned nj)
{
    const size_t row = (size_t)nj + 1;
    for (unsigned i = 0; i < ni; i++) {
        for (unsigned j = 0; j < nj; j++) {
            uint32_t a = (uint32_t)(i * row + j), b = a + 1;
            uint32_t c = (uint32_t)((i + 1) * row + j), d = c + 1;
            *idx++ = a, *idx++ = b, *idx++ = c;
            *idx++ = b, *idx++ = d, *idx++ = c;
        }
    }
}

pelt_status pelt_mesh_torus(float major_radius, float minor_radius, unsigned major_segments,
                            unsigned minor_segments, pelt_mesh **out, pelt_error *err)
{
    const char *fn = "pelt_mesh_torus";
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s: out is NULL", fn);
    *out = NULL;
    pelt_status st;
    if ((st = check_size(fn, "major_radius", major_radius, err)) ||
        (st = check_size(fn, "minor_radius", minor_radius, err)) ||
        (st = check_segments(fn, "major_segments", major_segments, 3, err)) ||
        (st = check_segments(fn, "minor_segments", minor_segments, 3, err)))
        return st;
    const unsigned M = major_segments, m = minor_segments;
    const size_t row = (size_t)m + 1;
    pelt_mesh *mesh = pelt__mesh_alloc(((size_t)M + 1) * row, 2 * (size_t)M * m);
    if (!mesh) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", fn);

    /* Vertex (i, j): i around the major circle (u), j around the tube (v). */
    for (unsigned i = 0; i <= M; i++) {
        float cp, sp;
        angle(i, M, PELT__TWO_PI, &cp, &sp);
        for (unsigned j = 0; j <= m; j++) {
            float ct, stt;
            angle(j, m, PELT__TWO_PI, &ct, &stt);
            size_t v = i * row + j;
            pelt_vec3 n = v3(ct * cp, stt, ct * sp);
            pelt_vec3 c = v3(major_radius * cp, 0.0f, major_radius * sp);
            v3_store(mesh->positions + 3 * v, v3_mad(c, n, minor_radius));
            v3_store(mesh->normals + 3 * v, n);
            mesh->uvs[2 * v] = (float)i / (float)M;
            mesh->uvs[2 * v + 1] = (float)j / (float)m;
        }
    }
    /* d(P)/dv x d(P)/du points along the outward normal. */
    grid_triangles(mesh->indices, M, m);
    pelt__mesh_finish(mesh, false);
    *out = mesh;
    return PELT_OK;
}

pelt_status pelt_mesh_sphere(float radius, unsigned slices, unsigned stacks, pelt_mesh **out,
                             pelt_error *err)
{
    const char *fn = "pelt_mesh_sphere";
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s: out is NULL", fn);
    *out = NULL;
    pelt_status st;
    if ((st = check_size(fn, "radius", radius, err)) ||
        (st = check_segments(fn, "slices", slices, 3, err)) ||
        (st = check_segments(fn, "stacks", stacks, 2, err)))
        return st;
    const size_t row = (size_t)stacks + 1;
    /* Pole rows are fans: one triangle per slice instead of a quad. */
    pelt_mesh *mesh = pelt__mesh_alloc(((size_t)slices + 1) * row, 2 * (size_t)slices * (stacks - 1));
    if (!mesh) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", fn);

    /* Vertex (i, j): i around the +Y axis (u), j from the north pole down. */
    for (unsigned i = 0; i <= slices; i++) {
        float cp, sp;
        angle(i, slices, PELT__TWO_PI, &cp, &sp);
        for (unsigned j = 0; j <= stacks; j++) {
            float ct, stt;
            angle(j, 2 * stacks, PELT__TWO_PI, &ct, &stt); /* theta = pi j / stacks */
            if (j == 0 || j == stacks) stt = 0.0f;        /* poles exactly on the axis */
            if (j == stacks) ct = -1.0f;
            size_t v = i * row + j;
            pelt_vec3 n = v3(stt * cp, ct, stt * sp);
            v3_store(mesh->positions + 3 * v, v3_scale(n, radius));
            v3_store(mesh->normals + 3 * v, n);
            mesh->uvs[2 * v] = (float)i / (float)slices;
            mesh->uvs[2 * v + 1] = 1.0f - (float)j / (float)stacks;
        }
    }
    /* d(P)/du x d(P)/d(down) points outwards, so (a, b, c) is CCW from outside. */
    uint32_t *idx = mesh->indices;
    for (unsigned i = 0; i < slices; i++) {
        for (unsigned j = 0; j < stacks; j++) {
            uint32_t a = (uint32_t)(i * row + j), c = a + 1;     /* c: one row down */
            uint32_t b = (uint32_t)((i + 1) * row + j), d = b + 1; /* b: one slice on */
            if (j != 0) *idx++ = a, *idx++ = b, *idx++ = c;
            if (j != stacks - 1) *idx++ = b, *idx++ = d, *idx++ = c;
        }
    }
    pelt__mesh_finish(mesh, false);
    *out = mesh;
    return PELT_OK;
}

pelt_status pelt_mesh_square(float size, unsigned subdivisions, pelt_mesh **out, pelt_error *err)
{
    const char *fn = "pelt_mesh_square";
    if (!out) return pelt__fail(err, PELT_ERR_INVALID_ARGUMENT, "%s: out is NULL", fn);
    *out = NULL;
    pelt_status st;
    if ((st = check_size(fn, "size", size, err)) ||
        (st = check_segments(fn, "subdivisions", subdivisions, 1, err)))
        return st;
    const unsigned n = subdivisions;
    const size_t row = (size_t)n + 1;
    pelt_mesh *mesh = pelt__mesh_alloc(row * row, 2 * (size_t)n * n);
    if (!mesh) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", fn);

    /* Vertex (i, j): x = -size/2 + size i/n (u = i/n), z likewise with j,
     * v = 1 - j/n so that (t, n x t) is right-handed (w = +1). */
    for (unsigned i = 0; i <= n; i++) {
        for (unsigned j = 0; j <= n; j++) {
            size_t v = i * row + j;
            float fu = (float)i / (float)n, fv = (float)j / (float)n;
            v3_store(mesh->positions + 3 * v, v3(size * (fu - 0.5f), 0.0f, size * (fv - 0.5f)));
            v3_store(mesh->normals + 3 * v, v3(0.0f, 1.0f, 0.0f));
            mesh->uvs[2 * v] = fu;
            mesh->uvs[2 * v + 1] = 1.0f - fv;
        }
    }
    /* (+z) x (+x) = +y: j (z) is the grid's inner direction. */
    grid_triangles(mesh->indices, n, n);
    pelt__mesh_finish(mesh, false);
    *out = mesh;
    return PELT_OK;
}
