// The outline's hairs (outline_vs.glsl): lit per vertex, blended by the
// share of the pixel each covers, mapped to the picture as the shells are.
in vec3 v_color;
in float v_alpha;
out vec4 o_color;

void main()
{
    o_color = vec4(display_color(v_color, u_exposure, u_tone), v_alpha);
}
