// All fins in one instanced draw: an instance is PELT_FIN_CHUNK fins (one
// instance per fin costs llvmpipe more than the fin itself), fin
// gl_InstanceID * PELT_FIN_CHUNK + gl_VertexID / (2 (rows + 1)) of this
// frame's fin table; the vertex is a point of a strip up the fin (row =
// corner / 2 of rows + 1, side = corner % 2: end a or b; fewer rows when
// the fur is short on screen). Each side rises along its vertex's
// displaced strand, worked out once a frame per vertex on the CPU by the C
// references of shell_vs.glsl (core/fur/fin_frame.c), so fins bend, curl,
// comb and are groomed with the shells. The fade comes with the fin.
// The tables (fin_table.glsl): u_fin_edges holds each fin's ends, start
// and fade bits; u_mask's wetness makes wet fins shine like wet shells.
uniform int u_fin_first;               // this draw's first fin in the table
uniform int u_fin_count;               // this draw's end in the table (wet fins follow dry ones)
uniform int u_outline_on;              // 1: the outline's hairs take over where the fur is short on screen

out vec2 v_uv;
out vec2 v_fin_uv;
out float v_density;
out float v_fade;
out vec3 v_root;      // groomed root and tip colours, lit per vertex as on
out vec3 v_tip;       // the shells (fur_light_terms' mul folded in)
out float v_spec;     // fur_light_terms' specular weight
#ifdef PELT_RINGLETS
// The ringlet's own light (own_light.glsl), as the shells': the reach the
// free hair was lit with and the hair frame's dots; the frame's u runs
// along the fin, the way the fin texture draws the curl sideways.
out vec2 v_light;
out vec3 v_ring_l;
out vec3 v_ring_e;
out vec3 v_ring_g;
#endif
#ifdef PELT_WET
// The edge's mask uv per unit of the fin texture's u: the way along the fin
// a tuft's pull moves the hair the fin shows (clump_fin_shift).
flat out vec2 v_clump_dir;
#endif

void main()
{
    int corners = 2 * (u_fin_rows + 1);
    int fin = u_fin_first + gl_InstanceID * PELT_FIN_CHUNK + gl_VertexID / corners;
    int corner = gl_VertexID % corners;
    if (fin >= u_fin_count) { // the last chunk's spare fins
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        return;
    }
    uvec4 e = texelFetch(u_fin_edges, table_at(fin), 0);
    int side = corner % 2, row = corner / 2;
    float h = float(row) / float(u_fin_rows);
    uint vi = side == 0 ? e.x : e.y;
    vec3 p = fin_vertex(vi, 2 * row).xyz;
    vec3 t = fin_vertex(vi, 2 * row + 1).xyz;
    vec4 nd = fin_vertex(vi, 2 * PELT_FIN_HEIGHTS);     // normal, density
    vec4 ex = fin_vertex(vi, 2 * PELT_FIN_HEIGHTS + 1); // uv, colour bytes two a float
    vec4 hair_color = vec4(floor(ex.z / 256.0), mod(ex.z, 256.0), floor(ex.w / 256.0), mod(ex.w, 256.0)) / 255.0;
    v_density = nd.w;
    v_fade = uintBitsToFloat(e.w);
    if (u_outline_on != 0) {
        // The outline's hairs take the fin's place as its hair shortens on
        // screen (fin_outline_share, the same for the whole fin), and
        // gone, the fin collapses.
        float wet;
        v_fade *= 1.0 - fin_outline_share(e.x, e.y, wet);
        if (v_fade <= 0.0) {
            gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
            return;
        }
    }
    v_uv = ex.xy;
    vec4 world = u_model * vec4(p, 1.0);
    fur_wetness = textureLod(u_mask, ex.xy, 0.0).a;
    vec3 light_mul;
    vec3 world_t = mat3(u_model) * t, world_n = mat3(u_model) * nd.xyz;
    fur_light_terms(world_t, world_n, world.xyz, h, light_mul, v_spec);
    // Along the fin: the edge's world length at the shells' texture scale.
    vec3 root_a = fin_vertex(e.x, 0).xyz, root_b = fin_vertex(e.y, 0).xyz;
    vec3 along = mat3(u_model) * (root_b - root_a);
    float edge = length(along) * u_tiling;
#ifdef PELT_WET
    vec2 uv_a = fin_vertex(e.x, 2 * PELT_FIN_HEIGHTS + 1).xy, uv_b = fin_vertex(e.y, 2 * PELT_FIN_HEIGHTS + 1).xy;
    v_clump_dir = edge > 0.0 ? (uv_b - uv_a) / edge : vec2(0.0);
#endif
#ifdef PELT_RINGLETS
    v_light = fur_light_reach.xz;
    vec3 ring_n = normalize(world_n);
    vec3 ring_u = along - ring_n * dot(along, ring_n);
    ring_u = dot(ring_u, ring_u) > 1e-20 ? normalize(ring_u) : normalize(cross(ring_n, vec3(0.3, 0.5, 0.8)));
    ringlet_frame_dots(normalize(world_t), ring_u, cross(ring_n, ring_u), normalize(u_light_dir),
                       normalize(world.xyz - u_eye), v_ring_l, v_ring_e, v_ring_g);
    light_mul = ringlet_light_mul(light_mul, fur_light_reach.z);
#endif
    v_root = groom_root_color(u_color, hair_color) * light_mul;
    v_tip = groom_tip_color(u_color, u_tip_color, hair_color) * light_mul;
    v_fin_uv = vec2(uintBitsToFloat(e.z) + float(side) * edge, h);
    gl_Position = u_view_proj * world;
}
