// The floor a shell shader is measured against (pelt bench --floor): one
// fetch of the fur's coverage, the same threshold, a constant colour.
in vec2 v_fur_uv;
flat in vec3 v_slices;
in float v_alpha;

uniform highp sampler2DArray u_fur; // PELT_UNIT_FUR

out vec4 o_color;

void main()
{
    if (v_alpha < 1.0 / 255.0) discard; // the same shells as the frame draws
    float a = texture(u_fur, vec3(v_fur_uv, v_slices.x)).a;
    if (a < 0.05) discard;
    o_color = vec4(0.45, 0.33, 0.2, a);
}
