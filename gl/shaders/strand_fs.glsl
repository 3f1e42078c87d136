// The strand reference's hairs are opaque: coverage comes from drawing
// them at more samples than pixels (pelt render --strands). Lit in linear
// light per vertex, mapped to the picture as the shells are.
in vec3 v_color;
out vec4 o_color;

void main()
{
    o_color = vec4(display_color(v_color, u_exposure, u_tone), 1.0);
}
