// The ground: Lambert under the light's shadow maps (shadow_map.glsl), its
// rim faded into what was drawn before it.
in vec3 v_world;
in vec2 v_disc;

uniform vec3 u_ground_color; // linear (gl/ground_pass.c decodes it)

out vec4 o_color;

void main()
{
    float r = length(v_disc);
    if (r > 1.0) discard;
    vec3 L = normalize(u_light_dir);
    float lambert = max(L.y, 0.0);
    if (lambert > 0.0) lambert *= shadow_light(v_world, u_shadow_slab.z, 4);
    vec3 lit = u_ground_color * (u_ambient + lambert * u_light_color); // linear light
    o_color = vec4(display_color(lit, u_exposure, u_tone), 1.0 - smoothstep(0.6, 1.0, r));
}
