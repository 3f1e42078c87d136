// The light pass's first step (gl/shadow_pass.c): the skin's depth from
// the light, into the depth map.
layout(location = PELT_ATTR_POSITION) in vec3 a_position;

void main()
{
    vec3 c = shadow_coord((u_model * vec4(a_position, 1.0)).xyz);
    gl_Position = vec4(c * 2.0 - 1.0, 1.0);
}
