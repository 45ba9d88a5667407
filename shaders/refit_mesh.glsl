// shaders/refit_mesh.glsl - mesh geometry for the refit shaders, after
// refit_layout.glsl and common.glsl.

// Attribute `which` of a vertex, in double.
real3 vertex_attribute(uint which, uint vertex) { return r3_f(vertex_float3(which, vertex)); }

// mlod__triangle_area
real triangle_area(uint tri)
{
    real3 v0 = vertex_attribute(0u, indices[3u * tri]), v1 = vertex_attribute(0u, indices[3u * tri + 1u]),
          v2 = vertex_attribute(0u, indices[3u * tri + 2u]);
    return r_mul(R_HALF, length_d(cross_d(r3_sub(v1, v0), r3_sub(v2, v0))));
}
