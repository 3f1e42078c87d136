// All shells in one instanced draw: the layer is gl_InstanceID.
// Silva et al. Eq. 1: offset(h) = beta(h) + phi(h).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec2 a_fur_uv;
layout(location = 4) in vec4 a_tangent;
layout(location = 5) in vec3 a_tip;     // p - p_root, mesh-local
layout(location = 6) in vec3 a_comb;    // comb direction x weight (0: stands up)

uniform mat4 u_model;
uniform mat4 u_view_proj;
uniform float u_layers;
uniform float u_first_layer;            // the instance range may start above 0
uniform float u_length;
uniform float u_curl_frequency;
uniform float u_curl_radius;
uniform float u_slant;                  // tan of the comb angle (Lengyel §3)
uniform sampler2D u_mask;               // wetness mask, rho in alpha

out vec2 v_uv;
out vec2 v_fur_uv;
out vec3 v_world;
out vec3 v_tangent;
out vec3 v_normal;
out float v_h;
flat out float v_layer;

void main()
{
    float layer = u_first_layer + float(gl_InstanceID);
    float h = (1.0 + layer) / u_layers;
    vec3 n = normalize(a_normal);
    vec3 u = normalize(a_tangent.xyz);
    vec3 v = cross(n, u) * a_tangent.w;
    float rho = textureLod(u_mask, a_uv, 0.0).a;
    vec3 offset = fur_bend(n, u_length, a_tip, h)
                + fur_curl(u, v, u_curl_frequency, u_curl_radius, rho, h)
                + fur_comb(a_comb, u_length, u_slant, h);
    vec3 t = fur_tangent_combed(n, u_length, a_tip, u, v, a_comb, u_curl_frequency,
                                u_curl_radius, rho, u_slant, h);
    vec4 world = u_model * vec4(a_position + offset, 1.0);
    v_world = world.xyz;
    v_tangent = mat3(u_model) * t;
    v_normal = mat3(u_model) * n;
    v_uv = a_uv;
    v_fur_uv = a_fur_uv;
    v_h = h;
    v_layer = layer;
    gl_Position = u_view_proj * world;
}
