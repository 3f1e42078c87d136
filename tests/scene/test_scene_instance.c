/* The scene runner (pelt/scene_instance.h): a scene becomes mesh, atlas,
 * fur, colour, water and a clock, with no GL anywhere in this program. */
#include "pelt/pelt.h"
#include "support/check.h"

#include <stdlib.h>
#include <string.h>

static pelt_scene small_scene(void)
{
    pelt_scene s;
    pelt_scene_defaults(&s);
    s.mesh.major_segments = 24;
    s.mesh.minor_segments = 12;
    s.fur.look.texture_size = 32;
    s.output.width = 64;
    s.output.height = 48;
    return s;
}

static pelt_scene_instance *make(const pelt_scene *s, const pelt_scene_instance_desc *d,
                                 pelt_error *err)
{
    pelt_scene_instance *inst = NULL;
    pelt_status st = pelt_scene_instantiate(s, d, &inst, err);
    if (st != PELT_OK) fprintf(stderr, "  %s\n", err->message);
    return inst;
}

static float wet_fraction(pelt_fur *fur)
{
    unsigned n = pelt_fur_mask_size(fur);
    uint8_t *px = malloc((size_t)n * n * 4);
    pelt_fur_mask_picture(fur, px);
    size_t wet = 0;
    for (size_t i = 0; i < (size_t)n * n; i++) wet += px[4 * i + 2] > 0;
    free(px);
    return (float)wet / (float)((size_t)n * n);
}

static void default_scene_makes_the_table1_torus(void)
{
    pelt_scene s;
    pelt_scene_defaults(&s);
    s.fur.look.texture_size = 32; /* speed; the mesh is what is checked */
    pelt_error err = {0};
    pelt_scene_instance *inst = make(&s, NULL, &err);
    CHECK(inst != NULL);
    if (!inst) return;
    CHECK(pelt_mesh_get_stats(pelt_scene_instance_mesh(inst)).triangle_count == 9360);
    pelt_fur_desc fd = pelt_fur_get_desc(pelt_scene_instance_fur(inst));
    CHECK(fd.layers == 32);
    CHECK(fd.wet.mask_size == 256);
    /* A scene that sets nothing gives the library's defaults: the same
       desc as a fur made from a zero desc on the same mesh. */
    pelt_fur_desc zero = {0};
    zero.look.texture_size = 32;
    pelt_fur *direct = NULL;
    CHECK(pelt_fur_create(pelt_scene_instance_mesh(inst), &zero, &direct, &err) == PELT_OK);
    if (direct) {
        pelt_fur_desc dd = pelt_fur_get_desc(direct);
        size_t rows = 0;
        const pelt_param *p = pelt_fur_params(&rows);
        for (size_t i = 0; i < rows; i++) {
            size_t bytes = p[i].type == PELT_PARAM_FLOAT ? p[i].count * sizeof(float)
                           : p[i].type == PELT_PARAM_BOOL ? sizeof(bool) : sizeof(unsigned);
            bool same = memcmp((const char *)&fd + p[i].offset, (const char *)&dd + p[i].offset, bytes) == 0;
            if (!same) fprintf(stderr, "  %s differs\n", p[i].name);
            CHECK(same);
        }
    }
    pelt_fur_destroy(direct);
    pelt_view v = pelt_scene_instance_view(inst);
    CHECK(v.width == 800 && v.height == 600);
    CHECK(pelt_scene_instance_time(inst) == 0.0f);
    pelt_scene_instance_destroy(inst);
    pelt_scene_free(&s);
}

static void advance_moves_the_clock_and_the_turntable(void)
{
    pelt_scene s = small_scene();
    s.animation.turntable = 90.0f; /* degrees per second */
    pelt_error err = {0};
    pelt_scene_instance *inst = make(&s, NULL, &err);
    CHECK(inst != NULL);
    if (!inst) return;
    pelt_view v0 = pelt_scene_instance_view(inst);
    for (int i = 0; i < 30; i++) pelt_scene_instance_advance(inst, 1.0f / 30.0f);
    CHECK_NEAR(pelt_scene_instance_time(inst), 1.0f, 1e-4);
    pelt_view v1 = pelt_scene_instance_view(inst);
    /* 90 degrees about +Y in one second: x goes to -z (column-major m[8] = sin). */
    CHECK_NEAR(v0.model[0], 1.0f, 1e-5);
    CHECK_NEAR(v1.model[0], 0.0f, 1e-3);
    CHECK_NEAR(fabsf(v1.model[8]), 1.0f, 1e-3);
    pelt_scene_instance_advance(inst, -1.0f); /* ignored */
    pelt_scene_instance_advance(inst, NAN);   /* ignored */
    CHECK_NEAR(pelt_scene_instance_time(inst), 1.0f, 1e-4);
    pelt_scene_instance_destroy(inst);
    pelt_scene_free(&s);
}

static void scene_water_reaches_the_fur(void)
{
    pelt_scene s = small_scene();
    pelt_error err = {0};
    CHECK(pelt_scene_set(&s, "wetness.droplets", "[{\"center\":[0.5,0.5],\"radius\":0.2,\"wetness\":1}]",
                         &err) == PELT_OK);
    pelt_scene_instance *inst = make(&s, NULL, &err);
    CHECK(inst != NULL);
    if (!inst) return;
    float f = wet_fraction(pelt_scene_instance_fur(inst));
    printf("  wet fraction of the mask after one droplet of radius 0.2: %.3f\n", (double)f);
    CHECK(f > 0.08f && f < 0.2f); /* pi 0.2^2 = 0.126 */
    pelt_scene_instance_destroy(inst);
    pelt_scene_free(&s);
}

static void rain_waits_for_its_start(void)
{
    pelt_scene s = small_scene();
    s.wetness.rain.rate = 400.0f;
    s.wetness.rain_start = 0.5f;
    pelt_error err = {0};
    pelt_scene_instance *inst = make(&s, NULL, &err);
    CHECK(inst != NULL);
    if (!inst) return;
    pelt_fur *fur = pelt_scene_instance_fur(inst);
    CHECK(wet_fraction(fur) == 0.0f); /* no rain during the settling */
    for (int i = 0; i < 10; i++) pelt_scene_instance_advance(inst, 1.0f / 30.0f);
    CHECK(wet_fraction(fur) == 0.0f); /* t = 0.33 < start */
    for (int i = 0; i < 10; i++) pelt_scene_instance_advance(inst, 1.0f / 30.0f);
    CHECK(wet_fraction(fur) > 0.0f);
    pelt_scene_instance_destroy(inst);
    pelt_scene_free(&s);
}

static void bad_image_names_key_and_file(void)
{
    pelt_scene s = small_scene();
    strcpy(s.texture.image, PELT_TEST_DATA "/no_such_image.png");
    pelt_error err = {0};
    pelt_scene_instance *inst = (pelt_scene_instance *)1;
    CHECK(pelt_scene_instantiate(&s, NULL, &inst, &err) == PELT_ERR_IO);
    CHECK(inst == NULL);
    CHECK(strstr(err.message, "texture.image") && strstr(err.message, "no_such_image.png"));
    strcpy(s.texture.image, PELT_TEST_DATA "/meshes/tetra.off"); /* not an image */
    CHECK(pelt_scene_instantiate(&s, NULL, &inst, &err) == PELT_ERR_FORMAT);
    CHECK(strstr(err.message, "texture.image") && strstr(err.message, "tetra.off"));
    pelt_scene_free(&s);
}

/* Hooks: every allocation of the instance goes through the caller's
 * allocator and comes back; warnings reach the logger, not stderr. */
typedef struct counting { size_t allocs, frees; } counting;
static void *count_alloc(size_t n, void *user) { ((counting *)user)->allocs++; return malloc(n); }
static void count_free(void *p, void *user) { ((counting *)user)->frees++; free(p); }

typedef struct log_seen { int warnings; char last[256]; } log_seen;
static void keep_log(pelt_log_level level, const char *msg, void *user)
{
    log_seen *l = user;
    if (level == PELT_LOG_WARNING) l->warnings++;
    snprintf(l->last, sizeof l->last, "%s", msg);
}

static void hooks_see_allocations_and_warnings(void)
{
    pelt_scene s = small_scene();
    pelt_error err = {0};
    CHECK(pelt_scene_set(&s, "mesh.file", PELT_TEST_DATA "/meshes/square_one_degenerate.obj", &err) ==
          PELT_OK);
    counting c = {0};
    log_seen l = {0};
    pelt_scene_instance_desc d = {.cache_dir = "",
                                  .hooks = {{count_alloc, count_free, &c}, {keep_log, &l}}};
    pelt_scene_instance *inst = make(&s, &d, &err);
    CHECK(inst != NULL);
    if (!inst) return;
    printf("  %zu allocations through the hooks; warning: %s\n", c.allocs, l.last);
    CHECK(c.allocs >= 10); /* the instance, and the fur with all it owns */
    CHECK(l.warnings >= 1);
    CHECK(strstr(l.last, "degenerate") != NULL);
    pelt_scene_instance_destroy(inst);
    CHECK(c.frees == c.allocs);
    pelt_scene_free(&s);
}

static void drop_at_pixel_wets_where_the_torus_is_seen(void)
{
    pelt_scene s = small_scene();
    pelt_error err = {0};
    pelt_scene_instance *inst = make(&s, NULL, &err);
    CHECK(inst != NULL);
    if (!inst) return;
    CHECK(!pelt_scene_instance_drop_at_pixel(inst, 1.0f, 1.0f, 0.1f, 1.0f)); /* a corner: sky */
    CHECK(wet_fraction(pelt_scene_instance_fur(inst)) == 0.0f);
    CHECK(pelt_scene_instance_drop_at_pixel(inst, 32.0f, 40.0f, 0.1f, 1.0f)); /* front of the ring */
    CHECK(wet_fraction(pelt_scene_instance_fur(inst)) > 0.0f);
    pelt_scene_instance_destroy(inst);
    pelt_scene_free(&s);
}

/* A window orbits the camera and resizes: the view and the pixel rays
 * follow; forces and rain can be switched from outside the scene. */
static void camera_forces_and_rain_can_be_changed(void)
{
    pelt_scene s = small_scene();
    pelt_error err = {0};
    pelt_scene_instance *inst = make(&s, NULL, &err);
    CHECK(inst != NULL);
    if (!inst) return;
    pelt_camera c = pelt_scene_instance_camera(inst);
    CHECK(c.yaw == 30.0f && c.distance > 0.0f);
    c.distance *= 100.0f; /* far away: the pixel that saw the ring sees sky */
    pelt_scene_instance_set_camera(inst, &c, 128, 0);
    pelt_view v = pelt_scene_instance_view(inst);
    CHECK(v.width == 128 && v.height == 48);
    CHECK(!pelt_scene_instance_drop_at_pixel(inst, 32.0f, 40.0f, 0.1f, 1.0f));
    CHECK(pelt_scene_instance_camera(inst).distance == c.distance);
    pelt_forces f = pelt_scene_instance_forces(inst);
    CHECK(f.gravity[1] < 0.0f);
    f.gravity[1] = 0.0f;
    f.wind[0] = 5.0f;
    pelt_scene_instance_set_forces(inst, &f);
    f = pelt_scene_instance_forces(inst);
    CHECK(f.gravity[1] == 0.0f && f.wind[0] == 5.0f);
    pelt_scene_instance_set_rain_rate(inst, 400.0f);
    pelt_scene_instance_advance(inst, 0.1f);
    CHECK(wet_fraction(pelt_scene_instance_fur(inst)) > 0.0f);
    pelt_scene_instance_destroy(inst);
    pelt_scene_free(&s);
}

/* animation.name finds the tube's "bend" and plays it (test_skeleton and
 * test_skin_render check the poses); mesh.up turns +Z to +Y; a missing
 * animation is refused by name. */
static void animation_and_up_axis(void)
{
    pelt_scene s = small_scene();
    s.mesh.shape = PELT_SHAPE_FILE;
    strcpy(s.mesh.file, PELT_TEST_DATA "/skin/tube.gltf");
    strcpy(s.animation.name, "bend");
    s.mesh.up = PELT_UP_POS_Z;
    pelt_error err = {0};
    pelt_scene_instance_desc d = {.cache_dir = "", .settle_seconds = -1.0f};
    pelt_scene_instance *inst = make(&s, &d, &err);
    CHECK(inst != NULL);
    if (inst) {
        pelt_view v = pelt_scene_instance_view(inst);
        /* +Z of the mesh is +Y of the world. */
        CHECK_NEAR(v.model[8], 0.0, 1e-6);
        CHECK_NEAR(v.model[9], 1.0, 1e-6);
        CHECK_NEAR(v.model[10], 0.0, 1e-6);
        pelt_scene_instance_advance(inst, 1.0f); /* upper bent by 90 degrees */
        const pelt_mesh *m = pelt_scene_instance_mesh(inst);
        CHECK(pelt_mesh_skin_info(m).animations == 1);
        pelt_scene_instance_destroy(inst);
    }
    strcpy(s.animation.name, "walk");
    inst = (pelt_scene_instance *)1;
    CHECK(pelt_scene_instantiate(&s, &d, &inst, &err) == PELT_ERR_INVALID_ARGUMENT);
    CHECK(inst == NULL);
    CHECK(strstr(err.message, "animation.name") && strstr(err.message, "tube.gltf") &&
          strstr(err.message, "no animation 'walk'"));
    pelt_scene_free(&s);
}

int main(void)
{
    RUN(default_scene_makes_the_table1_torus);
    RUN(advance_moves_the_clock_and_the_turntable);
    RUN(scene_water_reaches_the_fur);
    RUN(rain_waits_for_its_start);
    RUN(bad_image_names_key_and_file);
    RUN(hooks_see_allocations_and_warnings);
    RUN(drop_at_pixel_wets_where_the_torus_is_seen);
    RUN(camera_forces_and_rain_can_be_changed);
    RUN(animation_and_up_axis);
    return check_summary();
}
