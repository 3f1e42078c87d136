// Lengyel et al. 2001 §2.4 in the shell draw: instance i (inner first) of
// a level is the shell j = shells.x - 1 - i from the outside, at layer
// N - 1 - j * shells.y; the even shells (from the outside) blend into the
// next level's composite, the odd ones fade out. shells and next are the
// shell pass's uniforms (pelt__lod_shell_uniforms). Mirrors
// pelt__lod_shell_instance (core/fur/lod.c).
float shell_instance(float i, vec4 shells, vec2 next, float N, out vec3 slices, out float alpha)
{
    float j = shells.x - 1.0 - i;
    bool kept = mod(j, 2.0) < 0.5;
    float own = shells.z + i;
    slices = vec3(own, kept ? next.x + next.y - 1.0 - floor(j * 0.5) : own, kept ? shells.w : 0.0);
    alpha = kept ? 1.0 : 1.0 - shells.w;
    return N - 1.0 - j * shells.y;
}
