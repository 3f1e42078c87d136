// Silva et al. Eq. 6 (Kajiya-Kay) and the shadow factor gamma; mirrored by
// core/fur/shading.c. E points from the eye towards the shaded point.
// From the dots T.L and T.E (ringlet_dots gives them for a curl).
vec2 kajiya_kay_dots(float tl, float te, float p)
{
    float sin_tl = sqrt(max(0.0, 1.0 - tl * tl));
    float sin_te = sqrt(max(0.0, 1.0 - te * te));
    return vec2(sin_tl, pow(max(0.0, tl * te + sin_tl * sin_te), p));
}

vec2 kajiya_kay(vec3 T, vec3 L, vec3 E, float p)
{
    return kajiya_kay_dots(dot(T, L), dot(T, E), p);
}

// Wet fur's highlight: (exponent, specular gain) at wetness rho, the
// exponent p sharpened and the gain raised towards their fully wet
// multiples. Mirrors pelt__wet_shine (docs/wetness.md, Wet shine).
vec2 wet_shine(float rho, float p, float sharpness, float gloss)
{
    float r = clamp(rho, 0.0, 1.0);
    return vec2(p * (1.0 + (sharpness - 1.0) * r), 1.0 + (gloss - 1.0) * r);
}

// Wet skin's sheen (docs/wetness.md, Wet optics): the water film between
// the tufts, Blinn-Phong at the wet hair's exponent times sharpness (a
// flatter film) and its gain, over the film's cover rho. Mirrors
// pelt__wet_skin_sheen.
float wet_skin_sheen(float n_dot_h, float rho, float p, float sharpness, float gloss)
{
    vec2 shine = wet_shine(rho, p, sharpness, gloss);
    return clamp(rho, 0.0, 1.0) * shine.y * pow(clamp(n_dot_h, 0.0, 1.0), shine.x * sharpness);
}

// Wet hair's colour (docs/wetness.md, Wet optics): water fills the gaps
// between the hairs, so less light scatters back out (darker by darken
// rho), and what does has passed through more hair (more saturated: each
// channel's share of the brightest raised to 1 + WET_SATURATION rho).
// Mirrors pelt__wet_color.
const float WET_SATURATION = 0.8;
vec3 wet_color(vec3 c, float rho, float darken)
{
    float r = clamp(rho, 0.0, 1.0);
    float top = max(max(c.r, c.g), max(c.b, 1e-6));
    return top * pow(max(c, vec3(0.0)) / top, vec3(1.0 + WET_SATURATION * r)) * (1.0 - darken * r);
}

float shadow_factor(float k_shadow, float h)
{
    return (k_shadow - 1.0 + h) / k_shadow;
}

// Linear light (docs/shading.md): sRGB colours decoded, lit, exposed, tone
// mapped and encoded. Mirrors pelt__srgb_decode / _encode, pelt__aces,
// pelt__tone and pelt__display (core/fur/shading.c).
vec3 srgb_decode(vec3 c)
{
    return mix(pow((c + 0.055) / 1.055, vec3(2.4)), c / 12.92, lessThanEqual(c, vec3(0.04045)));
}

// Taylor's fit of the power in square roots (pelt__srgb_encode); the
// display mapping below folds it into one fit with the tone curve.
vec3 srgb_encode(vec3 l)
{
    l = clamp(l, 0.0, 1.0);
    vec3 s1 = sqrt(l), s2 = sqrt(s1), s3 = sqrt(s2);
    vec3 fit = 0.662002687 * s1 + 0.684122060 * s2 - 0.323583601 * s3 - 0.0225411470 * l;
    return mix(fit, 12.92 * l, lessThanEqual(l, vec3(0.0031308)));
}

// The strand's shade, by Taylor's cubic (pelt__shade_decode).
float shade_decode(float c)
{
    return c * (c * (0.305306011 * c + 0.682171111) + 0.012522878);
}

// Narkowicz's fit of the ACES filmic curve (2015), its input scaled by
// his 0.6 (PELT__TONE_BIAS).
const float TONE_BIAS = 0.6;

vec3 aces(vec3 x)
{
    return x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
}

// tone 0: filmic, 1: none (clamp only).
vec3 tone_map(vec3 x, float exposure, float tone)
{
    vec3 v = max(x * exposure, 0.0);
    if (tone > 0.5) return min(v, 1.0);
    return clamp(aces(TONE_BIAS * v), 0.0, 1.0);
}

// What a pixel shows: the sRGB encoding of tone_map, fitted whole for
// each curve (pelt__display): with s = sqrt(clamp(exposure x, 0, v_max)),
// P(s) / Q(s), P = p1 s + ... + p5 s^5, Q = 1 + q1 s + ... + q4 s^4. One
// square root and one division a channel instead of tone_map's division
// and srgb_encode's three square roots. P's p1..p4, Q's q1..q4, (p5, v_max).
const vec4 DISPLAY_FILMIC_P = vec4(-0.0576929201, 3.39692282, -35.8013261, 146.612241);
const vec4 DISPLAY_FILMIC_Q = vec4(-12.7071925, 60.9314706, -69.6605025, 158.831435);
const vec2 DISPLAY_FILMIC_R = vec2(2.03500454, 12.0694);
const vec4 DISPLAY_NONE_P = vec4(0.0326068422, 3.15541583, 363.172133, 0.0);
const vec4 DISPLAY_NONE_Q = vec4(-2.93838857, 323.863771, 44.6805545, 0.0);
const vec2 DISPLAY_NONE_R = vec2(0.0, 1.0);

vec3 display_color(vec3 x, float exposure, float tone)
{
    bool none = tone > 0.5;
    vec4 p = none ? DISPLAY_NONE_P : DISPLAY_FILMIC_P;
    vec4 q = none ? DISPLAY_NONE_Q : DISPLAY_FILMIC_Q;
    vec2 r = none ? DISPLAY_NONE_R : DISPLAY_FILMIC_R;
    vec3 s = sqrt(clamp(x * exposure, 0.0, r.y));
    vec3 num = s * (p.x + s * (p.y + s * (p.z + s * (p.w + s * r.x))));
    vec3 den = 1.0 + s * (q.x + s * (q.y + s * (q.z + s * q.w)));
    return clamp(num / den, 0.0, 1.0);
}

// Hair beyond Kajiya-Kay: Scheuermann's (GDC 2004) reading of Marschner et
// al. 2003. Mirrors pelt__shift_tangent, pelt__strand_specular,
// pelt__hair_transmission and pelt__hair_lobes (core/fur/shading.h says
// what each term is).
const float HAIR_SHIFT_PRIMARY = 0.1;    // PELT__HAIR_SHIFT_PRIMARY: towards the tip
const float HAIR_SHIFT_SECONDARY = -0.15; // PELT__HAIR_SHIFT_SECONDARY: towards the root
const float HAIR_SECONDARY_WIDTH = 0.5;
const float HAIR_SECONDARY_GAIN = 0.5;
const float HAIR_TT_WIDTH = 0.5;
const float HAIR_TT_GAIN = 1.5;
const float HAIR_TT_AZIMUTH = 2.0;
const float HAIR_TT_REACH = 0.8; // transmission's body shadow: clamp(0.8 n.L + REACH, 0, 1)

vec3 shift_tangent(vec3 T, vec3 N, float shift)
{
    vec3 t = T + shift * N;
    float len = length(t);
    return len > 1e-12 ? t / len : T;
}

float strand_specular(vec3 T, vec3 H, float p)
{
    float u = dot(T, H);
    return smoothstep(-1.0, 0.0, u) * pow(max(0.0, 1.0 - u * u), 0.5 * p);
}

float hair_transmission(vec3 T, vec3 L, vec3 E, float p)
{
    float tl = dot(T, L);
    float te = dot(T, E);
    float sin_tl = sqrt(max(0.0, 1.0 - tl * tl));
    float sin_te = sqrt(max(0.0, 1.0 - te * te));
    float cone = pow(max(0.0, tl * te + sin_tl * sin_te), p);
    float cos_phi = (dot(L, E) - tl * te) / max(sin_tl * sin_te, 1e-4);
    return cone * pow(clamp(cos_phi, 0.0, 1.0), HAIR_TT_AZIMUTH);
}

// (diffuse, primary, secondary, transmission).
vec4 hair_lobes(vec3 T, vec3 N, vec3 L, vec3 E, float p)
{
    float tl = dot(T, L);
    vec3 h = L - E;
    float len = length(h);
    vec3 H = len > 1e-12 ? h / len : N;
    return vec4(sqrt(max(0.0, 1.0 - tl * tl)),
                strand_specular(shift_tangent(T, N, HAIR_SHIFT_PRIMARY), H, p),
                strand_specular(shift_tangent(T, N, HAIR_SHIFT_SECONDARY), H, p * HAIR_SECONDARY_WIDTH),
                hair_transmission(T, L, E, p * HAIR_TT_WIDTH));
}

// Occlusion from the fur's own density (pelt__fur_occlusion).
float fur_occlusion(float depth, float h)
{
    return exp(-depth * (1.0 - h));
}

// Grooming (Lengyel et al. §3): a vertex's hair colour c.rgb (sRGB bytes,
// decoded) over the look's colour with weight c.a; its tip is brightened
// by the look's own tip-to-root ratio. Mirrored by pelt__groom_root_color
// / _tip_color.
vec3 groom_root_color(vec3 color, vec4 c)
{
    return mix(color, srgb_decode(c.rgb), c.a);
}

vec3 groom_tip_color(vec3 color, vec3 tip, vec4 c)
{
    return mix(tip, min(srgb_decode(c.rgb) * tip / max(color, vec3(0.01)), vec3(1.0)), c.a);
}

// Grooming's density keeps the strands whose id (the fur volume's blue,
// uniform in [0,1]) is below it; 1 keeps all of them.
bool groom_keeps(float id, float density)
{
    return density >= 1.0 || id < density;
}

// Lengyel et al. §2.4: the (diffuse, specular) factors of the hair
// lighting table, read with bilinear filtering (pelt__lengyel_table).
vec2 lengyel_lookup(sampler2D table, vec3 T, vec3 L, vec3 H)
{
    return texture(table, vec2(dot(T, L), dot(T, H)) * 0.5 + 0.5).rg;
}

// Kenwright's inter-fur shadow: the fur-texture step towards the light in
// the tangent frame (pelt__inter_shadow_offset).
vec2 inter_shadow_offset(vec3 L, vec3 u, vec3 v, float step)
{
    return vec2(dot(L, u), dot(L, v)) * step;
}

// How much of Kenwright's shadow a shell draws where the eye sees the
// surface at n_dot_v: all face-on, none from the side
// (pelt__inter_shadow_view_fade).
const float INTER_SHADOW_SIDE_ON = 0.3; // PELT__INTER_SHADOW_SIDE_ON
const float INTER_SHADOW_FACE_ON = 0.7; // PELT__INTER_SHADOW_FACE_ON
float inter_shadow_view_fade(float n_dot_v)
{
    return smoothstep(INTER_SHADOW_SIDE_ON, INTER_SHADOW_FACE_ON, abs(n_dot_v));
}
