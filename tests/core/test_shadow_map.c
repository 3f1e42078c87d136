/* Deep opacity maps' C references (core/fur/shadow_map.h): what the light
 * pass accumulates and the receivers read back. */
#include "support/check.h"

#include "core/base/rng.h"
#include "core/fur/shadow_map.h"

#include <math.h>
#include <string.h>

/* A texel's slice sums after fragments at positions k[i] of coverage a[i]. */
static void accumulate(const float *k, const float *a, int n, unsigned slices, float sums[PELT_SHADOW_MAX_SLICES])
{
    memset(sums, 0, PELT_SHADOW_MAX_SLICES * sizeof *sums);
    for (int i = 0; i < n; i++)
        for (unsigned j = 0; j < slices; j++)
            sums[j] += pelt__shadow_sigma(a[i]) * pelt__shadow_slice_weight(k[i], j, slices);
}

/* Transmittance falls monotonically with depth into the fur, from 1 in
 * front of all of it to the product of the layers' (1 - alpha) behind. */
static void transmittance_falls_with_depth(void)
{
    for (unsigned slices = 1; slices <= PELT_SHADOW_MAX_SLICES; slices++) {
        pelt__rng rng = pelt__rng_seed(slices, 7);
        float k[16], a[16], sums[PELT_SHADOW_MAX_SLICES];
        double all = 1.0;
        for (int i = 0; i < 16; i++) {
            k[i] = pelt__rng_float(&rng) * ((float)slices + 2.0f) - 1.0f;
            a[i] = pelt__rng_float(&rng);
            all *= 1.0 - fmin(a[i], 0.98);
        }
        accumulate(k, a, 16, slices, sums);
        float prev = 1.0f;
        int rises = 0;
        for (float x = -1.0f; x <= (float)slices + 1.0f; x += 0.01f) {
            float t = pelt__shadow_transmittance(pelt__shadow_opacity(sums, slices, x), 1.0f);
            if (t > prev + 1e-6f) rises++;
            prev = t;
        }
        CHECK(rises == 0);
        CHECK_NEAR(pelt__shadow_transmittance(pelt__shadow_opacity(sums, slices, -0.5f), 1.0f), 1.0, 1e-6);
        CHECK_NEAR(pelt__shadow_transmittance(pelt__shadow_opacity(sums, slices, (float)slices), 1.0f), all,
                   1e-4 * (1.0 + all));
    }
}

/* Hair well in front of a receiver shades it fully, hair well behind not
 * at all (one slice apart is the resolution). */
static void slices_separate_front_from_behind(void)
{
    const unsigned slices = 4;
    float k[1] = {1.2f}, a[1] = {0.6f}, sums[PELT_SHADOW_MAX_SLICES];
    accumulate(k, a, 1, slices, sums);
    CHECK_NEAR(pelt__shadow_opacity(sums, slices, 0.1f), 0.0, 1e-6);
    CHECK_NEAR(pelt__shadow_opacity(sums, slices, 3.0f), pelt__shadow_sigma(0.6f), 1e-6);
    CHECK_NEAR(pelt__shadow_transmittance(pelt__shadow_opacity(sums, slices, 4.0f), 1.0f), 0.4, 1e-5);
    /* Density scales the opacity. */
    CHECK_NEAR(pelt__shadow_transmittance(pelt__shadow_opacity(sums, slices, 4.0f), 2.0f), 0.16, 1e-5);
}

/* The light's frame puts the sphere inside the maps, depth growing away
 * from the light, and has a camera's winding. */
static void light_frame_fits_the_sphere(void)
{
    const float c[3] = {1.0f, -2.0f, 0.5f}, r = 1.5f, dirs[3][3] = {{0.5f, 1.0f, 0.8f}, {0, 1, 0}, {-1, 0.1f, 0}};
    for (int t = 0; t < 3; t++) {
        float tex[16], clip[16];
        pelt__shadow_light_frame(c, r, dirs[t], 2.0f, tex, clip);
        float len = sqrtf(dirs[t][0] * dirs[t][0] + dirs[t][1] * dirs[t][1] + dirs[t][2] * dirs[t][2]);
        float l[3] = {dirs[t][0] / len, dirs[t][1] / len, dirs[t][2] / len};
        for (int s = -1; s <= 1; s += 2) { /* the sphere's points nearest and farthest from the light */
            float p[3] = {c[0] + s * r * l[0], c[1] + s * r * l[1], c[2] + s * r * l[2]};
            float q[3];
            for (int i = 0; i < 3; i++) q[i] = tex[i] * p[0] + tex[4 + i] * p[1] + tex[8 + i] * p[2] + tex[12 + i];
            CHECK_NEAR(q[0], 0.5, 1e-5);
            CHECK_NEAR(q[1], 0.5, 1e-5);
            CHECK_NEAR(q[2], s > 0 ? 0.0 : 2.0 / 3.0, 1e-5);
            float w = clip[2] * p[0] + clip[6] * p[1] + clip[10] * p[2] + clip[14];
            CHECK_NEAR(w, 2.0 * q[2] - 1.0, 1e-5);
        }
        /* Across the light: the sphere's rim reaches the maps' edges. */
        float x[3] = {tex[0], tex[4], tex[8]};
        float xl = sqrtf(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        CHECK_NEAR(xl * 2.0f * r, 1.0, 1e-5);
        CHECK_NEAR(x[0] * l[0] + x[1] * l[1] + x[2] * l[2], 0.0, 1e-6);
    }
}

static void defaults_fill_in(void)
{
    pelt_shadow_desc d = pelt__shadow_resolved(&(pelt_shadow_desc){.enabled = true});
    CHECK(d.map_size == 512 && d.slices == 4);
    CHECK(d.softness == 1.0f && d.depth == 2.0f && d.density == 1.0f);
    CHECK(pelt__shadow_resolved(&(pelt_shadow_desc){.softness = -1.0f}).softness == 0.0f);
    pelt_ground_desc g = pelt__ground_resolved(NULL);
    CHECK(!g.enabled && g.size == 4.0f && g.color[0] > 0.0f);
}

int main(void)
{
    RUN(transmittance_falls_with_depth);
    RUN(slices_separate_front_from_behind);
    RUN(light_frame_fits_the_sphere);
    RUN(defaults_fill_in);
    return check_summary();
}
