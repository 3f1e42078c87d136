// The ground (gl/ground_pass.c): a disc in the plane y = u_ground.y under
// the mesh, drawn as one quad from gl_VertexID (no attributes).
uniform vec4 u_ground; // centre x, plane height, centre z, radius (world)

out vec3 v_world;
out vec2 v_disc; // -1..1 across the disc

void main()
{
    v_disc = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
    v_world = vec3(u_ground.x, u_ground.y, u_ground.z) + vec3(v_disc.x, 0.0, v_disc.y) * u_ground.w;
    gl_Position = u_view_proj * vec4(v_world, 1.0);
}
