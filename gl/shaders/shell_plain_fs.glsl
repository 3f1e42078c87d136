// The plain shell renderer's fragment stage: one fetch of the same fur
// texture, blended, no discard, the hair's colour unlit.
in vec2 v_fur_uv;
flat in float v_slice;

uniform highp sampler2DArray u_fur; // PELT_UNIT_FUR

out vec4 o_color;

void main()
{
    float a = texture(u_fur, vec3(v_fur_uv, v_slice)).a;
    o_color = vec4(sqrt(u_color), a); // the linear colour roughly back to sRGB
}
