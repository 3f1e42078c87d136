// The outline's hairs (outline_hair.glsl), drawn after the shells from the
// fin pass's vertex table (fin_vs.glsl) and a table of the hairs
// (pelt__outline_hairs: its fin's two vertices, its number on the fin,
// the fin's fade): an instance is PELT_FIN_CHUNK hairs, hair
// gl_InstanceID * PELT_FIN_CHUNK + gl_VertexID / (2 (rows + 1)); each a
// strip of the fins' rows up a ribbon facing the eye, as wide as the hair
// and at least a pixel (its alpha then the share of the pixel it covers),
// rising along its fin's strands at its root's place on the edge, lit as
// the fins are.
// The tables (fin_table.glsl): u_fin_edges holds the hairs in this draw.
uniform int u_fin_count;               // the hairs in the table
uniform float u_outline_hairs;         // hairs a fin carries per fur tile of its edge

out vec3 v_color;
out float v_alpha;

void main()
{
    int corners = 2 * (u_fin_rows + 1);
    int hair = gl_InstanceID * PELT_FIN_CHUNK + gl_VertexID / corners;
    int corner = gl_VertexID % corners;
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // collapsed unless drawn
    v_color = vec3(0.0);
    v_alpha = 0.0;
    if (hair >= u_fin_count) return; // the last chunk's spare hairs
    uvec4 e = texelFetch(u_fin_edges, table_at(hair), 0);
    int k = int(e.z);
    vec3 root_a = fin_vertex(e.x, 0).xyz, root_b = fin_vertex(e.y, 0).xyz;
    float edge = length(mat3(u_model) * (root_b - root_a)) * u_tiling;
    uint seed = outline_seed(e.x, e.y, uint(k));
    float show = outline_random(seed, 3u);
    float alpha = outline_alpha(float(k), edge * u_outline_hairs, uintBitsToFloat(e.w), show);
    vec4 nd = fin_vertex(e.x, 2 * PELT_FIN_HEIGHTS); // normal, groomed density
    // Grooming thins these hairs as it thins the shells' (groom_keeps).
    if (outline_random(seed, 5u) > nd.w) alpha = 0.0;
    float at = outline_random(seed, 0u);
    vec3 root = mix(root_a, root_b, at);
    // The share of the outline the fin's hairs carry, the fin's quad the
    // rest (fin_outline_share); wet hair darkens.
    alpha *= fin_outline_share(e.x, e.y, fur_wetness);
    if (alpha <= 0.0) return;

    int side = corner % 2, row = corner / 2;
    float h = float(row) / float(u_fin_rows);
    vec3 p = mix(fin_vertex(e.x, 2 * row).xyz, fin_vertex(e.y, 2 * row).xyz, at);
    vec3 t = mix(fin_vertex(e.x, 2 * row + 1).xyz, fin_vertex(e.y, 2 * row + 1).xyz, at);
    // Its own length and lean (outline_shape), as the fur texture's strands.
    float scale = length(mat3(u_model)[0]);
    vec3 along = root_b - root_a;
    along = dot(along, along) > 1e-20 ? normalize(along) * (u_hair_width / scale) : vec3(0.0);
    vec4 shape = outline_shape(root, p, along, outline_random(seed, 1u), outline_random(seed, 2u), h);
    vec4 world = u_model * vec4(shape.xyz, 1.0);
    vec3 T = normalize(mat3(u_model) * t);

    // The ribbon across the hair as the eye sees it, its half width in
    // pixels from the projection's derivative along it.
    vec3 to_eye = u_eye - world.xyz;
    vec3 across = cross(T, to_eye);
    float across_len = length(across);
    across = across_len > 1e-12 ? across / across_len : vec3(0.0);
    vec4 c = u_view_proj * world, d = u_view_proj * vec4(across, 0.0);
    float px_per_unit = length(0.5 * u_viewport * (d.xy * c.w - c.xy * d.w)) / max(c.w * c.w, 1e-12);
    float half_px = 0.5 * u_hair_width * (1.0 - u_taper * h) * scale * px_per_unit;
    float drawn = max(half_px, 0.5);
    world.xyz += across * ((side == 0 ? -1.0 : 1.0) * drawn / max(px_per_unit, 1e-12));
    v_alpha = min(alpha * half_px / drawn, 1.0);

    vec4 ex = fin_vertex(e.x, 2 * PELT_FIN_HEIGHTS + 1); // uv, colour bytes two a float
    vec4 hair_color = vec4(floor(ex.z / 256.0), mod(ex.z, 256.0), floor(ex.w / 256.0), mod(ex.w, 256.0)) / 255.0;
    vec3 mul;
    float spec;
    fur_light_terms(T, mat3(u_model) * nd.xyz, world.xyz, h, mul, spec);
    vec3 root_color = groom_root_color(u_color, hair_color);
    vec3 tip_color = groom_tip_color(u_color, u_tip_color, hair_color);
    // The strand's shade as the fur texture draws it, 0.4 to 1 (sRGB).
    float shade = shade_decode(0.4 + 0.6 * outline_random(seed, 4u));
    v_color = wet_color(mix(root_color, tip_color, h) * shade * mul, fur_wetness, u_wet_darken)
            + spec * (u_specular * u_light_color);
    gl_Position = u_view_proj * world;
}
