/* Skinned meshes (pelt/animation.h, core/mesh/skeleton.c) by what they
 * are for: the pose at any time equals the keyframes interpolated by hand,
 * the fur's tips trail the motion of a bending bone, and broken files get
 * a clear error. The tube of tests/data/skin (make-skinned-tube.py): two
 * bones, "upper" turning about +Z at y = 1, 0 -> 90 -> 0 degrees over 2 s. */
#include "support/check.h"

#include "pelt/animation.h"
#include "pelt/dynamics.h"
#include "pelt/fur.h"

#include "core/fur/fur_gpu.h"
#include "core/mesh/skeleton.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SKIN PELT_TEST_DATA "/skin/"

static pelt_mesh *tube;

/* Where the tube's rest point p goes with upper turned by `deg` about +Z
 * at (0, 1, 0): the weight of upper rises linearly from y = 0.8 to 1.2. */
static void by_hand(const float p[3], float deg, float out[3])
{
    float a = deg * 3.14159265f / 180.0f, w = fminf(fmaxf((p[1] - 0.8f) / 0.4f, 0.0f), 1.0f);
    float x = p[0], y = p[1] - 1.0f;
    float turned[3] = {cosf(a) * x - sinf(a) * y, sinf(a) * x + cosf(a) * y + 1.0f, p[2]};
    for (int k = 0; k < 3; k++) out[k] = (1.0f - w) * p[k] + w * turned[k];
}

static void the_file_brings_its_skeleton(void)
{
    pelt_skin_info s = pelt_mesh_skin_info(tube);
    CHECK(s.bones == 2);
    CHECK(s.animations == 1);
    CHECK(s.skinned_vertices == pelt_mesh_get_data(tube).vertex_count);
    pelt_animation_info a;
    CHECK(pelt_mesh_animation(tube, 0, &a));
    CHECK(!strcmp(a.name, "bend"));
    CHECK_NEAR(a.duration, 2.0, 1e-6);
    CHECK(!pelt_mesh_animation(tube, 1, &a));
    size_t i = 9;
    CHECK(pelt_mesh_find_animation(tube, "bend", &i, NULL) == PELT_OK && i == 0);
    CHECK(pelt_mesh_find_animation(tube, "0", &i, NULL) == PELT_OK && i == 0);
    pelt_error err = {0};
    CHECK(pelt_mesh_find_animation(tube, "walk", &i, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "no animation 'walk'") && strstr(err.message, "0 'bend'"));
    CHECK(pelt_mesh_find_animation(tube, "1", &i, &err) == PELT_ERR_INVALID_ARGUMENT);
}

/* Linear keys and slerp: 45 degrees half-way up and half-way down, 90 at
 * the top; looping and negative times wrap. */
static void the_pose_is_the_keys_interpolated(void)
{
    const pelt_mesh_data m = pelt_mesh_get_data(tube);
    size_t n = m.vertex_count;
    float *p = malloc(n * 10 * sizeof(float));
    if (!p) return;
    float *nrm = p + 3 * n, *tan = p + 6 * n;
    static const struct { float t, deg; } cases[] = {{0.0f, 0.0f}, {0.5f, 45.0f}, {1.0f, 90.0f}, {1.5f, 45.0f},
                                                      {2.5f, 45.0f}, {-1.5f, 45.0f}, {0.25f, 22.5f}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        CHECK(pelt_mesh_pose(tube, 0, cases[c].t, p, nrm, tan, NULL) == PELT_OK);
        double worst = 0.0, unit = 0.0;
        for (size_t v = 0; v < n; v++) {
            float want[3];
            by_hand(m.positions + 3 * v, cases[c].deg, want);
            for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(p[3 * v + k] - want[k]));
            float *q = nrm + 3 * v;
            unit = fmax(unit, fabs(sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) - 1.0));
        }
        printf("  t = %5.2f s: %4.1f degrees, worst |pose - by hand| = %.2g\n", (double)cases[c].t,
               (double)cases[c].deg, worst);
        CHECK(worst < 1e-4);
        CHECK(unit < 1e-4);
    }
    /* The normal at the top cap's centre turns with the bone. */
    CHECK(pelt_mesh_pose(tube, 0, 1.0f, p, nrm, tan, NULL) == PELT_OK);
    int centres = 0;
    for (size_t v = 0; v < n; v++)
        if (m.positions[3 * v + 1] > 1.999f && fabsf(m.positions[3 * v]) < 1e-6f && fabsf(m.positions[3 * v + 2]) < 1e-6f) {
            float *q = nrm + 3 * v;
            CHECK_NEAR(q[0], -1.0, 1e-3); /* +Y turned 90 degrees about +Z */
            CHECK_NEAR(q[1], 0.0, 1e-3);
            centres++;
        }
    CHECK(centres == 1);
    pelt_error err = {0};
    CHECK(pelt_mesh_pose(tube, 1, 0.0f, p, nrm, tan, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(pelt_mesh_pose(tube, 0, NAN, p, nrm, tan, &err) == PELT_ERR_INVALID_ARGUMENT);
    free(p);
}

/* The keys themselves: linear vectors, slerp the short way round, held
 * outside the keys, the rest value without keys. */
static void keys_interpolate_by_hand(void)
{
    const pelt__vec_key v[2] = {{1.0f, {0, 0, 0}}, {3.0f, {2, 4, -2}}};
    const float rest[3] = {7, 7, 7};
    float out[4];
    pelt__sample_vec(v, 2, 1.5f, rest, out);
    CHECK_NEAR(out[0], 0.5, 1e-6);
    CHECK_NEAR(out[1], 1.0, 1e-6);
    CHECK_NEAR(out[2], -0.5, 1e-6);
    pelt__sample_vec(v, 2, 0.0f, rest, out);
    CHECK_NEAR(out[1], 0.0, 1e-6);
    pelt__sample_vec(v, 2, 9.0f, rest, out);
    CHECK_NEAR(out[1], 4.0, 1e-6);
    pelt__sample_vec(v, 0, 2.0f, rest, out);
    CHECK_NEAR(out[1], 7.0, 1e-6);
    /* 0 and 120 degrees about +X, the second given as -q: 60 half-way. */
    float s = sinf(1.0471976f), c = cosf(1.0471976f);
    const pelt__quat_key q[2] = {{0.0f, {0, 0, 0, 1}}, {1.0f, {-s, 0, 0, -c}}};
    const float qrest[4] = {0, 0, 0, 1};
    pelt__sample_quat(q, 2, 0.5f, qrest, out);
    CHECK_NEAR(out[0], sinf(0.5235988f), 1e-5);
    CHECK_NEAR(out[3], cosf(0.5235988f), 1e-5);
}

/* The fur on the bending tube: while upper turns, the tips of its strands
 * lag behind the motion of their roots; held still, they come back. */
static void tips_trail_a_turning_bone(void)
{
    pelt_fur *fur = NULL;
    const pelt_fur_desc d = {.look.texture_size = 32, .length = 0.2f};
    CHECK(pelt_fur_create(tube, &d, &fur, NULL) == PELT_OK);
    if (!fur) return;
    const pelt_mesh_data m = pelt_mesh_get_data(tube);
    size_t n = m.vertex_count;
    float *p = malloc(n * 10 * sizeof(float));
    if (!p) {
        pelt_fur_destroy(fur);
        return;
    }
    float *nrm = p + 3 * n, *tan = p + 6 * n;
    const pelt_forces still = {0}; /* no gravity: only the motion bends the fur */
    double lag[2];
    for (int phase = 0; phase < 2; phase++) {
        /* phase 0: turning from 0 towards 45 degrees; phase 1: held at 45. */
        for (int i = 0; i <= 30; i++) {
            float t = phase == 0 ? (float)i / 60.0f : 0.5f;
            pelt_mesh_pose(tube, 0, t, p, nrm, tan, NULL);
            pelt_fur_set_pose(fur, p, nrm, tan, NULL);
            pelt_fur_step(fur, phase == 0 ? 1.0f / 60.0f : 0.1f, &still);
        }
        pelt__fur_snapshot fs;
        pelt__fur_gpu_snapshot(fur, &fs);
        const float *tips = fs.tips;
        /* Upper's vertices move along +Z x (p - (0, 1, 0)); a lagging tip
           leans against that. */
        double sum = 0.0;
        int count = 0;
        for (size_t v = 0; v < n; v++) {
            if (m.positions[3 * v + 1] < 1.5f) continue;
            const float *r = p + 3 * v, *o = tips + 3 * v;
            float motion[3] = {-(r[1] - 1.0f), r[0], 0.0f};
            float ml = sqrtf(motion[0] * motion[0] + motion[1] * motion[1]);
            float ol = sqrtf(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
            if (!(ml > 0.0f && ol > 0.0f)) continue;
            sum += (o[0] * motion[0] + o[1] * motion[1]) / (ml * ol);
            count++;
        }
        lag[phase] = count ? sum / count : 0.0;
    }
    printf("  tips along the roots' motion: %.3f while turning, %.3f held still\n", lag[0], lag[1]);
    CHECK(lag[0] < -0.05);
    CHECK(fabs(lag[1]) < 0.5 * fabs(lag[0]));
    pelt_error err = {0};
    p[0] = NAN;
    CHECK(pelt_fur_set_pose(fur, p, nrm, tan, &err) == PELT_ERR_INVALID_ARGUMENT);
    free(p);
    pelt_fur_destroy(fur);
}

static void broken_files_get_a_clear_error(void)
{
    static const struct { const char *file, *needle; } bad[] = {
        {SKIN "tube_bad_weights.gltf", "vertex 5 of mesh 'tube' has bone weights summing to 0"},
        {SKIN "tube_bad_key.gltf", "animation 'bend', node 'upper': rotation key 1 is not a finite rotation"},
        {SKIN "tube_bad_joint.gltf", "vertex 9 of mesh 'tube' has bone weights summing to 0"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        pelt_mesh *m = NULL;
        pelt_error err = {0};
        CHECK(pelt_mesh_load(bad[i].file, &m, &err) == PELT_ERR_FORMAT);
        CHECK(m == NULL);
        CHECK(strstr(err.message, bad[i].needle) != NULL);
        CHECK(strstr(err.message, bad[i].file) != NULL);
        if (!strstr(err.message, bad[i].needle)) fprintf(stderr, "  got: %s\n", err.message);
    }
    /* A mesh without a skeleton has no pose. */
    pelt_mesh *sq = NULL;
    CHECK(pelt_mesh_square(1.0f, 2, &sq, NULL) == PELT_OK);
    float buf[9 * 10];
    pelt_error err = {0};
    CHECK(pelt_mesh_pose(sq, 0, 0.0f, buf, buf + 27, buf + 54, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(pelt_mesh_skin_info(sq).bones == 0);
    pelt_mesh_destroy(sq);
}

int main(void)
{
    pelt_error err = {0};
    if (pelt_mesh_load(SKIN "tube.gltf", &tube, &err) != PELT_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    RUN(the_file_brings_its_skeleton);
    RUN(the_pose_is_the_keys_interpolated);
    RUN(keys_interpolate_by_hand);
    RUN(tips_trail_a_turning_bone);
    RUN(broken_files_get_a_clear_error);
    pelt_mesh_destroy(tube);
    return check_summary();
}
