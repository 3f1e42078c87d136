// Fur shape of Silva et al. §3.2 (Eq. 1 and 4), the same formulas and
// argument order as the C references in core/fur/fur_shape.c. No #version: the
// renderer concatenates this into the vertex shader (GLSL 3.30 core and
// GLSL ES 3.00). h in [0, 1] is the normalised height, h = (1 + n) / N.

// beta(h), Silva Eq. 1: quadratic Bezier from the root through n * L0 / 2 to
// the strand tip offset; at rest (tip = L0 n) it is h * L0 * n.
vec3 fur_bend(vec3 n, float L0, vec3 tip, float h)
{
    return n * (2.0 * h * (1.0 - h) * (0.5 * L0)) + tip * (h * h);
}

// The hair's normal on a coarse level: the vertex's normal plus the fitted
// difference d, given in its frame (u, v, n), made unit. Mirrors
// pelt__lod_fit_normal (core/fur/lod_normals.c).
vec3 level_fit_normal(vec3 n, vec3 u, vec3 v, vec3 d)
{
    return normalize(n + u * d.x + v * d.y + n * d.z);
}

// phi(h), Silva Eq. 4: (1 - rho) K h (cos(omega h) u + sin(omega h) v).
vec3 fur_curl(vec3 u, vec3 v, float omega, float K, float rho, float h)
{
    float alpha = (1.0 - rho) * K * h;
    return u * (alpha * cos(omega * h)) + v * (alpha * sin(omega * h));
}

// A ringlet's phase from its strand's id: 2 pi fract(3 id). Mirrors
// pelt__ringlet_phase.
float ringlet_phase(float id)
{
    return 6.2831853 * fract(3.0 * id);
}

// A ringlet's unit tangent: t plus d/dh of k h (cos(omega h + psi) u +
// sin(omega h + psi) v). Mirrors pelt__ringlet_tangent.
vec3 ringlet_tangent(vec3 t, vec3 u, vec3 v, float k, float omega, float h, float psi)
{
    float c = cos(omega * h + psi), s = sin(omega * h + psi);
    vec3 d = t + u * (k * (c - omega * h * s)) + v * (k * (s + omega * h * c));
    float len2 = dot(d, d);
    return len2 > 1e-30 ? d * inversesqrt(len2) : t;
}

// The slope of the fur texture's own curl along (u, v) per unit of the
// hair's length at h: a helix radius (cos, sin)(omega h + psi) or a wave
// along u (wave true). Mirrors pelt__strand_curl_slope.
vec2 strand_curl_slope(float radius, float omega, bool wave, float h, float psi)
{
    float c = cos(omega * h + psi), s = sin(omega * h + psi);
    return wave ? vec2(radius * omega * c, 0.0) : radius * omega * vec2(-s, c);
}

// ringlet_tangent's T, plus the slope `extra` along (u, v), dotted with
// two directions, from the frame's unit vectors dotted with them (ta, tb)
// and with each other (gram = t.u, t.v, u.v). Mirrors pelt__ringlet_dots.
vec2 ringlet_dots(vec3 ta, vec3 tb, vec3 gram, float k, float omega, float h, float psi, vec2 extra)
{
    float c = cos(omega * h + psi), s = sin(omega * h + psi);
    float a = k * (c - omega * h * s) + extra.x, b = k * (s + omega * h * c) + extra.y;
    float len2 = 1.0 + a * a + b * b + 2.0 * (a * gram.x + b * gram.y + a * b * gram.z);
    if (!(len2 > 1e-30)) return vec2(ta.x, tb.x);
    return vec2(dot(ta, vec3(1.0, a, b)), dot(tb, vec3(1.0, a, b))) * inversesqrt(len2);
}

// Unit d/dh (beta + phi): the shading tangent of the displaced strand
// (Silva Fig. 6); n where the derivative vanishes.
// Lengyel et al. §3 combing: a shear along the comb direction u; slant is
// the tangent of the slant angle. Mirrors pelt__fur_comb.
vec3 fur_comb(vec3 u, float L0, float slant, float h)
{
    return u * (h * L0 * slant);
}

// Wet fur lies along its grain (docs/wetness.md, Wet fur lies down): the
// comb's slant at wetness rho, its angle raised by lie rho radians, at most
// 75 degrees. Mirrors pelt__fur_wet_slant.
float wet_slant(float slant, float lie, float rho)
{
    float add = lie * rho;
    if (!(add > 0.0)) return slant;
    return tan(min(atan(slant) + add, 1.3089969));
}

// Lengyel et al. §3 grooming: shear per unit length, the comb direction
// times the global slant plus the groomed lean in the tangent frame (u, v).
// Mirrors pelt__fur_groom_shear.
vec3 fur_groom_shear(vec3 comb, float slant, vec3 u, vec3 v, vec2 lean)
{
    return comb * slant + u * lean.x + v * lean.y;
}

// T(h) of the combed strand (comb direction c); mirrors
// pelt__fur_tangent_combed.
vec3 fur_tangent_combed(vec3 n, float L0, vec3 tip, vec3 u, vec3 v, vec3 c, float omega, float K,
                        float rho, float slant, float h)
{
    vec3 db = n * ((1.0 - 2.0 * h) * L0) + tip * (2.0 * h);
    float k = (1.0 - rho) * K;
    float co = cos(omega * h);
    float s = sin(omega * h);
    vec3 d = db + u * (k * (co - omega * h * s)) + v * (k * (s + omega * h * co)) + c * (L0 * slant);
    float len2 = dot(d, d);
    return len2 > 1e-30 ? d * inversesqrt(len2) : n;
}

vec3 fur_tangent(vec3 n, float L0, vec3 tip, vec3 u, vec3 v, float omega, float K, float rho, float h)
{
    return fur_tangent_combed(n, L0, tip, u, v, u, omega, K, rho, 0.0, h);
}
