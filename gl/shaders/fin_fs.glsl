// Fin fragments: the fin texture (the same hair seen from the side), faded
// in near the silhouette, lit like the shells (fur_light.glsl); wet fins
// darken like the shells (their curl is already lost in the vertex stage).
in vec2 v_uv;
in vec2 v_fin_uv;
in float v_density;
in float v_fade;
in vec3 v_root; // lit
in vec3 v_tip;
in float v_spec;

uniform sampler2D u_fin_tex;   // PELT_UNIT_FIN
uniform sampler2D u_color_tex; // PELT_UNIT_COLOR
uniform sampler2D u_mask;      // PELT_UNIT_MASK

out vec4 o_color;

void main()
{
    vec4 hair = texture(u_fin_tex, v_fin_uv);
    hair.rgb /= max(hair.a, 1e-3); // premultiplied
    if (!groom_keeps(hair.b, v_density)) discard;
    if (hair.a < 0.05) discard;
    float a = hair.a * v_fade;
    vec3 base = mix(v_root, v_tip, hair.g) * shade_decode(hair.r); // linear light
    // Variants as the shells' (gl/fin_pass.c): only what the frame needs.
#ifdef PELT_COLOR_TEXTURE
    base *= texture(u_color_tex, v_uv * u_color_scale).rgb;
#endif
#ifdef PELT_WET
    base = wet_color(base, textureLod(u_mask, v_uv, 0.0).a, u_wet_darken);
#endif
    o_color = vec4(display_color(base + v_spec * (u_specular * u_light_color), u_exposure, u_tone), a);
}
