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
real interpolate1(real a, real b, real c, real s, real t)
{
    return r_add(r_add(a, r_mul(s, r_sub(b, a))), r_mul(t, r_sub(c, a)));
}

real3 interpolate(uint which, uint tri, real s, real t)
{
    real3 a = vertex_attribute(which, indices[3u * tri]), b = vertex_attribute(which, indices[3u * tri + 1u]),
          c = vertex_attribute(which, indices[3u * tri + 2u]);
    return real3(interpolate1(a.x, b.x, c.x, s, t), interpolate1(a.y, b.y, c.y, s, t), interpolate1(a.z, b.z, c.z, s, t));
}

void main()
{
    uint j = group_index() * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    if (j >= pc.count) return;
    uint node = pc.leaf_count - 1u + j, tri = leaf_sources[j];
    real s = r_f(barycentrics[j].x), t = r_f(barycentrics[j].y);
    real ratio = r_div(triangle_area(tri), r_load(triangle_areas[tri]));
    real3 p = interpolate(0u, tri, s, t);
    real r = r_mul(r_f(pc.radius_scale), r_sqrt(r_mul(r_load(pc.area_unit), ratio)));
    spheres[node] = vec4(r_to_f(p.x), r_to_f(p.y), r_to_f(p.z), float_up(r));
    if (pc.has_cones != 0u) {
        real3 n = real3(R_ZERO, R_ZERO, R_ZERO);
        if (pc.normal_stride != 0u) n = interpolate(1u, tri, s, t);
        if (!r_gt(dot3(n, n), R_ZERO)) {
            real3 v0 = vertex_attribute(0u, indices[3u * tri]), v1 = vertex_attribute(0u, indices[3u * tri + 1u]),
                  v2 = vertex_attribute(0u, indices[3u * tri + 2u]);
            n = cross_d(r3_sub(v1, v0), r3_sub(v2, v0));
        }
        // mlod__cone_from_normal
        real len = length_d(n);
        if (!r_gt(len, R_ZERO) || r_isinf(len) || r_isnan(len))
            cones[node] = cone_full(vec3(0.0, 0.0, 1.0));
        else
            cones[node] = vec4(r_to_f(r_div(n.x, len)), r_to_f(r_div(n.y, len)), r_to_f(r_div(n.z, len)), 0.0);
    }
    if (pc.has_colors != 0u) {
        real3 c = interpolate(2u, tri, s, t);
        colors[3u * node] = r_to_f(c.x);
        colors[3u * node + 1u] = r_to_f(c.y);
        colors[3u * node + 2u] = r_to_f(c.z);
    }
}
