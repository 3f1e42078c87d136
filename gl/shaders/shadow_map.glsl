// Deep opacity maps (docs/shadows.md), the receiving side, mirrored by
// core/fur/shadow_map.c: the skin's depth from the light, and the fur's
// opacity in up to 8 slices (two RGBA layers) of a slab in front of it.
// Reads the frame block, so it comes after blocks.glsl.
uniform highp sampler2D u_shadow_depth;        // PELT_UNIT_SHADOW_DEPTH: skin depth, nearest
uniform highp sampler2DArray u_shadow_opacity; // PELT_UNIT_SHADOW_OPACITY: slice sums, linear

// The weights a fragment at slice position k adds to slices 0-3 and 4-7
// of S (pelt__shadow_slice_weight): a one-slice ramp, the last slice all.
void shadow_slice_weights(float k, float S, out vec4 w0, out vec4 w1)
{
    w0 = clamp(vec4(1.0, 2.0, 3.0, 4.0) - k, 0.0, 1.0);
    w1 = clamp(vec4(5.0, 6.0, 7.0, 8.0) - k, 0.0, 1.0);
    w0 = mix(w0, vec4(1.0), step(vec4(S - 1.0), vec4(0.0, 1.0, 2.0, 3.0)));
    w1 = mix(w1, vec4(1.0), step(vec4(S - 1.0), vec4(4.0, 5.0, 6.0, 7.0)));
}

// What a fur fragment of coverage a adds (pelt__shadow_sigma).
float shadow_sigma(float a)
{
    return -log(1.0 - clamp(a, 0.0, 0.98));
}

// What a light pass's fragment at map texel `texel`, `depth` from the
// light, of coverage a adds to slices 0-3 (s0) and 4-7 (s1): its
// -ln(1 - a) at and behind its depth in the slab in front of the skin.
// False where it lies behind the skin: in the body's shadow, it shades
// nothing that is lit (the caller discards it).
bool shadow_slices_add(ivec2 texel, float depth, float a, out vec4 s0, out vec4 s1)
{
    s0 = s1 = vec4(0.0);
    float z_skin = texelFetch(u_shadow_depth, texel, 0).r;
    if (depth - u_shadow_slab.z > z_skin) return false;
    float k = (depth - (z_skin - u_shadow_slab.x)) / u_shadow_slab.x * u_shadow_map.y;
    shadow_slice_weights(k, u_shadow_map.y, s0, s1);
    float sigma = shadow_sigma(a);
    s0 *= sigma;
    s1 *= sigma;
    return true;
}

// The opacity in front of slice position k (pelt__shadow_opacity).
float shadow_opacity(vec4 s0, vec4 s1, float S, float k)
{
    float x = clamp(k, 0.0, S);
    float i = min(floor(x), S - 1.0);
    float f = x - i; // 1 at x = S
    float sums[9];
    sums[0] = 0.0;
    sums[1] = s0.x; sums[2] = s0.y; sums[3] = s0.z; sums[4] = s0.w;
    sums[5] = s1.x; sums[6] = s1.y; sums[7] = s1.z; sums[8] = s1.w;
    int j = int(i);
    return mix(sums[j], sums[j + 1], f);
}

// Light-space position: (s, t) on the maps, d the depth from the light.
vec3 shadow_coord(vec3 world)
{
    return (u_light_matrix * vec4(world, 1.0)).xyz;
}

// One tap of the maps at light-space point c moved by o on the maps: 0
// behind the skin (more than `bias`, depth units); else exp(-density x
// the fur's opacity in front).
float shadow_tap(vec3 c, float bias, vec2 o)
{
    float S = u_shadow_map.y, slab = u_shadow_slab.x;
    float z_skin = textureLod(u_shadow_depth, c.xy + o, 0.0).r;
    if (c.z - bias > z_skin) return 0.0; // behind the skin: the body's own shadow
    // Half a slice towards the light: the receiver's own hair, and what
    // lies level with it, does not shade it.
    float k = (c.z - (z_skin - slab)) / slab * S - 0.5;
    vec4 s0 = textureLod(u_shadow_opacity, vec3(c.xy + o, 0.0), 0.0);
    vec4 s1 = S > 4.0 ? textureLod(u_shadow_opacity, vec3(c.xy + o, 1.0), 0.0) : vec4(0.0);
    return exp(-u_shadow_slab.y * shadow_opacity(s0, s1, S, k));
}

// The transmittance towards the light at a world point; 1 outside the
// maps. `taps` 4 soften the edges with a rotated grid of radius softness
// texels (percentage-closer filtering); 1 is the fur's per-vertex lookup,
// whose interpolation over the triangle softens it already.
float shadow_transmittance(vec3 world, float bias, int taps)
{
    vec3 c = shadow_coord(world);
    if (any(lessThan(c.xy, vec2(0.0))) || any(greaterThan(c.xy, vec2(1.0)))) return 1.0;
    c.z = min(c.z, 1.0);
    if (taps == 1) return shadow_tap(c, bias, vec2(0.0));
    vec2 r = vec2(u_shadow_map.z * u_shadow_map.w);
    return 0.25 * (shadow_tap(c, bias, r * vec2(-0.25, -0.75)) + shadow_tap(c, bias, r * vec2(0.75, -0.25)) +
                   shadow_tap(c, bias, r * vec2(0.25, 0.75)) + shadow_tap(c, bias, r * vec2(-0.75, 0.25)));
}

// The light's direct term at a receiver: 1 without shadow maps.
float shadow_light(vec3 world, float bias, int taps)
{
    return u_shadow_map.x > 0.5 ? shadow_transmittance(world, bias, taps) : 1.0;
}
