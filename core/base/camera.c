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
