// A hair's own light, shared by the shells' and the fins' stages: a
// ringlet lit along its curl (docs/method.md, Ringlets) and a tuft's hair
// along its tuft (docs/wetness.md, Tuft light), in place of the free
// hair's light that the vertex stage worked out. Comes after blocks.glsl,
// shading.glsl and fur_shape.glsl.

// The vertex stage's part: the hair frame's unit vectors (t, u, v) dotted
// with the direction towards the light L, the eye's E and each other,
// for ringlet_dots per fragment: l = (t.L, u.L, v.L), e = (t.E, u.E, v.E),
// g = (t.u, t.v, u.v).
void ringlet_frame_dots(vec3 t, vec3 u, vec3 v, vec3 L, vec3 E, out vec3 l, out vec3 e, out vec3 g)
{
    l = vec3(dot(t, L), dot(u, L), dot(v, L));
    e = vec3(dot(t, E), dot(u, E), dot(v, E));
    g = vec3(dot(t, u), dot(t, v), dot(u, v));
}

// The vertex stage's light factor for the colours it passes on where the
// fragment stage lights ringlets (ringlet_light): dry Kajiya-Kay carries
// gamma alone (its light_mul is gamma (ambient + diffuse), the part the
// ringlet's light replaces); other variants keep light_mul.
vec3 ringlet_light_mul(vec3 light_mul, float gamma)
{
#if defined(PELT_SHADING_KK) && !defined(PELT_WET)
#ifdef PELT_SHADING_TABLE
    if (u_shading_model < 0.5)
#endif
        return vec3(gamma);
#endif
    return light_mul;
}

// Kajiya-Kay along the hair's own tangent T from its dots own = (T.L,
// T.E): the diffuse is scaled by the ratio of the two lights (inv_free:
// 1 / the free hair's light that base carries, or 1 where the vertex
// stage left it out) and the highlight is T's. reach = (facing, gamma)
// of fur_reach at the vertex. Other hair models keep the free hair's
// light.
void own_light_dots(vec2 own, vec2 reach, vec3 inv_free, float rho, inout vec3 base, inout float spec)
{
#if defined(PELT_SHADING_TABLE) && !defined(PELT_SHADING_KK)
    return;
#elif !defined(PELT_SHADING_KK)
    return;
#else
#ifdef PELT_SHADING_TABLE
    if (u_shading_model > 0.5) return;
#endif
    vec2 shine = wet_shine(rho, u_shininess, u_wet_sharpness, u_wet_gloss);
    vec2 kk = kajiya_kay_dots(own.x, own.y, shine.x);
    base *= (u_ambient + kk.x * reach.x * u_light_color) * inv_free;
    spec = reach.y * shine.y * kk.y * reach.x;
#endif
}

// 1 / the free hair's light (ambient + its Kajiya-Kay diffuse free_diffuse),
// for own_light_dots where the vertex stage folded it into base.
vec3 free_light_inverse(float free_diffuse, vec2 reach)
{
    return 1.0 / max(u_ambient + free_diffuse * reach.x * u_light_color, vec3(1e-4));
}

// The curl of the hair with this id at height h (over the full length):
// its ringlet and the fur texture's own curl (strand_curl_slope), from the
// frame's dots (ringlet_frame_dots). Water takes out the ringlet as it
// does from the volume's levels (1 - rho); the texture's curl stays, as
// in the texture. The wet variants' vertex stage folded the free hair's
// light into base; the dry one left it out (ringlet_light_mul).
// ringlet_own: the curl's own dots (T.L, T.E); ringlet_light lights them.
vec2 ringlet_own(float id, float rho, float h, vec3 ring_l, vec3 ring_e, vec3 ring_g)
{
    float k = (1.0 - rho) * u_ringlet_radius / max(u_length, 1e-6);
    float psi = ringlet_phase(id);
    vec2 extra = strand_curl_slope(u_strand_curl_radius, u_strand_curl_omega, u_strand_curl_wave > 0.5, h, psi);
    return ringlet_dots(ring_l, ring_e, ring_g, k, u_curl_frequency, h, psi, extra);
}

// 1 / the free hair's light from its dots (t.L, t.E) under wetness rho,
// where the vertex stage folded that light into base (the wet variants).
vec3 free_light_inverse_dots(float t_l, float t_e, float rho, vec2 reach)
{
    vec2 shine = wet_shine(rho, u_shininess, u_wet_sharpness, u_wet_gloss);
    return free_light_inverse(kajiya_kay_dots(t_l, t_e, shine.x).x, reach);
}

void ringlet_light(float id, float rho, float h, vec2 reach, vec3 ring_l, vec3 ring_e, vec3 ring_g,
                   inout vec3 base, inout float spec)
{
#ifdef PELT_WET
    vec3 inv_free = free_light_inverse_dots(ring_l.x, ring_e.x, rho, reach);
#else
    vec3 inv_free = vec3(1.0);
#endif
    own_light_dots(ringlet_own(id, rho, h, ring_l, ring_e, ring_g), reach, inv_free, rho, base, spec);
}
