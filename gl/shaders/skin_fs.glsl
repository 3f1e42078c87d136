// Opaque skin: the innermost fur slice lit by Lambert, under gamma(0).
in vec3 v_normal;
in vec2 v_uv;
in vec2 v_fur_uv;

uniform highp sampler2DArray u_fur; // PELT_UNIT_FUR
uniform sampler2D u_color_tex;     // PELT_UNIT_COLOR

out vec4 o_color;

void main()
{
    vec3 n = normalize(v_normal);
    float shade = texture(u_fur, vec3(v_fur_uv, 0.0)).r;
    vec3 base = u_color * texture(u_color_tex, v_uv * u_color_scale).rgb * shade;
    float lambert = max(dot(n, normalize(u_light_dir)), 0.0);
    // The skin sits under all the fur: gamma at h = 0.
    float gamma = shadow_factor(u_shadow, 0.0);
    o_color = vec4(base * gamma * (u_ambient + lambert * u_light_color), 1.0);
}
