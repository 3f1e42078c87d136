// The light on a hair, shared by the shells, the fins and the strand
// reference, in linear light: the hair model (Kajiya-Kay, Silva Eq. 6,
// Lengyel's §2.4 table, or Scheuermann's reading of Marschner; all in
// shading.glsl, docs/shading.md) with the displaced strand's tangent T,
// the body's own shadow on hair facing away from the light, and gamma(h)
// (the occlusion from the fur's density for Scheuermann-Marschner). Reads
// the uniform blocks, so it comes after blocks.glsl (and shadow_map.glsl).
uniform sampler2D u_light_table; // PELT_UNIT_LIGHT_TABLE

// The wetness under the hair being lit, for its shine (wet_shine): a
// stage that reads the mask sets it before fur_light_terms; dry otherwise.
float fur_wetness = 0.0;

// As a factor and a weight, colour = base * mul + spec * u_specular *
// u_light_color, in linear light, so the shells and the fins evaluate it
// per vertex (their lean fragment stage only fetches the hair, multiplies
// and maps the result to the picture: display_color). docs/lod.md says
// what that costs in the picture. The stages fold mul into the root and
// tip colours they pass on: fewer varyings to interpolate.
// The direct light's reach at a hair with surface normal N (unit) at
// world: (facing, seen, gamma): hair on the side of the body facing away
// from the light is in the body's shadow (the hair models alone would
// light it as brightly), the light's shadow maps darken it, and gamma(h)
// (Silva Eq. 6) darkens the lower fur.
vec3 fur_reach(vec3 N, vec3 world, float h)
{
    float nl = dot(N, normalize(u_light_dir)), seen = 1.0;
    float gamma = shadow_factor(u_shadow, h);
#ifdef PELT_SHADOW_MAP
    // The light's shadow maps (shadow_map.glsl) darken the direct light;
    // gamma, their cheap stand-in, stays only when asked for.
    seen = shadow_light(world, u_shadow_slab.z, 1);
    if (u_shadow_map.x > 0.5) gamma = mix(1.0, gamma, u_shadow_slab.w);
#endif
    return vec3(clamp(nl * 0.8 + 0.35, 0.0, 1.0) * seen, seen, gamma);
}

// The reach (fur_reach) the last fur_light_terms call lit with, for a
// stage that lights again per fragment (the shells' tuft light).
vec3 fur_light_reach = vec3(0.0);

void fur_light_terms(vec3 tangent, vec3 normal, vec3 world, float h, out vec3 mul, out float spec)
{
    vec3 T = normalize(tangent);
    vec3 N = normalize(normal);
    vec3 L = normalize(u_light_dir);
    vec3 E = normalize(world - u_eye);
    vec2 shine = wet_shine(fur_wetness, u_shininess, u_wet_sharpness, u_wet_gloss);
    vec3 reach = fur_reach(N, world, h);
    fur_light_reach = reach;
    float nl = dot(N, L), facing = reach.x, seen = reach.y, gamma = reach.z;
    // A program may be built for one model (the passes' variants,
    // gl/shell_pass.c: Kajiya-Kay, the table, or neither define for
    // Scheuermann-Marschner); else the fur's model is chosen at run time.
#if defined(PELT_SHADING_TABLE) && !defined(PELT_SHADING_KK)
    const float model = 1.0;
#elif defined(PELT_SHADING_KK) && !defined(PELT_SHADING_TABLE)
    const float model = 0.0;
#elif !defined(PELT_SHADING_KK) && !defined(PELT_SHADING_TABLE)
    const float model = 2.0;
#else
    float model = u_shading_model;
#endif
    if (model > 1.5) {
        // Two highlights shifted along the strand, the secondary tinted by
        // the hair (folded into mul, which multiplies the hair colour),
        // transmission towards a light behind the fur, and occlusion from
        // the fur's density in place of gamma (docs/shading.md).
        vec4 m = hair_lobes(T, N, L, E, shine.x);
        float occ = fur_occlusion(u_occlusion, h);
#ifdef PELT_SHADOW_MAP
        // Like gamma, a stand-in for the shadow maps: kept only when asked.
        if (u_shadow_map.x > 0.5) occ = mix(1.0, occ, u_shadow_slab.w);
#endif
        // Light from behind reaches the hair that stands clear of the
        // body, up to the silhouette: transmission's body shadow sets in
        // only where the body lies between (n.L below 0).
        float behind = clamp(nl * 0.8 + HAIR_TT_REACH, 0.0, 1.0) * seen;
        vec3 lit = (m.x + HAIR_SECONDARY_GAIN * shine.y * m.z * u_specular) * facing + HAIR_TT_GAIN * m.w * behind;
        mul = occ * (u_ambient + lit * u_light_color);
        spec = occ * shine.y * m.y * facing;
        return;
    }
    vec2 kk = model > 0.5 ? lengyel_lookup(u_light_table, T, L, normalize(L - E))
                          : kajiya_kay(T, L, E, shine.x);
    mul = gamma * (u_ambient + kk.x * facing * u_light_color);
    spec = gamma * shine.y * kk.y * facing;
}
