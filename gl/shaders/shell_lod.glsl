// Lengyel et al. 2001 §2.4 in the shell draw: instance i (inner first) of
// a level is the shell j = shells.x - 1 - i from the outside, at layer
// N - 1 - j * shells.y; the even shells (from the outside) blend into the
// next level's composite, the odd ones fade out. shells and next are the
// shell pass's uniforms (pelt__lod_shell_uniforms). Mirrors
// pelt__lod_shell_instance (core/fur/lod.c).
// The view's shell budget: pelt__lod_view_blend and pelt__lod_view_texel
// (core/fur/lod.c).
// The shells' spacing on screen: side-on, side_px, foreshortened by sin
// theta (view_spacing in core/fur/lod.c).
float shell_view_spacing(float side_px, float n_dot_v)
{
    float c = min(abs(n_dot_v), 1.0);
    return side_px * sqrt(1.0 - c * c);
}

// A curled hair's sideways drift per layer counts too, seen whole face-on.
float shell_view_blend(float side_px, float n_dot_v, float target_px, float drift)
{
    float fore = shell_view_spacing(side_px, n_dot_v), across = side_px * drift;
    float spacing = max(sqrt(fore * fore + across * across), 1e-6);
    return clamp(log2(target_px / spacing), 0.0, 1.0);
}

// pelt__lod_shell_lean_drift (core/fur/lod.c): a leaning hair's sideways
// move per layer spacing, tan of the angle between t and n.
const float SHELL_LEAN_MIN_COS = 0.05; // PELT__SHELL_LEAN_MIN_COS
float shell_lean_drift(vec3 t, vec3 n)
{
    float across = length(cross(t, n));
    float least = SHELL_LEAN_MIN_COS * sqrt(dot(t, t) * dot(n, n));
    return across > 0.0 ? across / max(abs(dot(t, n)), least) : 0.0;
}

// pelt__lod_sub_shell_need (core/fur/lod.c): how far a vertex needs the
// frame's close-up sub shells, from its layers' spacing on screen.
const float SUB_SHELL_PIXELS = 1.4; // PELT__SUB_SHELL_PIXELS
float sub_shell_need(float side_px, float n_dot_v, float drift)
{
    float fore = shell_view_spacing(side_px, n_dot_v), across = side_px * drift;
    float spacing = sqrt(fore * fore + across * across);
    return clamp((spacing / SUB_SHELL_PIXELS - 0.35) / 0.65, 0.0, 1.0);
}

// pelt__lod_sub_shell_exponent: sub shell `part` of k's exponent in its
// layer's coverage where the vertex needs them `need`.
float sub_shell_exponent(float part, float k, float need)
{
    if (!(k > 1.0)) return 1.0;
    return part < k - 1.5 ? need / k : 1.0 - (k - 1.0) * need / k;
}

// pelt__lod_back_hidden (core/fur/lod.c).
bool shell_back_hidden(float n_dot_v, float reach)
{
    return reach >= 0.0 && n_dot_v < -reach;
}

const float FIN_TEXTURE_ANISO = 4.0;   // PELT__FIN_TEXTURE_ANISO
const float FUR_TEXTURE_SHARPEN = 0.5; // PELT__FUR_TEXTURE_SHARPEN

// footprint_sides (core/fur/lod.c): a texture read's footprint from its uv
// derivatives dx, dy and the texture's size, the squared lengths of its
// longer (x) and shorter (y) side in texels.
vec2 footprint_sides(vec2 dx, vec2 dy, float texels)
{
    float a = dot(dx, dx) * texels * texels, b = dot(dy, dy) * texels * texels;
    return vec2(max(a, b), min(a, b));
}

// pelt__lod_fin_texture_aniso (core/fur/lod.c): the fins' max_aniso from
// the footprint's sides (derivatives in texels).
float fin_texture_aniso(vec2 dx, vec2 dy)
{
    float shorter = sqrt(footprint_sides(dx, dy, 1.0).y);
    return 1.0 + (FIN_TEXTURE_ANISO - 1.0) * clamp(2.0 - shorter, 0.0, 1.0);
}

const float FUR_TEXTURE_ROW_PX = 0.7; // PELT__FUR_TEXTURE_ROW_PX

// pelt__lod_fur_texture_aniso (core/fur/lod.c): how many texels of the
// footprint's long side may fall to a pixel, at most max_aniso, from the
// shells' spacing on screen (side_px side-on, foreshortened by n_dot_v).
float fur_texture_aniso(float side_px, float n_dot_v, float max_aniso)
{
    float spacing = shell_view_spacing(side_px, n_dot_v);
    return 1.0 + (max_aniso - 1.0) * clamp(2.0 - spacing / FUR_TEXTURE_ROW_PX, 0.0, 1.0);
}

// pelt__lod_fur_texture (core/fur/lod.c): the fur texture's mip level
// from the footprint's sides (fur-uv derivatives dx, dy, in tiles), its
// longer side over max_aniso or its shorter side.
float fur_texture_lod(vec2 dx, vec2 dy, float texels, float max_aniso)
{
    vec2 sides = footprint_sides(dx, dy, texels);
    return 0.5 * log2(max(max(sides.x / (max_aniso * max_aniso), sides.y), 1e-12));
}

// pelt__lod_shell_fur_texture (core/fur/lod.c): the shells read half a
// level finer where the footprint is round, so the nearest mip level is
// the footprint's rounded down, not up; none from twice as long as wide.
float shell_fur_texture_lod(vec2 dx, vec2 dy, float texels, float max_aniso)
{
    vec2 sides = footprint_sides(dx, dy, texels);
    float elongation = sqrt(sides.x / max(sides.y, 1e-12));
    return fur_texture_lod(dx, dy, texels, max_aniso) - FUR_TEXTURE_SHARPEN * clamp(2.0 - elongation, 0.0, 1.0);
}

// pelt__lod_fur_texture_taps (core/fur/lod.c): the fetches a shell
// fragment takes along its footprint's longer side, at most max_taps, and
// the level each reads at.
float fur_texture_taps(vec2 dx, vec2 dy, float texels, float max_aniso, float max_taps, out float lod)
{
    vec2 sides = footprint_sides(dx, dy, texels);
    float n = clamp(ceil(sqrt(sides.x / max(sides.y, 1e-12)) / max_aniso), 1.0, max_taps);
    lod = n > 1.0 ? fur_texture_lod(dx, dy, texels, max_aniso * n) : shell_fur_texture_lod(dx, dy, texels, max_aniso);
    return n;
}

// pelt__lod_fur_edge_gain (core/fur/lod.c): how many pixels a texel of
// the fur texture spans along the footprint's longer side, at least 1.
float fur_edge_gain(vec2 dx, vec2 dy, float texels)
{
    return max(inversesqrt(max(footprint_sides(dx, dy, texels).x, 1e-12)), 1.0);
}

// pelt__lod_fur_edge (core/fur/lod.c): the premultiplied texel hair with
// its coverage steepened by gain about the hair's edge (coverage 0.5).
vec4 fur_edge(vec4 hair, float gain)
{
    float a = clamp((hair.a - 0.5) * gain + 0.5, 0.0, 1.0);
    return hair * (a / max(hair.a, 1e-4));
}

vec4 shell_view_texel(float w, vec4 hair)
{
    return hair * (1.0 + w * (1.0 - hair.a));
}

float shell_instance(float i, vec4 shells, vec2 next, float N, out vec3 slices, out float alpha)
{
    float j = shells.x - 1.0 - i;
    bool kept = mod(j, 2.0) < 0.5;
    float own = shells.z + i;
    slices = vec3(own, kept ? next.x + next.y - 1.0 - floor(j * 0.5) : own, kept ? shells.w : 0.0);
    alpha = kept ? 1.0 : 1.0 - shells.w;
    return N - 1.0 - j * shells.y;
}

// pelt__lod_shell_overcount_cap (core/fur/lod.c): the most shells a ray
// stays in one hair across, for `layers` layers.
const float SHELL_OVERCOUNT_MAX = 3.0;           // PELT__SHELL_OVERCOUNT_MAX
const float SHELL_OVERCOUNT_REACH = 3.0 / 32.0;  // PELT__SHELL_OVERCOUNT_REACH
float shell_overcount_cap(float layers)
{
    return max(SHELL_OVERCOUNT_MAX, layers * SHELL_OVERCOUNT_REACH);
}

// pelt__lod_shell_overcount (core/fur/lod.c): how many consecutive shells
// a ray of sight crosses inside one hair, from the hair's width over the
// layer spacing, |T.V| and the hair's own drift per spacing; least .. cap
// (least 1 but where the surface is seen edge-on: shell_edge_least).
float shell_overcount(float width_over_spacing, float cos_view, float drift, float least, float cap)
{
    float c = clamp(abs(cos_view), 1e-3, 1.0);
    float tan_view = sqrt(max(1.0 - c * c, 0.0)) / c;
    float k = width_over_spacing / max(sqrt(tan_view * tan_view + drift * drift), 1e-3);
    return clamp(k, least, cap);
}

// pelt__lod_shell_stack_cos (core/fur/lod.c): shell_overcount's cos_view
// for a hair along t seen along V over a surface of normal n: the ray
// moves sideways against the hair by |t/(t.n) - V/(V.n)| a unit of height.
float shell_stack_cos(vec3 t, vec3 V, vec3 n)
{
    float tn = dot(t, n), vn = dot(V, n);
    float along = abs(tn * vn);
    vec3 across = t * vn - V * tn;
    float len = sqrt(along * along + dot(across, across));
    return len > 1e-12 ? along / len : 0.0;
}

// pelt__lod_shell_gap (core/fur/lod.c): the gap between this shell's
// section of a hair and the next shell's, seen from V, in fur-texture
// tiles (xy), and the weight of the read across it (z), where the shells
// stand spacing_px apart on screen seen side-on (negative: not known).
const float SHELL_GAP_FULL = 0.15;    // PELT__SHELL_GAP_FULL
const float SHELL_GAP_NONE = 0.35;    // PELT__SHELL_GAP_NONE
const float SHELL_GAP_MIN_COS = 0.05; // PELT__SHELL_GAP_MIN_COS
const float SHELL_GAP_OUTLINE_NONE = 0.1; // PELT__SHELL_GAP_OUTLINE_NONE
const float SHELL_GAP_OUTLINE_FULL = 0.2; // PELT__SHELL_GAP_OUTLINE_FULL
const float SHELL_GAP_PX_NONE = 0.25; // PELT__SHELL_GAP_PX_NONE
const float SHELL_GAP_PX_FULL = 0.6;  // PELT__SHELL_GAP_PX_FULL
vec3 shell_gap(vec3 n, vec3 t, vec3 V, vec3 u, vec3 v, float step, float uv_per_world, float spacing_px)
{
    float vn = dot(V, n);
    float g = 1.0 - smoothstep(SHELL_GAP_FULL, SHELL_GAP_NONE, abs(vn));
    g *= smoothstep(SHELL_GAP_OUTLINE_NONE, SHELL_GAP_OUTLINE_FULL, abs(vn));
    if (spacing_px >= 0.0) g *= smoothstep(SHELL_GAP_PX_NONE, SHELL_GAP_PX_FULL, spacing_px);
    vn = vn < 0.0 ? min(vn, -SHELL_GAP_MIN_COS) : max(vn, SHELL_GAP_MIN_COS);
    vec3 d = V * (step * dot(t, n) / vn) - t * step;
    return vec3(dot(d, u) * uv_per_world, dot(d, v) * uv_per_world, g);
}

// pelt__lod_shell_edge_least (core/fur/lod.c): the least count a shell may
// take where the eye sees the surface at n_dot_v, so that seen edge-on it
// stands for up to `depth` crossings of the hair: 1 / depth edge-on, 1
// from SHELL_EDGE_REACH.
const float SHELL_EDGE_REACH = 0.7; // PELT__SHELL_EDGE_REACH
float shell_edge_least(float n_dot_v, float depth)
{
    // 1 - (1 - 1/depth)(1 - s), not mix(): exactly 1 at depth 1.
    return 1.0 - (1.0 - 1.0 / max(depth, 1.0)) * (1.0 - smoothstep(0.0, SHELL_EDGE_REACH, abs(n_dot_v)));
}

// pelt__lod_shell_overcount_alpha: a shell's share when k show the hair.
float shell_overcount_alpha(float a, float k)
{
    return 1.0 - pow(max(1.0 - a, 0.0), 1.0 / max(k, 1.0));
}

// pelt__lod_coverage_log / _share: a shell fragment's coverage in the
// form that composes its powers. Each of the hair's coverage a shared
// among the k shells a ray crosses inside it (shell_overcount_alpha),
// squeezed into a tuft k times as dense (clump_coverage) and shared among
// a layer's k sub shells (sub_shell_alpha) is 1 - (1 - a)^e, e = 1/k:
// together 1 - (1 - a)^(e1 e2 e3), so a fragment takes log2 of 1 - a once
// and exp2 once instead of three powers.
// An opaque hair's log2(0): finite, so that it stays an opaque hair's
// under any positive exponent (exp2 of it is 0), where log2(0) is
// undefined in GLSL.
float coverage_log(float a)
{
    float clear = 1.0 - a;
    return clear > 0.0 ? log2(clear) : -1e30;
}

// log2(1 - 0.05): a coverage below 0.05 draws no hair. PELT__COVERAGE_CLEAR_LOG.
const float COVERAGE_CLEAR_LOG = -0.0740005814;

float coverage_share(float clear_log, float e)
{
    return 1.0 - exp2(clear_log * e);
}

// pelt__lod_shell_hair_span: the hair's width over the layer spacing at h.
float shell_hair_span(float width, float taper, float h, float layers, float length)
{
    return width * (1.0 - taper * clamp(h, 0.0, 1.0)) * layers / max(length, 1e-6);
}

// pelt__lod_shell_hair_drift: how far a hair drifts sideways per layer
// spacing, its ringlet's and the fur texture's own curl.
float shell_hair_drift(float ringlet, float omega, float h, float length, float curl_radius, float curl_omega)
{
    float ring = ringlet * sqrt(1.0 + omega * omega * h * h) / max(length, 1e-6);
    return ring + abs(curl_radius * curl_omega);
}
