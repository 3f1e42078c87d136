#include "core/base/vec.h"

#include <string.h>

void pelt__mat4_identity(float m[16])
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = m[5] = m[10] = m[15] = 1.0f;
}

void pelt__mat4_perspective(float m[16], float fov_y_rad, float aspect, float znear, float zfar)
{
    float f = 1.0f / tanf(fov_y_rad * 0.5f);
    memset(m, 0, 16 * sizeof(float));
    m[0] = f / aspect;
    m[5] = f;
    m[10] = (zfar + znear) / (znear - zfar);
    m[11] = -1.0f;
    m[14] = 2.0f * zfar * znear / (znear - zfar);
}

void pelt__mat4_look_at(float m[16], pelt_vec3 eye, pelt_vec3 target, pelt_vec3 up)
{
    pelt_vec3 f = v3_norm_or(v3_sub(target, eye), v3(0, 0, -1));
    pelt_vec3 s = v3_norm_or(v3_cross(f, up), v3(1, 0, 0));
    pelt_vec3 u = v3_cross(s, f);
    pelt__mat4_identity(m);
    m[0] = s.x; m[4] = s.y; m[8] = s.z;
    m[1] = u.x; m[5] = u.y; m[9] = u.z;
    m[2] = -f.x; m[6] = -f.y; m[10] = -f.z;
    m[12] = -v3_dot(s, eye);
    m[13] = -v3_dot(u, eye);
    m[14] = v3_dot(f, eye);
}

void pelt__mat4_mul(float out[16], const float a[16], const float b[16])
{
    float r[16];
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            float s = 0.0f;
            for (int k = 0; k < 4; k++) s += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = s;
        }
    memcpy(out, r, sizeof r);
}

void pelt__mat4_rotate(float m[16], pelt_vec3 a, float angle)
{
    float c = cosf(angle), s = sinf(angle), t = 1.0f - c;
    pelt__mat4_identity(m);
    m[0] = t * a.x * a.x + c;       m[4] = t * a.x * a.y - s * a.z; m[8] = t * a.x * a.z + s * a.y;
    m[1] = t * a.x * a.y + s * a.z; m[5] = t * a.y * a.y + c;       m[9] = t * a.y * a.z - s * a.x;
    m[2] = t * a.x * a.z - s * a.y; m[6] = t * a.y * a.z + s * a.x; m[10] = t * a.z * a.z + c;
}

pelt_vec3 pelt__mat4_apply(const float m[16], pelt_vec3 p, float w)
{
    return v3(m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12] * w,
              m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13] * w,
              m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14] * w);
}
