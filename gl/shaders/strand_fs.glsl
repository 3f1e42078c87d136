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
    if (!shadow_slices_add(ivec2(gl_FragCoord.xy), v_light_depth, v_cover, o_slices0, o_slices1)) discard;
}
#else
in vec3 v_color;
out vec4 o_color;

void main()
{
    o_color = vec4(display_color(v_color, u_exposure, u_tone), 1.0);
}
#endif
