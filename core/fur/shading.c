#include "core/fur/shading.h"

/* Silva et al. Eq. 6. E points from the eye to the point, so the mirror
 * cone of the light around T is where (T.L)(T.E) + sin sin peaks. */
void pelt__kajiya_kay(pelt_vec3 t, pelt_vec3 l, pelt_vec3 e, float p, float *diffuse,
                      float *specular)
{
    float tl = v3_dot(t, l), te = v3_dot(t, e);
    float sin_tl = sqrtf(fmaxf(0.0f, 1.0f - tl * tl));
    float sin_te = sqrtf(fmaxf(0.0f, 1.0f - te * te));
    *diffuse = sin_tl;
    *specular = powf(fmaxf(0.0f, tl * te + sin_tl * sin_te), p);
}

/* Silva et al. Eq. 6: darkens the lower part of the fur. */
float pelt__shadow_factor(float k_shadow, float h) { return (k_shadow - 1.0f + h) / k_shadow; }
