// Silva et al. Eq. 6 (Kajiya-Kay) and the shadow factor gamma; mirrored by
// core/fur/shading.c. E points from the eye towards the shaded point.
vec2 kajiya_kay(vec3 T, vec3 L, vec3 E, float p)
{
    float tl = dot(T, L);
    float te = dot(T, E);
    float sin_tl = sqrt(max(0.0, 1.0 - tl * tl));
    float sin_te = sqrt(max(0.0, 1.0 - te * te));
    return vec2(sin_tl, pow(max(0.0, tl * te + sin_tl * sin_te), p));
}

// Wet fur's highlight: (exponent, specular gain) at wetness rho, the
// exponent p sharpened and the gain raised towards their fully wet
// multiples. Mirrors pelt__wet_shine (docs/wetness.md, Wet shine).
vec2 wet_shine(float rho, float p, float sharpness, float gloss)
{
    float r = clamp(rho, 0.0, 1.0);
    return vec2(p * (1.0 + (sharpness - 1.0) * r), 1.0 + (gloss - 1.0) * r);
}

float shadow_factor(float k_shadow, float h)
{
    return (k_shadow - 1.0 + h) / k_shadow;
}

// Grooming (Lengyel et al. §3): a vertex's hair colour c.rgb over the
// look's colour with weight c.a; its tip is brightened by the look's own
// tip-to-root ratio. Mirrored by pelt__groom_root_color / _tip_color.
vec3 groom_root_color(vec3 color, vec4 c)
{
    return mix(color, c.rgb, c.a);
}

vec3 groom_tip_color(vec3 color, vec3 tip, vec4 c)
{
    return mix(tip, min(c.rgb * tip / max(color, vec3(0.01)), vec3(1.0)), c.a);
}

// Grooming's density keeps the strands whose id (the fur volume's blue,
// uniform in [0,1]) is below it; 1 keeps all of them.
bool groom_keeps(float id, float density)
{
    return density >= 1.0 || id < density;
}

// Lengyel et al. §2.4: the (diffuse, specular) factors of the hair
// lighting table, read with bilinear filtering (pelt__lengyel_table).
vec2 lengyel_lookup(sampler2D table, vec3 T, vec3 L, vec3 H)
{
    return texture(table, vec2(dot(T, L), dot(T, H)) * 0.5 + 0.5).rg;
}

// Kenwright's inter-fur shadow: the fur-texture step towards the light in
// the tangent frame (pelt__inter_shadow_offset).
vec2 inter_shadow_offset(vec3 L, vec3 u, vec3 v, float step)
{
    return vec2(dot(L, u), dot(L, v)) * step;
}
