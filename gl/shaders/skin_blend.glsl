// Linear-blend skinning in the vertex stage (PELT_GPU_SKIN, for measuring
// against the pose made once a frame on the CPU: pelt bench --animation,
// docs/animation.md). The attributes hold the bind-space vertex; each
// bone is 3 rows of its 4x4 matrix in u_bones.
#ifdef PELT_GPU_SKIN
layout(location = PELT_ATTR_BONES) in uvec4 a_bones;
layout(location = PELT_ATTR_WEIGHTS) in vec4 a_weights;
uniform highp sampler2D u_bones; // PELT_UNIT_BONES

vec4 bone_row(uint b, int r)
{
    int i = int(b) * 3 + r;
    return texelFetch(u_bones, ivec2(i % PELT_TABLE_WIDTH, i / PELT_TABLE_WIDTH), 0);
}

// The blend of the vertex's bones moves its position, normal and tangent
// (directions by the blend's linear part: the bones are rigid).
void skin_vertex(inout vec3 p, inout vec3 n, inout vec4 t)
{
    vec4 r0 = vec4(0.0), r1 = vec4(0.0), r2 = vec4(0.0);
    for (int k = 0; k < 4; k++) {
        float w = a_weights[k];
        if (w == 0.0) continue;
        uint b = a_bones[k];
        r0 += w * bone_row(b, 0);
        r1 += w * bone_row(b, 1);
        r2 += w * bone_row(b, 2);
    }
    vec4 hp = vec4(p, 1.0);
    p = vec3(dot(r0, hp), dot(r1, hp), dot(r2, hp));
    n = normalize(vec3(dot(r0.xyz, n), dot(r1.xyz, n), dot(r2.xyz, n)));
    t.xyz = normalize(vec3(dot(r0.xyz, t.xyz), dot(r1.xyz, t.xyz), dot(r2.xyz, t.xyz)));
}
#endif
