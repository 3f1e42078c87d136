// The plain shell renderer that pelt bench --plain measures pelt against:
// the classic method (Lengyel et al. §2.1 without the rest): every shell
// extruded along the vertex normal, all N of them on every triangle, one
// instanced draw, no strand shape, no level of detail, no lighting.
layout(location = PELT_ATTR_POSITION) in vec3 a_position;
layout(location = PELT_ATTR_NORMAL) in vec3 a_normal;
layout(location = PELT_ATTR_FUR_UV) in vec2 a_fur_uv;

out vec2 v_fur_uv;
flat out float v_slice;

void main()
{
    float layer = float(gl_InstanceID); // the innermost first: blended outwards
    float h = (1.0 + layer) / u_layers;
    vec3 p = a_position + normalize(a_normal) * (u_length * h);
    gl_Position = u_view_proj * (u_model * vec4(p, 1.0));
    v_fur_uv = a_fur_uv;
    v_slice = layer;
}
