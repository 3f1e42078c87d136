/* The orbit camera and rays through pixels (core/base/camera.c). */
#include "support/check.h"

#include "pelt/render.h"
#include "core/base/vec.h"

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

/* ---- pelt_camera_frame ---------------------------------------------------- */

enum { FRAME_POINTS = 2000 };
static float frame_pos[FRAME_POINTS * 3], frame_reach[FRAME_POINTS];

/* Points on an ellipsoid with semi-axes a along the direction at `yaw`
 * degrees in XZ, b across it in XZ, c along Y, centred at `centre`. */
static void ellipsoid_points(float a, float b, float c, float yaw, const float centre[3])
{
    float y = yaw * 3.14159265f / 180.0f;
    float ax = sinf(y), az = cosf(y); /* the long axis, yaw from +Z towards +X */
    for (int i = 0; i < FRAME_POINTS; i++) {
        /* A spiral over the sphere: even cover without randomness. */
        float t = ((float)i + 0.5f) / FRAME_POINTS;
        float cz = 1.0f - 2.0f * t, sz = sqrtf(fmaxf(0.0f, 1.0f - cz * cz));
        float ph = 2.39996323f * (float)i;
        float u = a * sz * cosf(ph), w = b * sz * sinf(ph), h = c * cz;
        frame_pos[3 * i + 0] = centre[0] + u * ax + w * az;
        frame_pos[3 * i + 1] = centre[1] + h;
        frame_pos[3 * i + 2] = centre[2] + u * az - w * ax;
        frame_reach[i] = 0.05f;
    }
}

/* The largest |NDC x| and |NDC y| of the points grown by their reach (four
 * points across each sphere in the view plane), and whether every one is
 * in front of the near plane. */
static bool ndc_extent(const pelt_camera *c, float aspect, float *ex, float *ey)
{
    pelt_view v;
    memset(&v, 0, sizeof v);
    pelt_camera_to_view(c, aspect, &v);
    float vp[16];
    pelt__mat4_mul(vp, v.proj, v.view);
    /* The view's right and up in world space: rows of the view matrix. */
    pelt_vec3 right = v3(v.view[0], v.view[4], v.view[8]), up = v3(v.view[1], v.view[5], v.view[9]);
    bool front = true;
    *ex = *ey = 0.0f;
    for (int i = 0; i < FRAME_POINTS; i++) {
        pelt_vec3 p = v3_load(frame_pos + 3 * i);
        pelt_vec3 offs[4] = {right, v3_scale(right, -1.0f), up, v3_scale(up, -1.0f)};
        for (int k = 0; k < 4; k++) {
            pelt_vec3 q = v3_mad(p, offs[k], frame_reach[i]);
            float clip[4];
            for (int r = 0; r < 4; r++)
                clip[r] = vp[r] * q.x + vp[4 + r] * q.y + vp[8 + r] * q.z + vp[12 + r];
            if (!(clip[3] > 0.0f) || clip[2] < -clip[3]) front = false;
            *ex = fmaxf(*ex, fabsf(clip[0] / clip[3]));
            *ey = fmaxf(*ey, fabsf(clip[1] / clip[3]));
        }
    }
    return front;
}

static void framing_fits_the_points_tightly_in_both_fields_of_view(void)
{
    const float centre[3] = {2.0f, -1.0f, 3.0f};
    const float aspects[] = {4.0f / 3.0f, 0.5f, 2.5f};
    for (int tall = 0; tall < 2; tall++)
        for (int k = 0; k < 3; k++) {
            ellipsoid_points(1.0f, 0.6f, tall ? 2.0f : 0.5f, 70.0f, centre);
            pelt_camera c = {30.0f, 25.0f, 4.2f, 40.0f, {0, 0, 0}};
            CHECK(pelt_camera_frame(&c, frame_pos, frame_reach, FRAME_POINTS, aspects[k], 0.0f));
            float ex, ey;
            CHECK(ndc_extent(&c, aspects[k], &ex, &ey));
            printf("  %s, aspect %.2f: distance %.3f, NDC extent x %.4f y %.4f\n",
                   tall ? "tall" : "flat", (double)aspects[k], (double)c.distance, (double)ex, (double)ey);
            /* Inside, and touching the tighter of the two edges. */
            CHECK(ex <= 1.0f + 1e-4f && ey <= 1.0f + 1e-4f);
            CHECK(fmaxf(ex, ey) > 0.97f);
            /* A margin moves the camera back by its share. */
            pelt_camera m = {30.0f, 25.0f, 4.2f, 40.0f, {0, 0, 0}};
            CHECK(pelt_camera_frame(&m, frame_pos, frame_reach, FRAME_POINTS, aspects[k], 0.1f));
            CHECK_NEAR(m.distance, c.distance * 1.1f, 1e-4 * c.distance);
        }
}

static void framing_aims_at_the_bounding_sphere_centre(void)
{
    /* An ellipsoid is symmetric about its centre, and so is its smallest
     * bounding sphere; reach grows every point alike. */
    const float centre[3] = {-3.0f, 0.5f, 7.0f};
    ellipsoid_points(1.2f, 0.4f, 0.7f, 10.0f, centre);
    pelt_camera c = {30.0f, 25.0f, 4.2f, 40.0f, {0, 0, 0}};
    CHECK(pelt_camera_frame(&c, frame_pos, frame_reach, FRAME_POINTS, 1.0f, 0.0f));
    for (int k = 0; k < 3; k++) CHECK_NEAR(c.target[k], centre[k], 0.02);
    /* One far point with a large reach pulls the centre towards it. */
    frame_reach[0] = 3.0f;
    pelt_camera d = c;
    CHECK(pelt_camera_frame(&d, frame_pos, frame_reach, FRAME_POINTS, 1.0f, 0.0f));
    pelt_vec3 towards = v3_sub(v3_load(frame_pos), v3_load(centre));
    CHECK(v3_dot(v3_sub(v3_load(d.target), v3_load(centre)), towards) > 0.0f);
}

/* The yaw is 45 degrees off the footprint's long axis, nearest the given
 * yaw; pitch and fov are kept. */
static void framing_takes_a_three_quarter_view_about_up(void)
{
    const float origin[3] = {0, 0, 0};
    const float axes[] = {0.0f, 20.0f, 45.0f, 90.0f, 130.0f};
    for (int k = 0; k < 5; k++) {
        ellipsoid_points(1.5f, 0.5f, 0.6f, axes[k], origin);
        pelt_camera c = {30.0f, 25.0f, 4.2f, 40.0f, {0, 0, 0}};
        CHECK(pelt_camera_frame(&c, frame_pos, frame_reach, FRAME_POINTS, 4.0f / 3.0f, 0.0f));
        float off = fmodf(c.yaw - axes[k] + 720.0f, 90.0f);
        float from_start = fabsf(c.yaw - 30.0f);
        printf("  long axis at yaw %5.1f: camera yaw %6.2f\n", (double)axes[k], (double)c.yaw);
        CHECK_NEAR(off, 45.0, 0.5);
        CHECK(from_start <= 45.5f);
        CHECK(c.pitch == 25.0f && c.fov_y == 40.0f);
    }
    /* A round footprint has no long axis: the yaw stays. */
    ellipsoid_points(1.0f, 1.0f, 0.3f, 0.0f, origin);
    pelt_camera c = {-70.0f, 10.0f, 4.2f, 40.0f, {0, 0, 0}};
    CHECK(pelt_camera_frame(&c, frame_pos, NULL, FRAME_POINTS, 1.0f, 0.0f));
    CHECK(c.yaw == -70.0f && c.pitch == 10.0f);
}

static void framing_refuses_bad_input(void)
{
    const float origin[3] = {0, 0, 0};
    ellipsoid_points(1.0f, 1.0f, 1.0f, 0.0f, origin);
    pelt_camera c = {30.0f, 25.0f, 4.2f, 40.0f, {1, 2, 3}}, keep = c;
    CHECK(!pelt_camera_frame(&c, frame_pos, NULL, 0, 1.0f, 0.0f));
    CHECK(!pelt_camera_frame(&c, frame_pos, NULL, FRAME_POINTS, 0.0f, 0.0f));
    CHECK(!pelt_camera_frame(&c, frame_pos, NULL, FRAME_POINTS, 1.0f, -1.0f));
    frame_pos[7] = NAN;
    CHECK(!pelt_camera_frame(&c, frame_pos, NULL, FRAME_POINTS, 1.0f, 0.0f));
    frame_pos[7] = 0.0f;
    frame_reach[3] = -1.0f;
    CHECK(!pelt_camera_frame(&c, frame_pos, frame_reach, FRAME_POINTS, 1.0f, 0.0f));
    CHECK(!memcmp(&c, &keep, sizeof c));
    /* One bare point: a camera still comes out, aimed at it. */
    const float one[3] = {5, 6, 7};
    CHECK(pelt_camera_frame(&c, one, NULL, 1, 1.0f, 0.0f));
    CHECK(c.distance > 0.0f && c.target[0] == 5.0f && c.target[2] == 7.0f);
}

int main(void)
{
    RUN(centre_pixel_ray_passes_through_the_target);
    RUN(top_edge_ray_leaves_at_half_the_field_of_view);
    RUN(model_transform_is_undone);
    RUN(singular_view_is_refused);
    RUN(framing_fits_the_points_tightly_in_both_fields_of_view);
    RUN(framing_aims_at_the_bounding_sphere_centre);
    RUN(framing_takes_a_three_quarter_view_about_up);
    RUN(framing_refuses_bad_input);
    return check_summary();
}
