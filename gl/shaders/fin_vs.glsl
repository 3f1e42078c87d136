// All fins in one instanced draw: an instance is PELT_FIN_CHUNK fins (one
// instance per fin costs llvmpipe more than the fin itself), fin
// gl_InstanceID * PELT_FIN_CHUNK + gl_VertexID / (2 (rows + 1)) of
// this frame's fin table; the vertex is a point of a strip up the fin (row
// = corner / 2 of rows + 1, side = corner % 2: vertex a or b; fewer rows
// when the fur is short on screen). Each side rises along its
// vertex's displaced strand, the same beta + phi + shear as the shells
// (shell_vs.glsl), so fins bend, curl and comb with them. A fin the fade
// makes invisible collapses to one point outside the view: no fragments.
uniform highp usampler2D u_fin_edges; // PELT_UNIT_FIN_EDGES: a, b, start bits
uniform int u_fin_count;              // fins in the table this frame
uniform int u_fin_rows;               // quads up a fin this frame, 1..PELT_FIN_ROWS

uniform highp sampler2D u_vertices; // PELT_UNIT_VERTICES
uniform highp sampler2D u_tips;     // PELT_UNIT_TIPS
uniform highp usampler2D u_groom;   // PELT_UNIT_GROOM
uniform sampler2D u_mask;           // PELT_UNIT_MASK
uniform int u_unfaded;              // 1: no fade (Lengyel Fig. 4e, for comparison)

out vec2 v_uv;
out vec2 v_fin_uv;
out float v_density;
out float v_fade;
out vec3 v_root;      // groomed root and tip colours
out vec3 v_tip;
out vec3 v_light_mul; // fur_light_terms, per vertex as on the shells
out vec3 v_light_add;

ivec2 table_at(int i)
{
    return ivec2(i % PELT_TABLE_WIDTH, i / PELT_TABLE_WIDTH);
}

vec4 vertex_texel(uint v, int k)
{
    return texelFetch(u_vertices, table_at(int(v) * PELT_TABLE_TEXELS + k), 0);
}

uint groom_word(uint v, int k)
{
    return texelFetch(u_groom, table_at(int(v) * PELT_GROOM_WORDS + k), 0).r;
}

void main()
{
    int corners = 2 * (u_fin_rows + 1);
    int fin = gl_InstanceID * PELT_FIN_CHUNK + gl_VertexID / corners;
    int corner = gl_VertexID % corners;
    if (fin >= u_fin_count) { // the last chunk's spare fins
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        return;
    }
    uvec3 e = texelFetch(u_fin_edges, table_at(fin), 0).xyz;
    uvec2 a_edge = e.xy;
    float a_start = uintBitsToFloat(e.z);
    int side = corner % 2;
    float h = float(corner / 2) / float(u_fin_rows);
    uint vi = side == 0 ? a_edge.x : a_edge.y, other = side == 0 ? a_edge.y : a_edge.x;
    // This side's position and normal serve the strand too; the other
    // end's two texels complete the fin normal.
    vec4 t0 = vertex_texel(vi, 0);
    vec3 n_raw = vertex_texel(vi, 1).xyz;
    vec3 p_other = vertex_texel(other, 0).xyz, n_other = vertex_texel(other, 1).xyz;
    vec3 pa = side == 0 ? t0.xyz : p_other, pb = side == 0 ? p_other : t0.xyz;
    vec3 na = side == 0 ? n_raw : n_other, nb = side == 0 ? n_other : n_raw;
    vec3 fin_n = normalize(mat3(u_model) * fin_normal(pa, pb, na, nb));
    v_fade = u_unfaded != 0 ? 1.0 : fin_fade(fin_n, u_view_dir);
    // The fragment stage drops coverage below 0.05, so a fin faded below
    // that draws nothing: collapse it here, before its other fetches.
    if (v_fade < 0.05) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        return;
    }
    vec3 n = normalize(n_raw);
    vec3 u = normalize(vertex_texel(vi, 2).xyz);
    vec3 v = cross(n, u) * t0.w;
    vec4 uvs = vertex_texel(vi, 3);
    vec3 comb = vertex_texel(vi, 4).xyz;
    vec3 tip = texelFetch(u_tips, table_at(int(vi)), 0).xyz;
    vec2 lean = vec2(uintBitsToFloat(groom_word(vi, 0)), uintBitsToFloat(groom_word(vi, 1)));
    float s = uintBitsToFloat(groom_word(vi, 2)) * u_fin_length;
    uint c = groom_word(vi, 4);
    vec4 hair_color = vec4(float(c & 255u), float((c >> 8) & 255u), float((c >> 16) & 255u),
                           float(c >> 24)) / 255.0;
    v_root = groom_root_color(u_color, hair_color);
    v_tip = groom_tip_color(u_color, u_tip_color, hair_color);
    v_density = uintBitsToFloat(groom_word(vi, 3));
    float rho = 0.0; // wetness straightens the curl; a dry frame reads no mask
#ifdef PELT_WET
    rho = textureLod(u_mask, uvs.xy, 0.0).a;
#endif
    float L = u_length * s;
    float K = u_curl_radius * s;
    vec3 shear = fur_groom_shear(comb, u_slant, u, v, lean);
    vec3 offset = fur_bend(n, L, tip * s, h) + fur_curl(u, v, u_curl_frequency, K, rho, h)
                + fur_comb(shear, L, 1.0, h);
    vec3 t = fur_tangent_combed(n, L, tip * s, u, v, shear, u_curl_frequency, K, rho, 1.0, h);
    vec4 world = u_model * vec4(t0.xyz + offset, 1.0);
    // Along the fin: the edge's world length at the shells' texture scale.
    float edge = length(mat3(u_model) * (pb - pa)) * u_tiling;
    v_fin_uv = vec2(a_start + float(side) * edge, h);
    v_uv = uvs.xy;
    fur_light_terms(mat3(u_model) * t, mat3(u_model) * n, world.xyz, h, v_light_mul, v_light_add);
    gl_Position = u_view_proj * world;
}
