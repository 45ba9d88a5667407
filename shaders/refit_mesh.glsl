// shaders/refit_mesh.glsl - mesh geometry for the refit shaders, after
// refit_layout.glsl and common.glsl.

// mlod__triangle_area
double triangle_area(uint tri)
{
    dvec3 v0 = vertex_attribute(0u, indices[3u * tri]), v1 = vertex_attribute(0u, indices[3u * tri + 1u]),
          v2 = vertex_attribute(0u, indices[3u * tri + 2u]);
    precise dvec3 e1 = dvec3(v1.x - v0.x, v1.y - v0.y, v1.z - v0.z);
    precise dvec3 e2 = dvec3(v2.x - v0.x, v2.y - v0.y, v2.z - v0.z);
    dvec3 n = cross_d(e1, e2);
    precise double area = 0.5LF * length_d(n);
    return area;
}
