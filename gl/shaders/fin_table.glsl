// The fin pass's tables, read by the fins' vertex stage (fin_vs.glsl) and
// the outline's hairs' (outline_vs.glsl): a row after row of
// PELT_TABLE_WIDTH texels; a fin vertex is PELT_FIN_VERTEX_TEXELS of them
// (core/fur/fur_gpu.h: its strand's points and tangents, its normal and
// groomed density, its uv and colour). Comes after outline_hair.glsl.
uniform highp usampler2D u_fin_edges;   // PELT_UNIT_FIN_EDGES: the fins' or the hairs' table of this draw
uniform highp sampler2D u_fin_vertices; // PELT_UNIT_FIN_VERTICES
uniform int u_fin_rows;                 // quads up a fin (and its hairs) this frame, 1..PELT_FIN_ROWS
uniform sampler2D u_mask;               // PELT_UNIT_MASK
uniform vec2 u_viewport;                // pixels (the outline's hairs' share)

ivec2 table_at(int i)
{
    return ivec2(i % PELT_TABLE_WIDTH, i / PELT_TABLE_WIDTH);
}

vec4 fin_vertex(uint v, int k)
{
    return texelFetch(u_fin_vertices, table_at(int(v) * PELT_FIN_VERTEX_TEXELS + k), 0);
}

// The share of the fin between fin vertices a and b that its outline hairs
// carry (outline_share), the rest its quad: from its hair's length on
// screen at the edge's middle and its two ends' wetness (in `wet`), so
// that the fin's quad and its hairs, each working it out, agree.
float fin_outline_share(uint a, uint b, out float wet)
{
    vec3 root_mid = 0.5 * (fin_vertex(a, 0).xyz + fin_vertex(b, 0).xyz);
    vec3 top_mid = 0.5 * (fin_vertex(a, 2 * u_fin_rows).xyz + fin_vertex(b, 2 * u_fin_rows).xyz);
    vec4 rc = u_view_proj * (u_model * vec4(root_mid, 1.0)), tc = u_view_proj * (u_model * vec4(top_mid, 1.0));
    float px = length(0.5 * u_viewport * (tc.xy / max(tc.w, 1e-6) - rc.xy / max(rc.w, 1e-6)));
    wet = max(textureLod(u_mask, fin_vertex(a, 2 * PELT_FIN_HEIGHTS + 1).xy, 0.0).a,
              textureLod(u_mask, fin_vertex(b, 2 * PELT_FIN_HEIGHTS + 1).xy, 0.0).a);
    return outline_share(px, wet);
}
