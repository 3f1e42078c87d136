// Fin fragments: the fin texture (the same hair seen from the side), faded
// in near the silhouette, lit like the shells (fur_light.glsl): ringlets
// along their curl (own_light.glsl); wet fins darken like the shells.
in vec2 v_uv;
in vec2 v_fin_uv;
in float v_density;
in float v_fade;
in vec3 v_root; // lit
in vec3 v_tip;
in float v_spec;
#ifdef PELT_RINGLETS
in vec2 v_light;  // the ringlet's own light (fin_vs.glsl)
in vec3 v_ring_l;
in vec3 v_ring_e;
in vec3 v_ring_g;
#endif

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
    float rho = 0.0, spec = v_spec;
#ifdef PELT_WET
    rho = textureLod(u_mask, v_uv, 0.0).a;
    base = wet_color(base, rho, u_wet_darken);
#endif
#ifdef PELT_RINGLETS
    // The hair the fin shows curls: lit along its ringlet, as the shells'
    // (own_light.glsl); the fin texture's id gives its phase.
#ifdef PELT_WET
    const bool free_in_base = true;
#else
    const bool free_in_base = false;
#endif
    ringlet_light(hair.b, rho, v_fin_uv.y, v_light, v_ring_l, v_ring_e, v_ring_g, free_in_base, base, spec);
#endif
    o_color = vec4(display_color(base + spec * (u_specular * u_light_color), u_exposure, u_tone), a);
}
