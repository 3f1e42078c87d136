/* The orbit camera and rays through pixels: view math, no GL. */
#include "pelt/camera.h"

#include "core/base/vec.h"

#include <string.h>

void pelt_camera_to_view(const pelt_camera *c, float aspect, pelt_view *v)
{
    const float deg = 3.14159265358979f / 180.0f;
    float yaw = c->yaw * deg, pitch = c->pitch * deg;
    pelt_vec3 target = v3_load(c->target);
    pelt_vec3 dir = v3(cosf(pitch) * sinf(yaw), sinf(pitch), cosf(pitch) * cosf(yaw));
    pelt_vec3 eye = v3_mad(target, dir, c->distance);
    pelt__mat4_look_at(v->view, eye, target, v3(0.0f, 1.0f, 0.0f));
    float znear = c->distance * 0.02f, zfar = c->distance * 10.0f;
    pelt__mat4_perspective(v->proj, c->fov_y * deg, aspect, znear, zfar);
    v3_store(v->eye, eye);
    pelt__mat4_identity(v->model);
}

/* ---- framing: pelt_camera_frame ---------------------------------------- */

static float reach_of(const float *reach, size_t i) { return reach ? reach[i] : 0.0f; }

/* The largest |p - c| + reach over the points, and the point reaching it. */
static float sphere_radius(const float *pos, const float *reach, size_t count, pelt_vec3 c,
                           size_t *far)
{
    float best = -1.0f;
    for (size_t i = 0; i < count; i++) {
        float d = v3_len(v3_sub(v3_load(pos + 3 * i), c)) + reach_of(reach, i);
        if (d > best) best = d, *far = i;
    }
    return best;
}

/* A small bounding sphere of the grown points: the best of the bounding
 * box's centre and Badoiu and Clarkson's iteration (step towards the
 * farthest point by 1/(k+1)), which closes in on the smallest sphere. */
static pelt_vec3 bounding_centre(const float *pos, const float *reach, size_t count)
{
    pelt_vec3 lo = v3_load(pos), hi = lo;
    for (size_t i = 1; i < count; i++) {
        pelt_vec3 p = v3_load(pos + 3 * i);
        lo = v3(fminf(lo.x, p.x), fminf(lo.y, p.y), fminf(lo.z, p.z));
        hi = v3(fmaxf(hi.x, p.x), fmaxf(hi.y, p.y), fmaxf(hi.z, p.z));
    }
    pelt_vec3 c = v3_scale(v3_add(lo, hi), 0.5f), best = c;
    size_t far = 0;
    float best_r = sphere_radius(pos, reach, count, c, &far);
    for (int k = 1; k <= 64; k++) {
        pelt_vec3 p = v3_load(pos + 3 * far);
        c = v3_lerp(c, p, 1.0f / (float)(k + 1));
        float r = sphere_radius(pos, reach, count, c, &far);
        if (r < best_r) best_r = r, best = c;
    }
    return best;
}

/* Yaw (degrees, from +Z towards +X) of the long axis of the points'
 * footprint on XZ, or NAN when the footprint is nearly round. */
static float long_axis_yaw(const float *pos, size_t count, pelt_vec3 c)
{
    double xx = 0.0, xz = 0.0, zz = 0.0;
    for (size_t i = 0; i < count; i++) {
        double x = pos[3 * i] - c.x, z = pos[3 * i + 2] - c.z;
        xx += x * x, xz += x * z, zz += z * z;
    }
    double tr = xx + zz, det = xx * zz - xz * xz;
    double disc = sqrt(fmax(0.25 * tr * tr - det, 0.0));
    double l1 = 0.5 * tr + disc, l2 = 0.5 * tr - disc;
    /* Principal extents are the square roots of the variances. */
    if (!(l1 > 0.0) || sqrt(fmax(l2, 0.0) / l1) > 0.85) return NAN;
    double angle = 0.5 * atan2(2.0 * xz, xx - zz); /* of (x, z) from +X */
    double ax = cos(angle), az = sin(angle);
    return (float)(atan2(ax, az) * 180.0 / 3.14159265358979);
}

/* The three-quarter yaw (axis + 45 + k 90) nearest `yaw`. */
static float three_quarter(float axis, float yaw)
{
    float best = yaw, best_d = INFINITY;
    for (int k = 0; k < 4; k++) {
        float y = axis + 45.0f + 90.0f * (float)k;
        float d = fmodf(fabsf(y - yaw), 360.0f);
        d = fminf(d, 360.0f - d);
        if (d < best_d) best_d = d, best = y;
    }
    /* Kept within a turn of `yaw`'s own range. */
    while (best - yaw > 180.0f) best -= 360.0f;
    while (yaw - best > 180.0f) best += 360.0f;
    return best;
}

bool pelt_camera_frame(pelt_camera *camera, const float *positions, const float *reach, size_t count,
                       float aspect, float margin)
{
    if (!camera || !positions || count == 0 || !(aspect > 0.0f) || !isfinite(aspect) ||
        !(margin >= 0.0f) || !isfinite(margin) || !(camera->fov_y > 0.0f && camera->fov_y < 180.0f) ||
        !isfinite(camera->pitch) || !isfinite(camera->yaw))
        return false;
    for (size_t i = 0; i < count; i++) {
        if (!isfinite(positions[3 * i]) || !isfinite(positions[3 * i + 1]) || !isfinite(positions[3 * i + 2]))
            return false;
        if (reach && !(reach[i] >= 0.0f && isfinite(reach[i]))) return false;
    }
    const float deg = 3.14159265358979f / 180.0f;
    pelt_vec3 c = bounding_centre(positions, reach, count);
    float axis = long_axis_yaw(positions, count, c);
    float yaw = isnan(axis) ? camera->yaw : three_quarter(axis, camera->yaw);

    /* The view basis of pelt_camera_to_view: the eye at c + dir * d looks
     * along f = -dir with +Y up. */
    float y = yaw * deg, p = camera->pitch * deg;
    pelt_vec3 dir = v3(cosf(p) * sinf(y), sinf(p), cosf(p) * cosf(y));
    pelt_vec3 f = v3_scale(dir, -1.0f);
    pelt_vec3 right = v3_norm_or(v3_cross(f, v3(0.0f, 1.0f, 0.0f)), v3(1.0f, 0.0f, 0.0f));
    pelt_vec3 up = v3_cross(right, f);
    float ty = tanf(0.5f * camera->fov_y * deg), tx = aspect * ty;
    float sy = sinf(atanf(ty)), sx = sinf(atanf(tx));
    /* A sphere of radius r at lateral offset s and depth z = d + x.f is
     * inside a half-angle a when z >= |s| / tan a + r / sin a; the near
     * plane (0.02 d) must stay in front of it too. */
    float d = 0.0f;
    for (size_t i = 0; i < count; i++) {
        pelt_vec3 x = v3_sub(v3_load(positions + 3 * i), c);
        float r = reach_of(reach, i), depth = v3_dot(x, f);
        float need_x = fabsf(v3_dot(x, right)) / tx + r / sx - depth;
        float need_y = fabsf(v3_dot(x, up)) / ty + r / sy - depth;
        float need_near = (r - depth) / 0.98f;
        d = fmaxf(d, fmaxf(need_x, fmaxf(need_y, need_near)));
    }
    if (!(d > 0.0f) || !isfinite(d)) d = 1.0f; /* a single bare point */
    camera->yaw = yaw;
    camera->distance = d * (1.0f + margin);
    v3_store(camera->target, c);
    return true;
}

/* 4x4 inverse by cofactors; false when singular. */
static bool invert(const float m[16], float out[16])
{
    float inv[16];
    inv[0] = m[5] * m[10] * m[15] - m[5] * m[11] * m[14] - m[9] * m[6] * m[15] + m[9] * m[7] * m[14] + m[13] * m[6] * m[11] - m[13] * m[7] * m[10];
    inv[4] = -m[4] * m[10] * m[15] + m[4] * m[11] * m[14] + m[8] * m[6] * m[15] - m[8] * m[7] * m[14] - m[12] * m[6] * m[11] + m[12] * m[7] * m[10];
    inv[8] = m[4] * m[9] * m[15] - m[4] * m[11] * m[13] - m[8] * m[5] * m[15] + m[8] * m[7] * m[13] + m[12] * m[5] * m[11] - m[12] * m[7] * m[9];
    inv[12] = -m[4] * m[9] * m[14] + m[4] * m[10] * m[13] + m[8] * m[5] * m[14] - m[8] * m[6] * m[13] - m[12] * m[5] * m[10] + m[12] * m[6] * m[9];
    inv[1] = -m[1] * m[10] * m[15] + m[1] * m[11] * m[14] + m[9] * m[2] * m[15] - m[9] * m[3] * m[14] - m[13] * m[2] * m[11] + m[13] * m[3] * m[10];
    inv[5] = m[0] * m[10] * m[15] - m[0] * m[11] * m[14] - m[8] * m[2] * m[15] + m[8] * m[3] * m[14] + m[12] * m[2] * m[11] - m[12] * m[3] * m[10];
    inv[9] = -m[0] * m[9] * m[15] + m[0] * m[11] * m[13] + m[8] * m[1] * m[15] - m[8] * m[3] * m[13] - m[12] * m[1] * m[11] + m[12] * m[3] * m[9];
    inv[13] = m[0] * m[9] * m[14] - m[0] * m[10] * m[13] - m[8] * m[1] * m[14] + m[8] * m[2] * m[13] + m[12] * m[1] * m[10] - m[12] * m[2] * m[9];
    inv[2] = m[1] * m[6] * m[15] - m[1] * m[7] * m[14] - m[5] * m[2] * m[15] + m[5] * m[3] * m[14] + m[13] * m[2] * m[7] - m[13] * m[3] * m[6];
    inv[6] = -m[0] * m[6] * m[15] + m[0] * m[7] * m[14] + m[4] * m[2] * m[15] - m[4] * m[3] * m[14] - m[12] * m[2] * m[7] + m[12] * m[3] * m[6];
    inv[10] = m[0] * m[5] * m[15] - m[0] * m[7] * m[13] - m[4] * m[1] * m[15] + m[4] * m[3] * m[13] + m[12] * m[1] * m[7] - m[12] * m[3] * m[5];
    inv[14] = -m[0] * m[5] * m[14] + m[0] * m[6] * m[13] + m[4] * m[1] * m[14] - m[4] * m[2] * m[13] - m[12] * m[1] * m[6] + m[12] * m[2] * m[5];
    inv[3] = -m[1] * m[6] * m[11] + m[1] * m[7] * m[10] + m[5] * m[2] * m[11] - m[5] * m[3] * m[10] - m[9] * m[2] * m[7] + m[9] * m[3] * m[6];
    inv[7] = m[0] * m[6] * m[11] - m[0] * m[7] * m[10] - m[4] * m[2] * m[11] + m[4] * m[3] * m[10] + m[8] * m[2] * m[7] - m[8] * m[3] * m[6];
    inv[11] = -m[0] * m[5] * m[11] + m[0] * m[7] * m[9] + m[4] * m[1] * m[11] - m[4] * m[3] * m[9] - m[8] * m[1] * m[7] + m[8] * m[3] * m[5];
    inv[15] = m[0] * m[5] * m[10] - m[0] * m[6] * m[9] - m[4] * m[1] * m[10] + m[4] * m[2] * m[9] + m[8] * m[1] * m[6] - m[8] * m[2] * m[5];
    float det = m[0] * inv[0] + m[1] * inv[4] + m[2] * inv[8] + m[3] * inv[12];
    if (!(fabsf(det) > 1e-30f) || !isfinite(det)) return false;
    for (int i = 0; i < 16; i++) out[i] = inv[i] / det;
    return true;
}

/* Unprojects a point of normalized device coordinates. */
static pelt_vec3 unproject(const float inv[16], float x, float y, float z)
{
    float v[4] = {x, y, z, 1.0f}, r[4];
    for (int row = 0; row < 4; row++)
        r[row] = inv[row] * v[0] + inv[4 + row] * v[1] + inv[8 + row] * v[2] + inv[12 + row] * v[3];
    return v3_scale(v3(r[0], r[1], r[2]), 1.0f / r[3]);
}

bool pelt_view_pixel_ray(const pelt_view *v, float px, float py, float origin[3], float direction[3])
{
    if (!v || v->width == 0 || v->height == 0) return false;
    float vp[16], mvp[16], inv[16];
    pelt__mat4_mul(vp, v->proj, v->view);
    pelt__mat4_mul(mvp, vp, v->model);
    if (!invert(mvp, inv)) return false;
    /* Pixel centres; rows count down from the top as image files do. */
    float x = 2.0f * (px + 0.5f) / (float)v->width - 1.0f;
    float y = 1.0f - 2.0f * (py + 0.5f) / (float)v->height;
    pelt_vec3 near = unproject(inv, x, y, -1.0f), far = unproject(inv, x, y, 1.0f);
    pelt_vec3 d = v3_norm_or(v3_sub(far, near), v3(0.0f, 0.0f, -1.0f));
    v3_store(origin, near);
    v3_store(direction, d);
    return isfinite(near.x) && isfinite(near.y) && isfinite(near.z);
}
