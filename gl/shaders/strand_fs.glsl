// The strand reference's hairs are opaque: coverage comes from drawing
// them at more samples than pixels (pelt render --strands). Lit in linear
// light per vertex, mapped to the picture as the shells are.
#ifdef PELT_LIGHT_PASS
// The light pass: each hair's -ln(1 - cover) into the slices at and behind
// its depth in the slab in front of the skin, as the shells' light pass
// adds theirs (shell_fs.glsl); hair behind the skin shades nothing lit.
in float v_light_depth;
in float v_cover;
layout(location = 0) out vec4 o_slices0;
layout(location = 1) out vec4 o_slices1;

void main()
{
    float z_skin = texelFetch(u_shadow_depth, ivec2(gl_FragCoord.xy), 0).r;
    if (v_light_depth - u_shadow_slab.z > z_skin) discard;
    float k = (v_light_depth - (z_skin - u_shadow_slab.x)) / u_shadow_slab.x * u_shadow_map.y;
    vec4 w0, w1;
    shadow_slice_weights(k, u_shadow_map.y, w0, w1);
    float sigma = shadow_sigma(v_cover);
    o_slices0 = sigma * w0;
    o_slices1 = sigma * w1;
}
#else
in vec3 v_color;
out vec4 o_color;

void main()
{
    o_color = vec4(display_color(v_color, u_exposure, u_tone), 1.0);
}
#endif
