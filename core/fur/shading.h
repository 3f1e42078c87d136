/* C references of the shading formulas that run in the fur shaders; the
 * parity test renders the GLSL versions (gl/shaders/shading.glsl) into a
 * float target and compares them with these. */
#ifndef PELT_SHADING_H
#define PELT_SHADING_H

#include "core/base/vec.h"

/* Silva et al. Eq. 6, Kajiya-Kay: T strand tangent, L towards the light,
 * E camera direction (from the eye towards the point), all unit.
 * Returns (C_d, C_s) factors: diffuse = |T x L|, specular =
 * max(0, (T.L)(T.E) + |T x L||T x E|)^p. */
void pelt__kajiya_kay(pelt_vec3 t, pelt_vec3 l, pelt_vec3 e, float p, float *diffuse,
                      float *specular);

/* Silva et al. Eq. 6 shadow factor gamma = (K - 1 + h) / K, K >= 1. */
float pelt__shadow_factor(float k_shadow, float h);

#endif
