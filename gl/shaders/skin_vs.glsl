// Opaque skin pass: the mesh itself, the innermost fur slice as its colour.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec2 a_fur_uv;

uniform mat4 u_model;
uniform mat4 u_view_proj;

out vec3 v_normal;
out vec2 v_uv;
out vec2 v_fur_uv;

void main()
{
    vec4 world = u_model * vec4(a_position, 1.0);
    v_normal = mat3(u_model) * a_normal;
    v_uv = a_uv;
    v_fur_uv = a_fur_uv;
    gl_Position = u_view_proj * world;
}
