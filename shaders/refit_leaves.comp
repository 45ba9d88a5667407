#version 450
// shaders/refit_leaves.comp - leaf j (j < pc.count) from its triangle and
// barycentrics: mlod__mesh_leaf of manylods.h (position, radius from the
// area ratio, cone from the interpolated or the face normal, colour).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_EXT_control_flow_attributes : require
#define MLOD_NO_VIEWS
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "refit_layout.glsl"
#include "common.glsl"
#include "refit_mesh.glsl"

// mlod__interpolate
dvec3 interpolate(uint which, uint tri, double s, double t)
{
    dvec3 a = vertex_attribute(which, indices[3u * tri]), b = vertex_attribute(which, indices[3u * tri + 1u]),
          c = vertex_attribute(which, indices[3u * tri + 2u]);
    precise dvec3 r = dvec3(a.x + s * (b.x - a.x) + t * (c.x - a.x), a.y + s * (b.y - a.y) + t * (c.y - a.y),
                            a.z + s * (b.z - a.z) + t * (c.z - a.z));
    return r;
}

void main()
{
    uint j = group_index() * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    if (j >= pc.count) return;
    uint node = pc.leaf_count - 1u + j, tri = leaf_sources[j];
    double s = double(barycentrics[j].x), t = double(barycentrics[j].y);
    precise double ratio = triangle_area(tri) / triangle_areas[tri];
    dvec3 p = interpolate(0u, tri, s, t);
    precise double r = double(pc.radius_scale) * sqrt(pc.area_unit * ratio);
    spheres[node] = vec4(float(p.x), float(p.y), float(p.z), float_up(r));
    if (pc.has_cones != 0u) {
        dvec3 n = dvec3(0.0LF);
        if (pc.normal_stride != 0u) n = interpolate(1u, tri, s, t);
        if (!(dot3(n, n) > 0.0LF)) {
            dvec3 v0 = vertex_attribute(0u, indices[3u * tri]), v1 = vertex_attribute(0u, indices[3u * tri + 1u]),
                  v2 = vertex_attribute(0u, indices[3u * tri + 2u]);
            precise dvec3 e1 = dvec3(v1.x - v0.x, v1.y - v0.y, v1.z - v0.z);
            precise dvec3 e2 = dvec3(v2.x - v0.x, v2.y - v0.y, v2.z - v0.z);
            n = cross_d(e1, e2);
        }
        // mlod__cone_from_normal
        precise double len = length_d(n);
        if (!(len > 0.0LF) || isinf(len) || isnan(len))
            cones[node] = cone_full(vec3(0.0, 0.0, 1.0));
        else
            cones[node] = vec4(float(n.x / len), float(n.y / len), float(n.z / len), 0.0);
    }
    if (pc.has_colors != 0u) {
        dvec3 c = interpolate(2u, tri, s, t);
        colors[3u * node] = float(c.x);
        colors[3u * node + 1u] = float(c.y);
        colors[3u * node + 2u] = float(c.z);
    }
}
