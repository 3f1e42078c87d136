// Opaque skin: the innermost fur slice lit by Lambert, under gamma(0) (or
// the hair model's occlusion at the roots), in linear light.
// Where grooming thins the hair (density below 1) the bare skin colour
// shows through in proportion. Wet skin is darker and carries the water
// film's sheen (docs/wetness.md, Wet optics).
in vec3 v_normal;
in vec2 v_uv;
in vec2 v_fur_uv;
in float v_density;
in vec4 v_hair_color;
in vec3 v_world;

uniform highp sampler2DArray u_fur; // PELT_UNIT_FUR
uniform sampler2D u_color_tex;     // PELT_UNIT_COLOR
uniform sampler2D u_mask;          // PELT_UNIT_MASK: wetness, rho in alpha

out vec4 o_color;

void main()
{
    vec3 n = normalize(v_normal);
    float shade = shade_decode(texture(u_fur, vec3(v_fur_uv, 0.0)).r); // linear light
    vec3 roots = groom_root_color(u_color, v_hair_color) * shade;
    // Variants as the shells' (gl/skin_pass.c): only what the frame needs.
#ifdef PELT_COLOR_TEXTURE
    roots *= texture(u_color_tex, v_uv * u_color_scale).rgb;
#endif
    vec3 base = mix(u_skin_color, roots, clamp(v_density, 0.0, 1.0));
    vec3 L = normalize(u_light_dir);
    float lambert = max(dot(n, L), 0.0);
    // The skin sits under all the fur: gamma at h = 0; with the light's
    // shadow maps, the fur's real opacity instead (unless gamma is kept),
    // read with a bias that grows as the light grazes the skin.
    // Scheuermann-Marschner's occlusion from the fur's density in place of gamma.
    float gamma = u_shading_model > 1.5 ? fur_occlusion(u_occlusion, 0.0) : shadow_factor(u_shadow, 0.0);
#ifdef PELT_SHADOW_MAP
    if (u_shadow_map.x > 0.5 && lambert > 0.0) {
        float nl = max(lambert, 0.1);
        lambert *= shadow_transmittance(v_world, u_shadow_slab.z * (1.0 + min(sqrt(1.0 - nl * nl) / nl, 4.0)), 4);
        gamma = mix(1.0, gamma, u_shadow_slab.w);
    }
#endif
#ifdef PELT_WET
    // The water film: the roots and skin darken as the hair does, and the
    // light the film mirrors has come down through the fur (gamma).
    float rho = clump_texel(u_mask, v_uv).a;
    base = wet_color(base, rho, u_wet_darken);
#endif
    vec3 light = base * gamma * (u_ambient + lambert * u_light_color);
#ifdef PELT_WET
    vec3 H = normalize(L + normalize(u_eye - v_world));
    if (lambert > 0.0)
        light += u_specular * u_light_color * gamma *
                 wet_skin_sheen(dot(n, H), rho, u_shininess, u_wet_sharpness, u_wet_gloss);
#endif
    o_color = vec4(display_color(light, u_exposure, u_tone), 1.0);
}
