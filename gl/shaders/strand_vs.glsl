// The strand reference (gl/strands_pass.c): every hair a ribbon of
// u_strand_segments quads, 6 vertices a quad, turned to face the eye
// and as wide as the hair (its radius from root to tapered tip), lit per
// vertex by the hairs' own model (fur_light.glsl) with the hair's tangent.
// The hairs' points come from core/fur/strand_ref.c in a buffer texture.
uniform highp samplerBuffer u_strands; // PELT_UNIT_STRANDS: 2 (segments + 1) + 2 texels a hair
uniform int u_strand_segments;         // core's pelt__strand_ref_segments

#ifdef PELT_LIGHT_PASS
// The light pass (gl/shadow_pass.c): the hairs drawn from the light into
// its opacity slices, so that the reference's hairs shade each other by
// their own coverage, not the shells'.
out float v_light_depth; // depth from the light
out float v_cover;       // the share of the drawn ribbon the hair covers
#else
out vec3 v_color;
#endif

// The unit direction across a hair of tangent T seen along d (towards the
// eye or the light): the ribbon's width lies along it.
vec3 ribbon_across(vec3 T, vec3 d)
{
    vec3 across = cross(T, d);
    float len = length(across);
    return len > 1e-8 ? across / len : normalize(cross(T, vec3(0.0, 1.0, 0.0)) + vec3(1e-4));
}

void main()
{
    int per_hair = 6 * u_strand_segments;
    int hair = gl_VertexID / per_hair;
    int corner = gl_VertexID % per_hair;
    int seg = corner / 6, k = corner % 6;
    // Two triangles a quad: (a-, a+, b-), (a+, b+, b-).
    int point = seg + ((k == 2 || k == 4 || k == 5) ? 1 : 0);
    float side = (k == 1 || k == 3 || k == 4) ? 1.0 : -1.0;
    int end = 2 * (u_strand_segments + 1); // the hair's points end here (core/fur/strand_ref.h)
    int base = hair * (end + 2);
    vec4 pr = texelFetch(u_strands, base + 2 * point);
    vec4 th = texelFetch(u_strands, base + 2 * point + 1);
    vec4 ns = texelFetch(u_strands, base + end);
    vec4 ex = texelFetch(u_strands, base + end + 1);
    vec4 hair_color = vec4(floor(ex.z / 256.0), mod(ex.z, 256.0), floor(ex.w / 256.0), mod(ex.w, 256.0)) / 255.0;

    vec4 world = u_model * vec4(pr.xyz, 1.0);
    vec3 T = normalize(mat3(u_model) * th.xyz);
    float scale = length(mat3(u_model)[0]);
#ifdef PELT_LIGHT_PASS
    // A ribbon facing the light, at least a texel of the maps wide so that
    // it covers the texels it crosses; each covers the hair's share of it.
    vec3 across_light = ribbon_across(T, u_light_dir);
    float texels_per_unit = length((u_light_matrix * vec4(across_light, 0.0)).xy) / u_shadow_map.z;
    float half_width = pr.w * scale * texels_per_unit; // texels
    float drawn = max(half_width, 0.75);
    v_cover = half_width / drawn;
    vec3 lc = shadow_coord(world.xyz + across_light * (side * drawn / max(texels_per_unit, 1e-8)));
    v_light_depth = lc.z;
    gl_Position = vec4(lc * 2.0 - 1.0, 1.0);
#else
    vec3 to_eye = u_eye - world.xyz;
    vec3 across = ribbon_across(T, to_eye);
    world.xyz += across * (side * pr.w * scale);
    // The hair is a tube: seen along its length, each piece's ends show as
    // half ellipses r |T.V| deep along the projected tangent, which a flat
    // ribbon leaves out (a hair seen end-on would cover nothing where the
    // tube covers the disc of its root). Each piece's quad reaches out at
    // both its ends by the ellipse's area-equivalent depth, pi/4 r |T.V|;
    // seen from the side nothing moves.
    float piece_end = point == seg ? -1.0 : 1.0; // this piece's start or its end
    vec3 V = to_eye / max(length(to_eye), 1e-8);
    float t_dot_v = dot(T, V);
    vec3 along_screen = T - t_dot_v * V;
    float along_len = length(along_screen);
    if (along_len > 1e-6) world.xyz += along_screen / along_len * (piece_end * abs(t_dot_v) * 0.78539816 * pr.w * scale);

    vec3 mul;
    float spec;
    fur_wetness = ex.x; // the wetness at the root: wet hair shines (fur_light_terms)
    fur_light_terms(T, mat3(u_model) * ns.xyz, world.xyz, th.w * ex.y, mul, spec);
    vec3 root = groom_root_color(u_color, hair_color);
    vec3 tip = groom_tip_color(u_color, u_tip_color, hair_color);
    // The strand's shade is sRGB like the shells' fur texture: decoded (linear light).
    // Wet hair is darker and more saturated, as the shells' (shell_fs.glsl).
    v_color = wet_color(mix(root, tip, th.w) * shade_decode(ns.w) * mul, ex.x, u_wet_darken)
            + spec * (u_specular * u_light_color);
    gl_Position = u_view_proj * world;
#endif
}
