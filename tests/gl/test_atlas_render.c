/* Fur over a patch atlas, rendered: a droplet that lands on a patch border
 * wets by distance on the surface and makes one round clump. */
#include "support/gl_test.h"

#include "core/mesh/mesh_internal.h"
#include "pelt/atlas.h"

enum { W = 200, H = 200 };

static pelt_headless *gl;

typedef struct drop_at {
    size_t triangle;
    float bary[3];
    float radius;
    const float *uv; /* NULL: surface droplet; else a plain uv-space droplet here */
    float uv_radius;
} drop_at;

static void add_drop(pelt_fur *fur, void *user)
{
    const drop_at *d = user;
    if (d->uv) {
        pelt_droplet dr = {{d->uv[0], d->uv[1]}, d->uv_radius, 1.0f};
        CHECK(pelt_fur_add_droplet(fur, &dr, NULL) == PELT_OK);
    } else {
        CHECK(pelt_fur_add_droplet_at(fur, d->triangle, d->bary, d->radius, 1.0f, NULL) == PELT_OK);
    }
}

/* The changed pixels' largest 4-connected blob: its share of all changed
 * pixels and the ratio of its largest to smallest radial extent over 16
 * directions around its centroid. */
static void blob_shape(const uint8_t *a, const uint8_t *b, double *share, double *roundness,
                       size_t *pixels)
{
    static uint8_t mask[W * H];
    static int label[W * H], queue[W * H];
    size_t changed = 0;
    for (int i = 0; i < W * H; i++) {
        int d = 0;
        for (int k = 0; k < 3; k++) {
            int e = abs((int)a[4 * i + k] - (int)b[4 * i + k]);
            if (e > d) d = e;
        }
        mask[i] = d > 12;
        label[i] = 0;
        changed += mask[i];
    }
    int best = 0, best_size = 0, next = 0;
    for (int i = 0; i < W * H; i++) {
        if (!mask[i] || label[i]) continue;
        int head = 0, tail = 0, size = 0;
        label[i] = ++next;
        queue[tail++] = i;
        while (head < tail) {
            int p = queue[head++], x = p % W, y = p / W;
            size++;
            const int nb[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
            for (int k = 0; k < 4; k++) {
                int nx = x + nb[k][0], ny = y + nb[k][1];
                if (nx < 0 || ny < 0 || nx >= W || ny >= H) continue;
                int q = ny * W + nx;
                if (mask[q] && !label[q]) {
                    label[q] = next;
                    queue[tail++] = q;
                }
            }
        }
        if (size > best_size) best_size = size, best = next;
    }
    double cx = 0, cy = 0;
    for (int i = 0; i < W * H; i++)
        if (label[i] == best && best) cx += i % W, cy += i / W;
    cx /= best_size > 0 ? best_size : 1;
    cy /= best_size > 0 ? best_size : 1;
    double extent[16] = {0};
    for (int i = 0; i < W * H; i++) {
        if (label[i] != best || !best) continue;
        double dx = i % W - cx, dy = i / W - cy, r = sqrt(dx * dx + dy * dy);
        int bin = (int)((atan2(dy, dx) + 3.14159265358979) / (2 * 3.14159265358979) * 16) % 16;
        if (r > extent[bin]) extent[bin] = r;
    }
    double lo = 1e9, hi = 0;
    for (int k = 0; k < 16; k++) lo = fmin(lo, extent[k]), hi = fmax(hi, extent[k]);
    *share = changed ? (double)best_size / (double)changed : 0.0;
    *roundness = lo > 0 ? hi / lo : 1e9;
    *pixels = (size_t)best_size;
}

static void droplet_on_patch_border_makes_one_round_clump(void)
{
    pelt_mesh *sphere = NULL;
    pelt_atlas *atlas = NULL;
    CHECK(pelt_mesh_sphere(1.0f, 48, 24, &sphere, NULL) == PELT_OK);
    pelt_atlas_desc ad = {.mode = PELT_ATLAS_PATCHES, .mask_size = 512};
    CHECK(sphere && pelt_atlas_create(sphere, &ad, &atlas, NULL) == PELT_OK);
    if (!atlas) {
        pelt_mesh_destroy(sphere);
        return;
    }
    const pelt_mesh *m = pelt_atlas_mesh(atlas);
    const uint32_t *patch = pelt_atlas_triangle_patches(atlas);
    /* A corner on a patch border, facing the camera (+Z) as well as can be:
     * a position whose triangles belong to two patches. */
    size_t best_t = 0;
    int best_c = 0;
    float best_z = -2.0f;
    for (size_t t = 0; t < m->triangle_count; t++)
        for (int c = 0; c < 3; c++) {
            const float *p = m->positions + 3 * m->indices[3 * t + c];
            if (p[2] <= best_z || fabsf(p[1]) > 0.5f) continue;
            bool border = false;
            for (size_t u = 0; u < m->triangle_count && !border; u++) {
                if (patch[u] == patch[t]) continue;
                for (int k = 0; k < 3; k++) {
                    const float *q = m->positions + 3 * m->indices[3 * u + k];
                    if (q[0] == p[0] && q[1] == p[1] && q[2] == p[2]) border = true;
                }
            }
            if (border) best_z = p[2], best_t = t, best_c = c;
        }
    CHECK(best_z > 0.7f);
    printf("  border corner at z %.3f\n", (double)best_z);
    const float *p = m->positions + 3 * m->indices[3 * best_t + best_c];
    pelt_camera cam = {0};
    cam.yaw = atan2f(p[0], p[2]) * 57.29578f;
    cam.pitch = asinf(p[1]) * 57.29578f;
    cam.distance = 1.4f;
    memcpy(cam.target, p, sizeof cam.target);
    cam.fov_y = 40.0f;
    pelt_fur_desc d = {.length = 0.08f, .wet.mask_size = 512};
    drop_at surface = {best_t, {0, 0, 0}, 0.15f, NULL, 0};
    surface.bary[best_c] = 1.0f;
    uint8_t *dry = gl_test_render(gl, m, &d, &cam, NULL, NULL, NULL);
    uint8_t *wet = gl_test_render(gl, m, &d, &cam, NULL, add_drop, &surface);
    /* The same drop as a plain uv-space droplet: it stops at the border. */
    const float *uv = m->uvs + 2 * m->indices[3 * best_t + best_c];
    drop_at flat = {0, {0, 0, 0}, 0, uv, 0.15f * pelt_atlas_get_stats(atlas)->texel_density /
                                                pelt_atlas_get_stats(atlas)->fur_per_atlas};
    uint8_t *cut = gl_test_render(gl, m, &d, &cam, NULL, add_drop, &flat);
    CHECK(dry && wet && cut);
    if (dry && wet && cut) {
        stbi_write_png(PELT_TEST_OUT "/border_clump.png", W, H, 4, wet, W * 4);
        stbi_write_png(PELT_TEST_OUT "/border_dry.png", W, H, 4, dry, W * 4);
        stbi_write_png(PELT_TEST_OUT "/border_clump_uv_space.png", W, H, 4, cut, W * 4);
        double share, round, cshare, cround;
        size_t px, cpx;
        blob_shape(dry, wet, &share, &round, &px);
        blob_shape(dry, cut, &cshare, &cround, &cpx);
        printf("  surface droplet on a border: one blob of %zu px holds %.3f of the change, "
               "extent ratio %.2f\n  uv-space droplet there: %zu px, share %.3f, ratio %.2f\n",
               px, share, round, cpx, cshare, cround);
        CHECK(px > 400);
        CHECK(share > 0.9);
        CHECK(round < 1.6);
    }
    free(dry);
    free(wet);
    free(cut);
    pelt_atlas_destroy(atlas);
    pelt_mesh_destroy(sphere);
}

/* The direction field travels with the atlas mesh to the renderer as the
 * comb: where a downward field vanishes (the poles) it fades to nothing,
 * so the fur stands up; on the equator it points down, at full length. */
static void comb_stands_fur_up_at_the_poles(void)
{
    pelt_mesh *sphere = NULL;
    pelt_atlas *atlas = NULL;
    CHECK(pelt_mesh_sphere(1.0f, 48, 24, &sphere, NULL) == PELT_OK);
    pelt_atlas_desc ad = {.mode = PELT_ATLAS_PATCHES};
    CHECK(sphere && pelt_atlas_create(sphere, &ad, &atlas, NULL) == PELT_OK);
    pelt_mesh *m = atlas ? pelt_atlas_take_mesh(atlas) : NULL;
    CHECK(m && m->comb);
    if (m && m->comb) {
        double pole = 0.0, equator = 1.0;
        size_t at_pole = 0, on_equator = 0;
        for (size_t i = 0; i < m->vertex_count; i++) {
            float y = m->positions[3 * i + 1];
            const float *c = m->comb + 3 * i;
            float w = sqrtf(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
            if (fabsf(y) < 0.05f) CHECK(c[1] < -0.8f); /* combed down */
            if (fabsf(y) > 0.999f) pole = fmax(pole, w), at_pole++;
            if (fabsf(y) < 0.05f) equator = fmin(equator, w), on_equator++;
        }
        CHECK(at_pole > 0 && on_equator > 0);
        printf("  longest comb at a pole %.3f, shortest on the equator %.3f\n", pole, equator);
        CHECK(pole < 0.2);
        CHECK(equator > 0.8);
    }
    pelt_mesh_destroy(m);
    pelt_atlas_destroy(atlas);
    pelt_mesh_destroy(sphere);
}

/* A mesh file's vertex colours, read as a flow map, comb the fur: here a
 * whirl around +Y (colour = 0.5 + 0.5 (-z, 0, x) / |(x, z)|). */
static void vertex_colours_comb_the_fur(void)
{
    pelt_mesh *m = NULL;
    pelt_atlas *atlas = NULL;
    CHECK(pelt_mesh_load(PELT_TEST_DATA "/meshes/swirl_colors.ply", &m, NULL) == PELT_OK);
    CHECK(m && pelt_mesh_directions(m));
    if (!m || !pelt_mesh_directions(m)) {
        pelt_mesh_destroy(m);
        return;
    }
    pelt_atlas_desc ad = {.mode = PELT_ATLAS_PATCHES, .vertex_directions = pelt_mesh_directions(m)};
    CHECK(pelt_atlas_create(m, &ad, &atlas, NULL) == PELT_OK);
    pelt_mesh *split = atlas ? pelt_atlas_take_mesh(atlas) : NULL;
    CHECK(split && split->comb);
    size_t checked = 0, along = 0;
    for (size_t i = 0; split && split->comb && i < split->vertex_count; i++) {
        const float *p = split->positions + 3 * i, *c = split->comb + 3 * i;
        float r = hypotf(p[0], p[2]), cl = sqrtf(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        if (r < 0.3f || cl < 0.5f) continue; /* away from the whirl's centre */
        checked++;
        float cosang = (-p[2] * c[0] + p[0] * c[2]) / (r * cl);
        if (cosang > 0.95f) along++;
    }
    printf("  %zu of %zu combs within 18 degrees of the whirl\n", along, checked);
    CHECK(checked > 100);
    CHECK(along > checked * 95 / 100);
    pelt_mesh_destroy(split);
    pelt_atlas_destroy(atlas);
    pelt_mesh_destroy(m);
}

int main(void)
{
    gl = gl_test_open(W, H, false);
    if (!gl) return check_skip("no OpenGL context");
    RUN(droplet_on_patch_border_makes_one_round_clump);
    RUN(comb_stands_fur_up_at_the_poles);
    RUN(vertex_colours_comb_the_fur);
    pelt_headless_destroy(gl);
    return check_summary();
}
