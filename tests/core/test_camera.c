/* The orbit camera and rays through pixels (core/camera.c). */
#include "support/check.h"

#include "pelt/render.h"

#include <math.h>
#include <string.h>

static pelt_view view_of(float yaw, float pitch, float distance, unsigned w, unsigned h)
{
    pelt_view v;
    memset(&v, 0, sizeof v);
    pelt_camera c = {yaw, pitch, distance, 40.0f, {0.5f, -0.25f, 1.0f}};
    pelt_camera_to_view(&c, (float)w / (float)h, &v);
    v.width = w;
    v.height = h;
    return v;
}

/* Distance from point p to the line o + t d (d unit). */
static float line_distance(const float o[3], const float d[3], const float p[3])
{
    float q[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]};
    float t = q[0] * d[0] + q[1] * d[1] + q[2] * d[2];
    float r[3] = {q[0] - t * d[0], q[1] - t * d[1], q[2] - t * d[2]};
    return sqrtf(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
}

static void centre_pixel_ray_passes_through_the_target(void)
{
    /* An odd size has a pixel whose centre is the image centre. */
    pelt_view v = view_of(30.0f, 25.0f, 4.0f, 101, 75);
    float o[3], d[3];
    CHECK(pelt_view_pixel_ray(&v, 50.0f, 37.0f, o, d));
    const float target[3] = {0.5f, -0.25f, 1.0f};
    CHECK_NEAR(line_distance(o, d, target), 0.0, 1e-4);
    /* It starts at the eye's side and points at the target. */
    float to[3] = {target[0] - o[0], target[1] - o[1], target[2] - o[2]};
    CHECK(to[0] * d[0] + to[1] * d[1] + to[2] * d[2] > 0.0f);
}

static void top_edge_ray_leaves_at_half_the_field_of_view(void)
{
    pelt_view v = view_of(0.0f, 0.0f, 4.0f, 100, 100);
    float oc[3], dc[3], ot[3], dt[3];
    CHECK(pelt_view_pixel_ray(&v, 49.5f, 49.5f, oc, dc)); /* centre (between pixels) */
    CHECK(pelt_view_pixel_ray(&v, 49.5f, -0.5f, ot, dt)); /* top edge */
    float cosang = dc[0] * dt[0] + dc[1] * dt[1] + dc[2] * dt[2];
    CHECK_NEAR(acosf(cosang) * 180.0f / 3.14159265f, 20.0, 1e-2);
    CHECK(dt[1] > dc[1]); /* row 0 is the top: the ray tilts up */
}

static void model_transform_is_undone(void)
{
    pelt_view v = view_of(0.0f, 0.0f, 4.0f, 101, 101);
    /* The mesh moved 1 along +X: in mesh coordinates the ray through the
     * centre passes through target - (1, 0, 0). */
    v.model[12] = 1.0f;
    float o[3], d[3];
    CHECK(pelt_view_pixel_ray(&v, 50.0f, 50.0f, o, d));
    const float p[3] = {-0.5f, -0.25f, 1.0f};
    CHECK_NEAR(line_distance(o, d, p), 0.0, 1e-4);
}

static void singular_view_is_refused(void)
{
    pelt_view v = view_of(0.0f, 0.0f, 4.0f, 10, 10);
    memset(v.model, 0, sizeof v.model);
    float o[3], d[3];
    CHECK(!pelt_view_pixel_ray(&v, 5.0f, 5.0f, o, d));
    v = view_of(0.0f, 0.0f, 4.0f, 10, 10);
    v.width = 0;
    CHECK(!pelt_view_pixel_ray(&v, 5.0f, 5.0f, o, d));
}

int main(void)
{
    RUN(centre_pixel_ray_passes_through_the_target);
    RUN(top_edge_ray_leaves_at_half_the_field_of_view);
    RUN(model_transform_is_undone);
    RUN(singular_view_is_refused);
    return check_summary();
}
