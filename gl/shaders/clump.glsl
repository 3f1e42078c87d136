// Clump displacement: Silva et al. Eq. 5 and Alg. 2 as docs/wetness.md reads them.
// The C reference is core/wet/clump.c; keep the two in step. No #version line:
// the renderer concatenates this into the shell fragment shader. Valid as
// GLSL 3.30 core and GLSL ES 3.00 (needs a float precision in scope on ES).

// The wet shells' tufts: the wet programs look up the clumps, but for the
// layers below the tufts' base (PELT_TUFT_BASE, pelt__clump_below_tufts),
// where a clump leaves its hairs where they grew: darkened, no lookup.
#if defined(PELT_WET) && !defined(PELT_TUFT_BASE)
#define PELT_TUFTS 1
#endif

const int CLUMP_KEEP = 0;      // dry texel: draw at p, undisplaced
const int CLUMP_DISPLACED = 1; // draw the hair rooted at q (d = q - p)
const int CLUMP_DISCARD = 2;   // another clump's texel, or q is dry
const float CLUMP_MAX_PULL = 0.95;

// Ringlets (docs/method.md): the fur volume holds Silva's curl drawn strand
// by strand at `levels` amplitudes, full to none, `stride` slices apart. At
// wetness rho: (slice offset of the level below, of the one above, the
// weight of the one above). Mirrors pelt__ringlet_levels.
vec3 ringlet_levels(float rho, float levels, float stride)
{
    if (!(levels > 1.0)) return vec3(0.0);
    float t = clamp(rho, 0.0, 1.0) * (levels - 1.0);
    float k = min(floor(t), levels - 2.0);
    return vec3(k * stride, (k + 1.0) * stride, t - k);
}

// Eq. 5 profile at h = (1+n)/N: (1-w) h' + w (1 + ln h / ln N) with
// h' = (h - 1/N) / (1 - 1/N), clamped: 0 at the first layer, 1 at the tip.
float clump_profile(float h, float w, float N)
{
    if (!(N > 1.0)) return 1.0;
    if (!(h > 0.0)) return 0.0;
    float first = 1.0 / N;
    float lin = (h - first) / (1.0 - first);
    float lg = 1.0 + log(h) / log(N);
    return clamp((1.0 - w) * lin + w * lg, 0.0, 1.0);
}

// Where a tuft starts to gather its hairs (PELT__CLUMP_BASE): below, the
// roots stay spread; above, Eq. 5's profile over the rest of the height.
// Mirrors pelt__clump_tuft_profile.
const float CLUMP_BASE = 0.25;
float clump_tuft_profile(float h, float w, float N)
{
    if (!(N > 1.0)) return 1.0;
    float first = 1.0 / N;
    float t = clamp((h - CLUMP_BASE) / (1.0 - CLUMP_BASE), 0.0, 1.0);
    return clump_profile(first + (1.0 - first) * t, w, N);
}

// How fast the tuft's profile rises at h, per unit of height: its change
// over one layer spacing, centred on h. Mirrors pelt__clump_tuft_slope.
float clump_tuft_slope(float h, float w, float N)
{
    float half_step = 0.5 / max(N, 1.0);
    return (clump_tuft_profile(h + half_step, w, N) - clump_tuft_profile(h - half_step, w, N)) / (2.0 * half_step);
}

// The dots (T.L, T.E) of a hair in a tuft (docs/wetness.md, Tuft light):
// its tangent T is the hair's own unit tangent t plus the tuft's pull
// along the height, the way to the clump centre (mask uv) times d(pull)/dh,
// carried to world units per unit of the hair's length by du and dv,
// normalised. Worked out from the dots the vertex stage interpolates:
// l = (t.L, du.L, dv.L), e = (t.E, du.E, dv.E), g = (t.du, t.dv, du.du,
// dv.dv), m = du.dv. t's dots where the sum vanishes. Mirrors
// pelt__tuft_dots.
vec2 tuft_dots(vec3 l, vec3 e, vec4 g, float m, vec2 to_centre, float slope)
{
    vec2 c = to_centre * slope;
    vec2 d = vec2(l.x + c.x * l.y + c.y * l.z, e.x + c.x * e.y + c.y * e.z);
    float len2 = 1.0 + 2.0 * (c.x * g.x + c.y * g.y) + c.x * c.x * g.z + c.y * c.y * g.w + 2.0 * c.x * c.y * m;
    return len2 > 1e-30 ? d * inversesqrt(len2) : vec2(l.x, e.x);
}

// Strays: a share of the hairs, picked by the strand's id (the fur
// texture's blue channel), stays out of the tufts. Mirrors pelt__clump_stray.
bool clump_stray(float id, float share)
{
    return fract(id * 7.31) < share;
}

// Strays at a fragment the clump lookup did not keep (docs/wetness.md,
// Strays): the tuft's hair pulled in from q (`hair`) is dropped where the
// lookup discarded or if it is a stray; the hair growing here (`own`)
// stands instead if it is a stray. True where `own` is the hair drawn.
bool clump_stray_hair(int clump, inout vec4 hair, vec4 own, float share)
{
    if (clump == CLUMP_DISCARD || clump_stray(hair.b / max(hair.a, 1e-3), share)) hair = vec4(0.0);
    if (own.a > hair.a && clump_stray(own.b / max(own.a, 1e-3), share)) {
        hair = own;
        return true;
    }
    return false;
}

// The texel GL's NEAREST + CLAMP_TO_EDGE picks: clamp(floor(uv*size), 0, size-1),
// clamped as a float so no out-of-range float reaches the int conversion.
vec4 clump_texel(sampler2D mask, vec2 uv)
{
    vec2 size = vec2(textureSize(mask, 0));
    vec2 i = clamp(floor(uv * size), vec2(0.0), size - 1.0);
    return texelFetch(mask, ivec2(i), 0);
}

// A tuft's lean (docs/wetness.md, Tufts lean): the tip stands off the
// clump centre by amount r (x, y) in mask uv, x and y in [-1, 1] from the
// byte a natural clump carries in its radius's lowest bits. Mirrors
// pelt__clump_lean.
vec2 clump_lean(vec4 t, float amount)
{
    uint bits = floatBitsToUint(t.z);
    float a = amount * t.z;
    return a * (vec2(float(bits & 15u), float((bits >> 4u) & 15u)) / 7.5 - 1.0);
}

// Alg. 2 with the inverse mapping q = c + (p - pull lean - c) / (1 - pull),
// pull = min(s rho f(h), 0.95), from p's mask texel t and the profile f =
// clump_tuft_profile(h, w, N), which the shells work out once per layer in
// the vertex stage; `lean` is the tuft's (clump_lean).
int clump_lookup_texel(sampler2D mask, vec4 t, vec2 p, float f, float s, vec2 lean, out vec2 q)
{
    q = p;
    if (!(t.a > 0.0)) return CLUMP_KEEP;
    vec2 o = p - t.xy;
    // p outside the clump: another clump's texel.
    if (length(o) > t.z) return CLUMP_DISCARD;
    float pull = clamp(s * t.a * f, 0.0, CLUMP_MAX_PULL);
    float g = 1.0 / (1.0 - pull);
    o -= pull * lean;
    // The root must lie in this clump: strands from beyond its radius
    // belong to a neighbour, so the clump narrows towards its tip.
    if (length(o) * g > t.z) return CLUMP_DISCARD;
    q = t.xy + o * g;
    if (!(clump_texel(mask, q).a > 0.0)) return CLUMP_DISCARD;
    return CLUMP_DISPLACED;
}

int clump_lookup(sampler2D mask, vec2 p, float h, float w, float N, float s, float lean, out vec2 q)
{
    vec4 t = clump_texel(mask, p);
    return clump_lookup_texel(mask, t, p, clump_tuft_profile(h, w, N), s, clump_lean(t, lean), q);
}

// Coverage of strands squeezed by a factor k (0 < k <= 1) towards the clump
// centre: coverage a seen through a bundle 1/k times as dense,
// 1 - (1 - a)^(1 / k). Mirrors pelt__clump_coverage.
float clump_coverage(float a, float k)
{
    return 1.0 - pow(max(1.0 - a, 0.0), 1.0 / k);
}

// The squeeze a tuft's coverage is raised by (clump_coverage) where the
// squeezed read stands at mip level `lod` (docs/wetness.md, Tuft
// coverage): none where it still resolves the hairs (a pixel spans at most
// 2 of its texels), each drawn where the tuft gathers it, the full squeeze
// where the mip level averages them (4 texels and more) and only the
// bundle's density says how many a ray meets. Mirrors
// pelt__clump_bundle_squeeze.
const float CLUMP_RESOLVED_LOD = 1.0;
float clump_bundle_squeeze(float squeeze, float lod)
{
    return mix(1.0, squeeze, clamp(lod - CLUMP_RESOLVED_LOD, 0.0, 1.0));
}

// A fin shows the hair rooted along its edge from the side: the hair a
// tuft pulls from q = p + d lies along the fin by d's component along the
// edge, in fin-texture units; `dir` is the edge's mask uv per fin-texture
// unit. Mirrors pelt__clump_fin_shift.
float clump_fin_shift(vec2 d, vec2 dir)
{
    float len2 = dot(dir, dir);
    return len2 > 1e-20 ? dot(d, dir) / len2 : 0.0;
}

// Sub shells (docs/wetness.md): sub shell `part` (0 the innermost) of k
// drawn for `layer` of a level stepping `step` layers, evenly below the
// layer down to the one below. Mirrors pelt__sub_shell_layer.
float sub_shell_layer(float layer, float part, float k, float step)
{
    return layer - (k - 1.0 - part) / k * step;
}

// What each of k sub shells covers so that the k of them cover a.
// Mirrors pelt__sub_shell_alpha.
float sub_shell_alpha(float a, float k)
{
    return k > 1.0 ? 1.0 - pow(max(1.0 - a, 0.0), 1.0 / k) : a;
}
