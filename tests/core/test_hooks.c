/* Allocator and logger hooks (pelt_hooks): an object made with them
 * allocates everything it owns through them and frees it all back. */
#include "pelt/atlas.h"
#include "pelt/pelt.h"
#include "support/check.h"

#include <stdlib.h>
#include <string.h>

/* A counting allocator: each block carries its size in front, so the
 * bytes handed out and given back can be compared. */
typedef struct counter {
    size_t allocs, frees, live_bytes, peak_bytes;
    size_t fail_after; /* 0 = never fail; else the n-th alloc returns NULL */
} counter;

static void *count_alloc(size_t size, void *user)
{
    counter *c = user;
    if (c->fail_after && c->allocs + 1 == c->fail_after) return NULL;
    size_t *p = malloc(sizeof(size_t) * 2 + size);
    if (!p) return NULL;
    p[0] = size;
    c->allocs++;
    c->live_bytes += size;
    if (c->live_bytes > c->peak_bytes) c->peak_bytes = c->live_bytes;
    return p + 2;
}

static void count_free(void *ptr, void *user)
{
    counter *c = user;
    size_t *p = (size_t *)ptr - 2;
    c->frees++;
    c->live_bytes -= p[0];
    free(p);
}

static pelt_fur_desc counted_desc(counter *c)
{
    pelt_fur_desc d = {.layers = 8, .look.texture_size = 32, .wet.mask_size = 64};
    d.hooks.allocator = (pelt_allocator){count_alloc, count_free, c};
    return d;
}

static void fur_allocates_everything_through_its_hooks(void)
{
    pelt_mesh *mesh = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 24, 12, &mesh, NULL) == PELT_OK);
    if (!mesh) return;
    counter c = {0};
    pelt_fur_desc d = counted_desc(&c);
    pelt_fur *fur = NULL;
    pelt_error err = {0};
    CHECK(pelt_fur_create(mesh, &d, &fur, &err) == PELT_OK);
    if (!fur) {
        pelt_mesh_destroy(mesh);
        return;
    }
    size_t after_create = c.allocs;
    /* Strands, the fur volume, the mask, the surface index, the BVH, the
     * rain: at least one block each. */
    printf("  create: %zu allocations, %zu bytes live\n", c.allocs, c.live_bytes);
    CHECK(after_create >= 8);
    CHECK(c.live_bytes >= (size_t)33 * 32 * 9 + 64 * 64 * 16); /* volume + mask */
    CHECK(pelt_fur_set_color_pattern(fur, PELT_COLOR_PATTERN_SPOTS, 3, &err) == PELT_OK);
    uint8_t grey[16 * 16];
    memset(grey, 200, sizeof grey);
    CHECK(pelt_fur_paint_wetness(fur, grey, 16, 16, 1.0f, &err) == PELT_OK);
    CHECK(c.allocs > after_create); /* pattern, painting scratch */
    pelt_rain rain = {.rate = 200.0f, .seed = 7};
    pelt_fur_set_rain(fur, &rain);
    size_t before_steps = c.allocs;
    for (int i = 0; i < 30; i++) pelt_fur_step(fur, 1.0f / 30.0f, NULL);
    CHECK(c.allocs == before_steps); /* no allocation in the per-frame path */
    float origin[3] = {1.0f, 2.0f, 0.0f}, down[3] = {0.0f, -1.0f, 0.0f};
    CHECK(pelt_fur_add_droplet_ray(fur, origin, down, 0.1f, 1.0f));
    pelt_fur_destroy(fur);
    printf("  %zu allocations, %zu frees, peak %zu bytes, %zu bytes left\n", c.allocs, c.frees,
           c.peak_bytes, c.live_bytes);
    CHECK(c.frees == c.allocs);
    CHECK(c.live_bytes == 0);
    pelt_mesh_destroy(mesh);
}

static void failed_allocation_cleans_up(void)
{
    pelt_mesh *mesh = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 24, 12, &mesh, NULL) == PELT_OK);
    if (!mesh) return;
    /* Fail each allocation of create in turn: a clean error, nothing kept. */
    counter probe = {0};
    pelt_fur_desc d = counted_desc(&probe);
    pelt_fur *fur = NULL;
    CHECK(pelt_fur_create(mesh, &d, &fur, NULL) == PELT_OK);
    pelt_fur_destroy(fur);
    size_t n = probe.allocs, failures = 0;
    for (size_t k = 1; k <= n; k++) {
        counter c = {.fail_after = k};
        d = counted_desc(&c);
        pelt_error err = {0};
        fur = (pelt_fur *)1;
        pelt_status st = pelt_fur_create(mesh, &d, &fur, &err);
        if (st == PELT_ERR_OUT_OF_MEMORY && fur == NULL && c.live_bytes == 0 && c.frees == c.allocs)
            failures++;
        else
            fprintf(stderr, "  allocation %zu failing: status %d, %zu bytes left\n", k, (int)st,
                    c.live_bytes);
    }
    printf("  each of %zu allocations failed in turn: %zu clean errors\n", n, failures);
    CHECK(failures == n);
    pelt_mesh_destroy(mesh);
}

static void half_an_allocator_is_refused(void)
{
    pelt_mesh *mesh = NULL;
    CHECK(pelt_mesh_torus(1.0f, 0.4f, 12, 8, &mesh, NULL) == PELT_OK);
    if (!mesh) return;
    counter c = {0};
    pelt_fur_desc d = counted_desc(&c);
    d.hooks.allocator.free = NULL;
    pelt_fur *fur = NULL;
    pelt_error err = {0};
    CHECK(pelt_fur_create(mesh, &d, &fur, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(fur == NULL && c.allocs == 0);
    CHECK(strstr(err.message, "pelt_fur_desc.hooks.allocator") != NULL);
    pelt_mesh_destroy(mesh);
}

typedef struct log_seen { int warnings; char last[512]; } log_seen;
static void keep_log(pelt_log_level level, const char *msg, void *user)
{
    log_seen *l = user;
    if (level == PELT_LOG_WARNING) l->warnings++;
    snprintf(l->last, sizeof l->last, "%s", msg);
}

static void atlas_allocates_through_its_hooks_and_warns_to_the_logger(void)
{
    pelt_mesh *mesh = NULL;
    pelt_error err = {0};
    CHECK(pelt_mesh_load(PELT_TEST_DATA "/meshes/cube_quads.obj", &mesh, &err) == PELT_OK);
    if (!mesh) return;
    counter c = {0};
    log_seen l = {0};
    pelt_atlas_desc d = {.hooks = {{count_alloc, count_free, &c}, {keep_log, &l}}};
    pelt_atlas *atlas = NULL;
    CHECK(pelt_atlas_create(mesh, &d, &atlas, &err) == PELT_OK);
    printf("  %zu allocations; warning: %s\n", c.allocs, l.last);
    CHECK(c.allocs >= 20); /* the atlas's arrays and the builder's */
    CHECK(l.warnings == 1 && strstr(l.last, "not using the mesh's uvs") != NULL);
    pelt_atlas_destroy(atlas);
    CHECK(c.frees == c.allocs && c.live_bytes == 0);
    d.hooks.allocator.alloc = NULL;
    CHECK(pelt_atlas_create(mesh, &d, &atlas, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "pelt_atlas_desc.hooks.allocator") != NULL);
    pelt_mesh_destroy(mesh);
}

int main(void)
{
    RUN(fur_allocates_everything_through_its_hooks);
    RUN(failed_allocation_cleans_up);
    RUN(half_an_allocator_is_refused);
    RUN(atlas_allocates_through_its_hooks_and_warns_to_the_logger);
    return check_summary();
}
