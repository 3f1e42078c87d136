/* Seam-free droplets (Silva et al. §3.1 Alg. 1 over an atlas): a drop on a
 * patch border wets every patch within its world radius as one clump. The
 * checks rasterize the atlas themselves (float barycentrics, brute force)
 * and compare against 3D distances, not against outputs of the code. */
#include "support/check.h"
#include "core/mesh/mesh_internal.h"
#include "core/wet/surface_droplet.h"
#include "core/base/vec.h"
#include "pelt/atlas.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct fixture {
    pelt_atlas *atlas;
    const pelt_mesh *mesh;
    const uint32_t *patch; /* per triangle */
    pelt__wetness *mask;
    pelt__surface_index *index;
    int32_t *owner; /* per texel: triangle whose uv footprint holds its centre, or -1 */
} fixture;

static double now_s(void)
{
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static pelt_vec3 pos(const pelt_mesh *m, size_t t, int k)
{
    return v3_load(m->positions + (size_t)m->indices[3 * t + k] * 3);
}

static const float *uv(const pelt_mesh *m, size_t t, int k)
{
    return m->uvs + (size_t)m->indices[3 * t + k] * 2;
}

/* Barycentric weights of point q in triangle t's uv footprint (may be
 * outside, then some weight is negative). False when degenerate. */
static bool uv_bary(const pelt_mesh *m, size_t t, const double q[2], double w[3])
{
    const float *a = uv(m, t, 0), *b = uv(m, t, 1), *c = uv(m, t, 2);
    double den = ((double)b[0] - a[0]) * ((double)c[1] - a[1]) - ((double)c[0] - a[0]) * ((double)b[1] - a[1]);
    if (den == 0.0) return false;
    w[1] = ((q[0] - a[0]) * ((double)c[1] - a[1]) - ((double)c[0] - a[0]) * (q[1] - a[1])) / den;
    w[2] = (((double)b[0] - a[0]) * (q[1] - a[1]) - (q[0] - a[0]) * ((double)b[1] - a[1])) / den;
    w[0] = 1.0 - w[1] - w[2];
    return true;
}

static pelt_vec3 blend(const pelt_mesh *m, size_t t, const double w[3])
{
    pelt_vec3 r = v3_scale(pos(m, t, 0), (float)w[0]);
    r = v3_add(r, v3_scale(pos(m, t, 1), (float)w[1]));
    return v3_add(r, v3_scale(pos(m, t, 2), (float)w[2]));
}

static void texel_centre(const pelt__wetness *mk, size_t i, double q[2])
{
    q[0] = ((double)(i % mk->width) + 0.5) / mk->width;
    q[1] = ((double)(i / mk->width) + 0.5) / mk->height;
}

static bool fixture_make(fixture *f, pelt_mesh *in)
{
    memset(f, 0, sizeof *f);
    pelt_atlas_desc desc = {0};
    desc.mode = PELT_ATLAS_PATCHES;
    pelt_error err = {0};
    bool ok = pelt_atlas_create(in, &desc, &f->atlas, &err) == PELT_OK;
    pelt_mesh_destroy(in);
    CHECK(ok);
    if (!ok) return false;
    f->mesh = pelt_atlas_mesh(f->atlas);
    f->patch = pelt_atlas_triangle_patches(f->atlas);
    unsigned size = pelt_atlas_get_stats(f->atlas)->mask_size;
    CHECK(pelt__wetness_create(size, size, NULL, &f->mask, NULL) == PELT_OK);
    CHECK(pelt__surface_index_create(f->mesh, NULL, &f->index, NULL) == PELT_OK);
    return f->mask && f->index;
}

/* Brute-force owner of every texel centre (tolerant test: a centre on a
 * shared edge may go to either triangle; their 3D points agree). */
static void fixture_owners(fixture *f)
{
    const pelt_mesh *m = f->mesh;
    size_t n = (size_t)f->mask->width * f->mask->height;
    f->owner = malloc(n * sizeof *f->owner);
    for (size_t i = 0; i < n; i++) f->owner[i] = -1;
    for (size_t t = 0; t < m->triangle_count; t++) {
        float lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
        for (int k = 0; k < 3; k++)
            for (int a = 0; a < 2; a++) {
                lo[a] = fminf(lo[a], uv(m, t, k)[a]);
                hi[a] = fmaxf(hi[a], uv(m, t, k)[a]);
            }
        unsigned W = f->mask->width, H = f->mask->height;
        int x0 = (int)floorf(lo[0] * W) - 1, x1 = (int)ceilf(hi[0] * W) + 1;
        int y0 = (int)floorf(lo[1] * H) - 1, y1 = (int)ceilf(hi[1] * H) + 1;
        for (int y = y0 < 0 ? 0 : y0; y <= y1 && y < (int)H; y++)
            for (int x = x0 < 0 ? 0 : x0; x <= x1 && x < (int)W; x++) {
                size_t i = (size_t)y * W + (size_t)x;
                double q[2], w[3];
                texel_centre(f->mask, i, q);
                if (uv_bary(m, t, q, w) && w[0] >= -1e-7 && w[1] >= -1e-7 && w[2] >= -1e-7)
                    f->owner[i] = (int32_t)t;
            }
    }
}

static void fixture_free(fixture *f)
{
    free(f->owner);
    pelt__surface_index_destroy(f->index);
    pelt__wetness_destroy(f->mask);
    pelt_atlas_destroy(f->atlas);
}

static fixture sphere_fixture(void)
{
    pelt_mesh *s = NULL;
    CHECK(pelt_mesh_sphere(1.0f, 48, 24, &s, NULL) == PELT_OK);
    fixture f;
    fixture_make(&f, s);
    return f;
}

/* A corner of a triangle whose position is shared with a triangle of
 * another patch, away from the poles. */
static bool find_border_corner(const fixture *f, size_t *tri, int *corner)
{
    const pelt_mesh *m = f->mesh;
    const uint32_t *welded = pelt_atlas_welded_vertices(f->atlas);
    size_t nv = m->vertex_count;
    uint32_t *first_patch = malloc(nv * sizeof *first_patch);
    for (size_t v = 0; v < nv; v++) first_patch[v] = UINT32_MAX;
    bool found = false;
    for (size_t t = 0; t < m->triangle_count && !found; t++)
        for (int k = 0; k < 3 && !found; k++) {
            uint32_t v = m->indices[3 * t + k], w = welded[v];
            if (w >= nv) continue;
            if (fabsf(m->positions[(size_t)v * 3 + 1]) > 0.5f) continue;
            if (first_patch[w] == UINT32_MAX) {
                first_patch[w] = f->patch[t];
            } else if (first_patch[w] != f->patch[t]) {
                *tri = t;
                *corner = k;
                found = true;
            }
        }
    free(first_patch);
    return found;
}

/* Edge length of a triangle in world units: the radius scale. */
static float edge_length(const pelt_mesh *m, size_t t)
{
    return v3_len(v3_sub(pos(m, t, 1), pos(m, t, 0)));
}

typedef struct border_drop {
    size_t tri;
    pelt_vec3 p;
    float radius;
} border_drop;

static border_drop drop_on_border(fixture *f, float wetness)
{
    border_drop d = {0};
    int k = 0;
    CHECK(find_border_corner(f, &d.tri, &k));
    float bary[3] = {0, 0, 0};
    bary[k] = 1.0f;
    d.p = pos(f->mesh, d.tri, k);
    d.radius = 3.0f * edge_length(f->mesh, d.tri);
    CHECK(pelt__droplet_surface(f->mask, f->mesh, f->index, d.tri, bary, d.radius, wetness,
                                NULL) == PELT_OK);
    return d;
}

static void border_drop_wets_two_patches(void)
{
    fixture f = sphere_fixture();
    fixture_owners(&f);
    drop_on_border(&f, 0.8f);
    size_t n = (size_t)f.mask->width * f.mask->height, wet = 0;
    uint32_t patch_a = UINT32_MAX;
    bool two = false;
    for (size_t i = 0; i < n; i++) {
        if (!(f.mask->texels[i * 4 + 3] > 0.0f)) continue;
        wet++;
        CHECK(f.owner[i] >= 0);
        if (f.owner[i] < 0) continue;
        uint32_t p = f.patch[f.owner[i]];
        if (patch_a == UINT32_MAX) patch_a = p;
        else if (p != patch_a) two = true;
    }
    CHECK(wet > 20);
    CHECK(two);
    fixture_free(&f);
}

static void border_drop_is_one_clump_in_3d(void)
{
    fixture f = sphere_fixture();
    fixture_owners(&f);
    border_drop d = drop_on_border(&f, 0.8f);
    size_t n = (size_t)f.mask->width * f.mask->height, checked = 0;
    double worst = 0.0, worst_r = 0.0;
    for (size_t i = 0; i < n; i++) {
        const float *t = f.mask->texels + i * 4;
        if (!(t[3] > 0.0f) || f.owner[i] < 0) continue;
        /* The stored centre, taken back to 3D through this texel's own
         * triangle, lands on the drop point. */
        double c[2] = {t[0], t[1]}, w[3];
        CHECK(uv_bary(f.mesh, (size_t)f.owner[i], c, w));
        pelt_vec3 back = blend(f.mesh, (size_t)f.owner[i], w);
        double e = v3_len(v3_sub(back, d.p));
        if (e > worst) worst = e;
        /* The stored radius, taken back through the same triangle, is the
         * world radius. */
        size_t ot = (size_t)f.owner[i];
        double world = 0.5 * v3_len(v3_cross(v3_sub(pos(f.mesh, ot, 1), pos(f.mesh, ot, 0)),
                                              v3_sub(pos(f.mesh, ot, 2), pos(f.mesh, ot, 0))));
        const float *a = uv(f.mesh, ot, 0), *b = uv(f.mesh, ot, 1), *cc = uv(f.mesh, ot, 2);
        double uva = 0.5 * fabs(((double)b[0] - a[0]) * ((double)cc[1] - a[1]) -
                                ((double)cc[0] - a[0]) * ((double)b[1] - a[1]));
        double rw = t[2] / sqrt(uva / world);
        double er = fabs(rw - d.radius) / d.radius;
        if (er > worst_r) worst_r = er;
        checked++;
    }
    CHECK(checked > 20);
    printf("  centre back in 3D: worst %.4f of radius %.4f; radius worst %.3f relative\n",
           worst, (double)d.radius, worst_r);
    /* A flat patch cannot be exact on a curved surface: a centre a surface
     * distance s away, taken through a tangent plane, misses P by about
     * s^2 / 2 on the unit sphere; allow that plus 10% of the radius for
     * the flattening's stretch. A centre in the wrong patch's coordinates
     * would miss by the distance between patches in the atlas. */
    CHECK(worst <= 0.5 * d.radius * d.radius + 0.1 * d.radius);
    CHECK(worst_r <= 0.25);
    fixture_free(&f);
}

static void wet_texels_lie_within_world_radius(void)
{
    fixture f = sphere_fixture();
    fixture_owners(&f);
    border_drop d = drop_on_border(&f, 0.8f);
    size_t n = (size_t)f.mask->width * f.mask->height;
    size_t bad_wet = 0, bad_dry = 0, stray = 0, inside = 0;
    for (size_t i = 0; i < n; i++) {
        bool wet = f.mask->texels[i * 4 + 3] > 0.0f;
        if (f.owner[i] < 0) {
            stray += wet; /* a texel outside every triangle stays dry */
            continue;
        }
        double q[2], w[3];
        texel_centre(f.mask, i, q);
        uv_bary(f.mesh, (size_t)f.owner[i], q, w);
        double dist = v3_len(v3_sub(blend(f.mesh, (size_t)f.owner[i], w), d.p));
        if (wet && dist > d.radius * 1.001) bad_wet++;
        if (!wet && dist < d.radius * 0.999) bad_dry++;
        inside += dist < d.radius;
    }
    CHECK(stray == 0);
    CHECK(bad_wet == 0);
    CHECK(bad_dry == 0); /* every texel in the ball was reached */
    CHECK(inside > 20);
    fixture_free(&f);
}

static void changes_stay_inside_dirty_and_wet_rects(void)
{
    fixture f = sphere_fixture();
    size_t n = (size_t)f.mask->width * f.mask->height;
    unsigned rect[4];
    pelt__wetness_take_dirty(f.mask, rect); /* start clean */
    float *before = malloc(n * 4 * sizeof *before);
    memcpy(before, f.mask->texels, n * 4 * sizeof *before);
    drop_on_border(&f, 0.6f);
    CHECK(pelt__wetness_take_dirty(f.mask, rect));
    for (size_t i = 0; i < n; i++) {
        if (memcmp(before + i * 4, f.mask->texels + i * 4, 4 * sizeof(float)) == 0) continue;
        unsigned x = (unsigned)(i % f.mask->width), y = (unsigned)(i / f.mask->width);
        CHECK(x >= rect[0] && x < rect[2] && y >= rect[1] && y < rect[3]);
        CHECK(x >= f.mask->wet[0] && x < f.mask->wet[2] && y >= f.mask->wet[1] &&
              y < f.mask->wet[3]);
    }
    free(before);
    fixture_free(&f);
}

/* A triangle whose neighbourhood of `radius` around its centroid lies in
 * its own patch. */
static bool find_interior(const fixture *f, float radius, size_t *tri)
{
    const pelt_mesh *m = f->mesh;
    for (size_t t = 0; t < m->triangle_count; t += 7) {
        pelt_vec3 c = v3_scale(v3_add(pos(m, t, 0), v3_add(pos(m, t, 1), pos(m, t, 2))), 1.0f / 3.0f);
        if (fabsf(c.y) > 0.6f) continue;
        bool alone = true;
        for (size_t s = 0; s < m->triangle_count && alone; s++) {
            if (f->patch[s] == f->patch[t]) continue;
            for (int k = 0; k < 3; k++)
                if (v3_len(v3_sub(pos(m, s, k), c)) < 2.0f * radius) alone = false;
        }
        if (alone) {
            *tri = t;
            return true;
        }
    }
    return false;
}

/* The droplet a surface point makes in uv space, by hand: centre = the
 * barycentric blend of the triangle's uvs, radius scaled by the triangle's
 * sqrt(uv area / world area). */
static pelt_droplet uv_droplet(const pelt_mesh *m, size_t t, const float bary[3], float radius,
                               float wetness)
{
    pelt_droplet d = {{0.0f, 0.0f}, 0.0f, wetness};
    for (int k = 0; k < 3; k++) {
        d.center[0] += bary[k] * uv(m, t, k)[0];
        d.center[1] += bary[k] * uv(m, t, k)[1];
    }
    const float *a = uv(m, t, 0), *b = uv(m, t, 1), *c = uv(m, t, 2);
    float uv_area = 0.5f * fabsf((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
    float world_area = 0.5f * v3_len(v3_cross(v3_sub(pos(m, t, 1), pos(m, t, 0)),
                                              v3_sub(pos(m, t, 2), pos(m, t, 0))));
    d.radius = radius * sqrtf(uv_area / world_area);
    return d;
}

/* One triangle, world area 2, uv area 0.125: a drop of world radius 0.4 is
 * a clump of uv radius 0.4 * sqrt(0.125 / 2) = 0.1 centred on the
 * barycentric blend of the uvs. */
static void point_drop_scales_radius_by_uv_area(void)
{
    const float p[9] = {0, 0, 0, 2, 0, 0, 0, 2, 0}, t[6] = {0, 0, 0.5f, 0, 0, 0.5f};
    const uint32_t ix[3] = {0, 1, 2};
    pelt_mesh_data md = {.positions = p, .uvs = t, .vertex_count = 3, .indices = ix,
                         .triangle_count = 1};
    pelt_mesh *m = NULL;
    pelt__surface_index *index = NULL;
    pelt__wetness *mask = NULL;
    CHECK(pelt_mesh_create(&md, &m, NULL) == PELT_OK);
    if (!m) return;
    CHECK(pelt__surface_index_create(m, NULL, &index, NULL) == PELT_OK);
    CHECK(pelt__wetness_create(16, 16, NULL, &mask, NULL) == PELT_OK);
    const float bary[3] = {0.2f, 0.3f, 0.5f};
    CHECK(pelt__droplet_surface(mask, m, index, 0, bary, 0.4f, 0.6f, NULL) == PELT_OK);
    /* Texel (2, 4) holds uv (0.15, 0.25). */
    const float *x = mask->texels + (4 * 16 + 2) * 4;
    CHECK_NEAR(x[0], 0.15, 1e-6);
    CHECK_NEAR(x[1], 0.25, 1e-6);
    CHECK_NEAR(x[2], 0.1, 1e-6);
    CHECK(x[3] == 0.6f);
    pelt_droplet d = uv_droplet(m, 0, bary, 0.4f, 0.6f);
    CHECK_NEAR(d.radius, 0.1, 1e-6);
    pelt_error err = {0};
    CHECK(pelt__droplet_surface(mask, m, index, 1, bary, 0.4f, 0.6f, &err) ==
          PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "triangle 1") != NULL);
    pelt__wetness_destroy(mask);
    pelt__surface_index_destroy(index);
    pelt_mesh_destroy(m);
}

static void interior_drop_matches_mask_droplet(void)
{
    fixture f = sphere_fixture();
    pelt__wetness *ref = NULL;
    CHECK(pelt__wetness_create(f.mask->width, f.mask->height, NULL, &ref, NULL) == PELT_OK);
    size_t tri = 0;
    float radius = 1.5f * edge_length(f.mesh, 0 + 100);
    CHECK(find_interior(&f, radius, &tri));
    /* Three drops: dry texels, a merge into the same clump, a hair dryer.
     * Before each the reference mask copies the surface mask, so each drop
     * is compared alone. */
    const float bary[3][3] = {{0.3f, 0.3f, 0.4f}, {0.5f, 0.25f, 0.25f}, {0.2f, 0.6f, 0.2f}};
    const float wet[3] = {0.5f, 0.4f, -0.2f};
    size_t n = (size_t)ref->width * ref->height, both = 0, differ = 0;
    for (int k = 0; k < 3; k++) {
        memcpy(ref->texels, f.mask->texels, n * 4 * sizeof(float));
        CHECK(pelt__droplet_surface(f.mask, f.mesh, f.index, tri, bary[k], radius, wet[k], NULL) ==
              PELT_OK);
        pelt_droplet d = uv_droplet(f.mesh, tri, bary[k], radius, wet[k]);
        CHECK(pelt__wetness_add_droplet(ref, &d, NULL) == PELT_OK);
        for (size_t i = 0; i < n; i++) {
            const float *a = f.mask->texels + i * 4, *b = ref->texels + i * 4;
            bool same = fabsf(a[0] - b[0]) <= 1e-5f && fabsf(a[1] - b[1]) <= 1e-5f &&
                        fabsf(a[2] - b[2]) <= 1e-5f + 1e-3f * b[2] && fabsf(a[3] - b[3]) <= 1e-5f;
            if (same) {
                both += a[3] > 0.0f;
                continue;
            }
            /* Only at the rim, where uv and surface distance disagree by
             * the patch's stretch and the curvature. */
            differ++;
            double q[2];
            texel_centre(ref, i, q);
            double dist = hypot(q[0] - d.center[0], q[1] - d.center[1]);
            CHECK(dist > 0.85 * d.radius && dist < 1.15 * d.radius);
        }
    }
    printf("  interior drops: %zu wet texels agree, %zu differ at the rim\n", both, differ);
    CHECK(both > 10);
    CHECK(differ * 5 <= both);
    pelt__wetness_destroy(ref);
    fixture_free(&f);
}

static void negative_drop_dries_the_clump(void)
{
    fixture f = sphere_fixture();
    drop_on_border(&f, 0.7f);
    size_t n = (size_t)f.mask->width * f.mask->height, wet = 0;
    for (size_t i = 0; i < n; i++) wet += f.mask->texels[i * 4 + 3] > 0.0f;
    CHECK(wet > 0);
    border_drop d = drop_on_border(&f, -1.0f);
    (void)d;
    for (size_t i = 0; i < n; i++) CHECK(f.mask->texels[i * 4 + 3] == 0.0f);
    /* A hair dryer on dry fur makes nothing wet. */
    drop_on_border(&f, -0.5f);
    for (size_t i = 0; i < n; i++) CHECK(f.mask->texels[i * 4 + 3] == 0.0f);
    fixture_free(&f);
}

static void bad_arguments_are_rejected(void)
{
    fixture f = sphere_fixture();
    float ok[3] = {0.2f, 0.3f, 0.5f}, nan3[3] = {NAN, 0.5f, 0.5f};
    pelt_error err = {0};
    size_t tc = f.mesh->triangle_count;
    CHECK(pelt__droplet_surface(f.mask, f.mesh, f.index, tc, ok, 0.1f, 1.0f, &err) ==
          PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "triangle") != NULL);
    CHECK(pelt__droplet_surface(f.mask, f.mesh, f.index, 0, nan3, 0.1f, 1.0f, NULL) ==
          PELT_ERR_INVALID_ARGUMENT);
    CHECK(pelt__droplet_surface(f.mask, f.mesh, f.index, 0, ok, -0.1f, 1.0f, NULL) ==
          PELT_ERR_INVALID_ARGUMENT);
    CHECK(pelt__droplet_surface(f.mask, f.mesh, f.index, 0, ok, INFINITY, 1.0f, NULL) ==
          PELT_ERR_INVALID_ARGUMENT);
    CHECK(pelt__droplet_surface(f.mask, f.mesh, f.index, 0, ok, 0.1f, NAN, NULL) ==
          PELT_ERR_INVALID_ARGUMENT);
    CHECK(pelt__droplet_surface(f.mask, f.mesh, NULL, 0, ok, 0.1f, 1.0f, NULL) ==
          PELT_ERR_INVALID_ARGUMENT);
    /* An index of another mesh is refused. */
    pelt_mesh *other = NULL;
    CHECK(pelt_mesh_sphere(1.0f, 8, 4, &other, NULL) == PELT_OK);
    CHECK(pelt__droplet_surface(f.mask, other, f.index, 0, ok, 0.1f, 1.0f, NULL) ==
          PELT_ERR_INVALID_ARGUMENT);
    pelt_mesh_destroy(other);
    size_t n = (size_t)f.mask->width * f.mask->height;
    for (size_t i = 0; i < n * 4; i++) CHECK(f.mask->texels[i] == 0.0f);
    unsigned rect[4];
    CHECK(!pelt__wetness_take_dirty(f.mask, rect));
    fixture_free(&f);
}

/* On the torus (closed both ways, patch borders everywhere) too: every
 * wet texel within the world radius, every texel in it wet. */
static void torus_border_drop_covers_the_ball(void)
{
    pelt_mesh *t = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 48, 24, &t, NULL) == PELT_OK);
    fixture f;
    if (!fixture_make(&f, t)) return;
    fixture_owners(&f);
    border_drop d = drop_on_border(&f, 1.0f);
    size_t n = (size_t)f.mask->width * f.mask->height, bad = 0, wet = 0;
    for (size_t i = 0; i < n; i++) {
        bool w = f.mask->texels[i * 4 + 3] > 0.0f;
        wet += w;
        if (f.owner[i] < 0) {
            bad += w;
            continue;
        }
        double q[2], b[3];
        texel_centre(f.mask, i, q);
        uv_bary(f.mesh, (size_t)f.owner[i], q, b);
        double dist = v3_len(v3_sub(blend(f.mesh, (size_t)f.owner[i], b), d.p));
        if ((w && dist > d.radius * 1.001) || (!w && dist < d.radius * 0.999)) bad++;
    }
    CHECK(wet > 20);
    CHECK(bad == 0);
    fixture_free(&f);
}

/* The procedural sphere's own uvs wrap once around: the seam at u = 0 / 1
 * joins two ends of one chart. A drop on it must express its centre on
 * each side in that side's coordinates, not carry u = 0.99 over to u = 0.01. */
static void drop_on_uv_seam_keeps_each_side_local(void)
{
    pelt_mesh *s = NULL;
    CHECK(pelt_mesh_sphere(1.0f, 48, 24, &s, NULL) == PELT_OK);
    pelt__wetness *mask = NULL;
    pelt__surface_index *index = NULL;
    CHECK(pelt__wetness_create(256, 256, NULL, &mask, NULL) == PELT_OK);
    CHECK(pelt__surface_index_create(s, NULL, &index, NULL) == PELT_OK);
    /* A corner at u = 0 near the equator. */
    size_t tri = SIZE_MAX;
    int corner = 0;
    for (size_t t = 0; t < s->triangle_count && tri == SIZE_MAX; t++)
        for (int k = 0; k < 3; k++)
            if (uv(s, t, k)[0] == 0.0f && fabsf(pos(s, t, k).y) < 0.2f) {
                tri = t;
                corner = k;
                break;
            }
    CHECK(tri != SIZE_MAX);
    if (tri == SIZE_MAX) return;
    float bary[3] = {0, 0, 0};
    bary[corner] = 1.0f;
    pelt_vec3 p = pos(s, tri, corner);
    float radius = 2.0f * edge_length(s, tri);
    CHECK(pelt__droplet_surface(mask, s, index, tri, bary, radius, 1.0f, NULL) == PELT_OK);
    size_t n = (size_t)mask->width * mask->height, low = 0, high = 0;
    double worst = 0.0;
    for (size_t i = 0; i < n; i++) {
        const float *t = mask->texels + i * 4;
        if (!(t[3] > 0.0f)) continue;
        double q[2];
        texel_centre(mask, i, q);
        low += q[0] < 0.5;
        high += q[0] >= 0.5;
        /* The centre sits on this texel's side of the seam: a few
         * triangles away in u, not across the whole texture. */
        double du = fabs(q[0] - t[0]);
        if (du > worst) worst = du;
    }
    (void)p;
    CHECK(low > 0 && high > 0);
    CHECK(worst <= 4.0 / 48.0);
    pelt__surface_index_destroy(index);
    pelt__wetness_destroy(mask);
    pelt_mesh_destroy(s);
}

/* Time per droplet of about 4 texels radius on a ~100k-triangle atlas. */
static void droplet_cost_follows_footprint(void)
{
    pelt_mesh *s = NULL;
    CHECK(pelt_mesh_sphere(1.0f, 320, 160, &s, NULL) == PELT_OK);
    fixture f;
    double t0 = now_s();
    if (!fixture_make(&f, s)) return;
    double t1 = now_s();
    const pelt_mesh *m = f.mesh;
    /* World radius of 4 texels from the mean uv-per-world scale. */
    double uva = 0.0, wa = 0.0;
    for (size_t t = 0; t < m->triangle_count; t++) {
        const float *a = uv(m, t, 0), *b = uv(m, t, 1), *c = uv(m, t, 2);
        uva += 0.5 * fabs(((double)b[0] - a[0]) * ((double)c[1] - a[1]) -
                          ((double)c[0] - a[0]) * ((double)b[1] - a[1]));
        wa += 0.5 * v3_len(v3_cross(v3_sub(pos(m, t, 1), pos(m, t, 0)),
                                     v3_sub(pos(m, t, 2), pos(m, t, 0))));
    }
    float radius = (float)(4.0 / (f.mask->width * sqrt(uva / wa)));
    uint64_t rng = 12345;
    const int count = 2000;
    double t2 = now_s();
    for (int i = 0; i < count; i++) {
        rng = rng * 6364136223846793005ull + 1442695040888963407ull;
        size_t tri = (size_t)(rng >> 33) % m->triangle_count;
        float bary[3] = {0.2f, 0.3f, 0.5f};
        CHECK(pelt__droplet_surface(f.mask, m, f.index, tri, bary, radius, 0.7f, NULL) == PELT_OK);
    }
    double t3 = now_s();
    /* The sphere's pole fans hold hundreds of slivers within 4 texels, so
     * time mid-latitude drops (regular triangles) apart. */
    int mid = 0;
    for (int i = 0; mid < count; i++) {
        rng = rng * 6364136223846793005ull + 1442695040888963407ull;
        size_t tri = (size_t)(rng >> 33) % m->triangle_count;
        if (fabsf(pos(m, tri, 0).y) > 0.8f) continue;
        float bary[3] = {0.2f, 0.3f, 0.5f};
        CHECK(pelt__droplet_surface(f.mask, m, f.index, tri, bary, radius, 0.7f, NULL) == PELT_OK);
        mid++;
    }
    double t4 = now_s();
    size_t wet = 0, n = (size_t)f.mask->width * f.mask->height;
    for (size_t i = 0; i < n; i++) wet += f.mask->texels[i * 4 + 3] > 0.0f;
    printf("  %zu triangles, mask %u: atlas + index %.2f s, %.2f us per droplet "
           "(%.2f us at |y| <= 0.8; radius %.4f world = 4 texels), %zu texels wet\n",
           m->triangle_count, f.mask->width, t1 - t0, (t3 - t2) / count * 1e6,
           (t4 - t3) / count * 1e6, (double)radius, wet);
    CHECK(m->triangle_count > 90000);
    CHECK(wet > 0);
    fixture_free(&f);
}

int main(void)
{
    RUN(border_drop_wets_two_patches);
    RUN(border_drop_is_one_clump_in_3d);
    RUN(wet_texels_lie_within_world_radius);
    RUN(changes_stay_inside_dirty_and_wet_rects);
    RUN(point_drop_scales_radius_by_uv_area);
    RUN(interior_drop_matches_mask_droplet);
    RUN(negative_drop_dries_the_clump);
    RUN(bad_arguments_are_rejected);
    RUN(torus_border_drop_covers_the_ball);
    RUN(drop_on_uv_seam_keeps_each_side_local);
    RUN(droplet_cost_follows_footprint);
    return check_summary();
}
