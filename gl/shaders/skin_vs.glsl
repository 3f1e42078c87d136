// Opaque skin pass: the mesh itself, the innermost fur slice as its colour.
layout(location = PELT_ATTR_POSITION) in vec3 a_position;
layout(location = PELT_ATTR_NORMAL) in vec3 a_normal;
layout(location = PELT_ATTR_UV) in vec2 a_uv;
layout(location = PELT_ATTR_FUR_UV) in vec2 a_fur_uv;
layout(location = PELT_ATTR_GROOM) in vec4 a_groom;  // lean u, lean v, length scale, density
layout(location = PELT_ATTR_HAIR_COLOR) in vec4 a_hair_color;

out vec3 v_normal;
out vec2 v_uv;
out vec2 v_fur_uv;
out float v_density;
out vec4 v_hair_color;
out vec3 v_world;

void main()
{
    vec4 world = u_model * vec4(a_position, 1.0);
    v_normal = mat3(u_model) * a_normal;
    v_world = world.xyz;
    v_uv = a_uv;
    v_fur_uv = a_fur_uv;
    v_density = a_groom.w;
    v_hair_color = a_hair_color;
    gl_Position = u_view_proj * world;
}
