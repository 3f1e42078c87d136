/* The water object (core/wet/water.c): every way water arrives marks the
 * texels it changed in one dirty rectangle, natural clumps see each call's
 * change, the rain falls and the mask dries in one step. Expected values
 * come from the geometry of a square. */
#include "support/check.h"
#include "core/mesh/raycast.h"
#include "core/wet/water.h"
#include "pelt/mesh.h"

#include <math.h>
#include <stdlib.h>

static float wet_sum(const pelt__wetness *m)
{
    double s = 0.0;
    for (size_t i = 0; i < (size_t)m->width * m->height; i++) s += m->texels[4 * i + 3];
    return (float)s;
}

/* A 2 x 2 square in XZ, normal +Y, uvs over [0,1]^2. */
static void with_water(float clump_size, void (*body)(pelt__water *w))
{
    pelt_mesh *sq = NULL;
    pelt__bvh *bvh = NULL;
    pelt__water *w = NULL;
    CHECK(pelt_mesh_square(2.0f, 8, &sq, NULL) == PELT_OK);
    CHECK(sq && pelt__bvh_build(sq, NULL, &bvh, NULL) == PELT_OK);
    pelt__water_desc d = {64, clump_size, 7};
    CHECK(bvh && pelt__water_create(sq, bvh, &d, NULL, &w, NULL) == PELT_OK);
    if (w) body(w);
    pelt__water_destroy(w);
    pelt__bvh_destroy(bvh);
    pelt_mesh_destroy(sq);
}

static void ray_drop(pelt__water *w)
{
    unsigned r[4];
    CHECK(!pelt__water_take_dirty(w, r)); /* a new mask is dry and clean */
    const float origin[3] = {0.5f, 3.0f, 0.5f}, down[3] = {0.0f, -1.0f, 0.0f}, up[3] = {0.0f, 1.0f, 0.0f};
    CHECK(!pelt__water_drop_ray(w, origin, up, 0.2f, 1.0f)); /* misses */
    CHECK(!pelt__water_take_dirty(w, r));
    CHECK(pelt__water_drop_ray(w, origin, down, 0.2f, 1.0f));
    CHECK(pelt__water_take_dirty(w, r));
    /* The droplet is 0.2 of the world's 2 units, 0.1 of the mask: about 6
     * texels across out of 64, round the hit. */
    CHECK(r[0] < r[2] && r[1] < r[3] && r[2] - r[0] <= 12 && r[3] - r[1] <= 12);
    CHECK(!pelt__water_take_dirty(w, r)); /* taken */
    CHECK(wet_sum(pelt__water_mask(w)) > 0.0f);
}

static void drying_and_clearing(pelt__water *w)
{
    pelt_droplet d = {{0.5f, 0.5f}, 0.2f, 1.0f};
    CHECK(pelt__water_drop_uv(w, &d, 1, NULL) == PELT_OK);
    float wet = wet_sum(pelt__water_mask(w));
    CHECK(wet > 0.0f);
    pelt__water_step(w, 0.5f); /* no dry rate: nothing dries */
    CHECK(wet_sum(pelt__water_mask(w)) == wet);
    pelt__water_set_dry_rate(w, 0.5f);
    pelt__water_step(w, 0.5f);
    float dried = wet_sum(pelt__water_mask(w));
    CHECK(dried < wet && dried >= 0.0f);
    pelt__water_clear(w);
    CHECK(wet_sum(pelt__water_mask(w)) == 0.0f);
    pelt_droplet bad = {{NAN, 0.5f}, 0.2f, 1.0f};
    pelt_error err = {0};
    CHECK(pelt__water_drop_uv(w, &bad, 1, &err) == PELT_ERR_INVALID_ARGUMENT);
}

/* With natural clumps, a droplet's texels are clumped by the cells: the
 * dirty rectangle still covers them and the mask got wet. */
static void natural_clumps_see_each_drop(pelt__water *w)
{
    const float bary[3] = {1.0f / 3, 1.0f / 3, 1.0f / 3};
    CHECK(pelt__water_drop_at(w, 10, bary, 0.3f, 1.0f, NULL) == PELT_OK);
    unsigned r[4];
    CHECK(pelt__water_take_dirty(w, r));
    CHECK(r[0] < r[2] && r[1] < r[3]);
    CHECK(wet_sum(pelt__water_mask(w)) > 0.0f);
    pelt_rain rain = {0};
    rain.seed = 3;
    pelt__water_random_drops(w, &rain, 5);
    CHECK(pelt__water_take_dirty(w, r));
}

static void ray(void) { with_water(0.0f, ray_drop); }
static void drying(void) { with_water(0.0f, drying_and_clearing); }
static void clumps(void) { with_water(0.25f, natural_clumps_see_each_drop); }

int main(void)
{
    RUN(ray);
    RUN(drying);
    RUN(clumps);
    return check_summary();
}
