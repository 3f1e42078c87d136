/* Small inline vector and matrix math shared by core/ and gl/. */
#ifndef PELT_VEC_H
#define PELT_VEC_H

#include <math.h>

typedef struct pelt_vec3 { float x, y, z; } pelt_vec3;

static inline pelt_vec3 v3(float x, float y, float z) { pelt_vec3 r = {x, y, z}; return r; }
static inline pelt_vec3 v3_load(const float *p) { return v3(p[0], p[1], p[2]); }
static inline void v3_store(float *p, pelt_vec3 a) { p[0] = a.x; p[1] = a.y; p[2] = a.z; }
static inline pelt_vec3 v3_add(pelt_vec3 a, pelt_vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline pelt_vec3 v3_sub(pelt_vec3 a, pelt_vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline pelt_vec3 v3_scale(pelt_vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
static inline pelt_vec3 v3_mad(pelt_vec3 a, pelt_vec3 b, float s) { return v3(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s); }
static inline float v3_dot(pelt_vec3 a, pelt_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline pelt_vec3 v3_cross(pelt_vec3 a, pelt_vec3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline pelt_vec3 v3_lerp(pelt_vec3 a, pelt_vec3 b, float t) { return v3_mad(a, v3_sub(b, a), t); }
static inline float v3_len(pelt_vec3 a) { return sqrtf(v3_dot(a, a)); }
/* Unit vector along a, or `fallback` when a is (near) zero. */
static inline pelt_vec3 v3_norm_or(pelt_vec3 a, pelt_vec3 fallback)
{
    float l = v3_len(a);
    return l > 1e-20f ? v3_scale(a, 1.0f / l) : fallback;
}
/* A unit vector perpendicular to unit n: the t of v3_basis. */
static inline pelt_vec3 v3_perpendicular(pelt_vec3 n)
{
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float b = n.x * n.y * a;
    return v3(1.0f + s * n.x * n.x * a, s * b, -s * n.x);
}
/* The orthonormal basis of core/: unit t and b across unit n, with (t, b, n)
 * right-handed (b = n x t). Duff et al. 2017, "Building an orthonormal
 * basis, revisited": no branch on n but the sign of n.z, continuous except
 * where n.z changes sign. */
static inline void v3_basis(pelt_vec3 n, pelt_vec3 *t, pelt_vec3 *b)
{
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    *t = v3_perpendicular(n);
    *b = v3(n.x * n.y * a, s + n.y * n.y * a, -n.y);
}
static inline float clampf(float x, float lo, float hi) { return x < lo ? lo : (x > hi ? hi : x); }

/* Column-major 4x4 matrices, as OpenGL takes them. */
void pelt__mat4_perspective(float m[16], float fov_y_rad, float aspect, float znear, float zfar);
void pelt__mat4_look_at(float m[16], pelt_vec3 eye, pelt_vec3 target, pelt_vec3 up);
void pelt__mat4_mul(float out[16], const float a[16], const float b[16]);
void pelt__mat4_identity(float m[16]);
/* Rotation by `angle` radians about a unit axis. */
void pelt__mat4_rotate(float m[16], pelt_vec3 axis, float angle);
/* Transforms a point (w = 1) or a direction (w = 0). */
pelt_vec3 pelt__mat4_apply(const float m[16], pelt_vec3 p, float w);

#endif
