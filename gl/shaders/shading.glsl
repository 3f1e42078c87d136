// Silva et al. Eq. 6 (Kajiya-Kay) and the shadow factor gamma; mirrored by
// core/shading.c. E points from the eye towards the shaded point.
vec2 kajiya_kay(vec3 T, vec3 L, vec3 E, float p)
{
    float tl = dot(T, L);
    float te = dot(T, E);
    float sin_tl = sqrt(max(0.0, 1.0 - tl * tl));
    float sin_te = sqrt(max(0.0, 1.0 - te * te));
    return vec2(sin_tl, pow(max(0.0, tl * te + sin_tl * sin_te), p));
}

float shadow_factor(float k_shadow, float h)
{
    return (k_shadow - 1.0 + h) / k_shadow;
}
