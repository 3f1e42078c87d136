// Fins (Lengyel et al. 2001 §2.3): the fin normal and the fade, mirrored by
// core/fur/fins.c (pelt__fin_normal, pelt__fin_fade).

// The fin holds the edge and the mean of its end normals.
vec3 fin_normal(vec3 pa, vec3 pb, vec3 na, vec3 nb)
{
    vec3 c = cross(pb - pa, na + nb);
    float l2 = dot(c, c);
    return l2 > 1e-40 ? c * inversesqrt(l2) : na;
}

// Opacity factor max(0, 2|p| - 1), p = fin normal . view direction.
float fin_fade(vec3 fin_n, vec3 view_dir)
{
    return max(0.0, 2.0 * abs(dot(fin_n, view_dir)) - 1.0);
}
