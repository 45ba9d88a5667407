#version 450
// shaders/refit_merge.comp - the internal nodes pc.first .. pc.first +
// pc.count - 1 (one depth) from their children: mlod__merge_nodes of
// manylods.h (sphere, cone, colour weighted by the leaves below).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_EXT_control_flow_attributes : require
#define MLOD_NO_VIEWS
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "refit_layout.glsl"
#include "common.glsl"
#include "refit_mesh.glsl"

void main()
{
    uint k = group_index() * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    if (k >= pc.count) return;
    uint i = pc.first + k, l = 2u * i + 1u, r = 2u * i + 2u;
    spheres[i] = sphere_enclose(spheres[l], spheres[r]);
    if (pc.has_cones != 0u) cones[i] = cone_enclose(cones[l], cones[r]);
    if (pc.has_colors != 0u) {
        real wl = r_u(leaves_below(l, pc.leaf_count)), wr = r_u(leaves_below(r, pc.leaf_count));
        for (uint c = 0u; c < 3u; c++) {
            real v = r_div(r_add(r_mul(wl, r_f(colors[3u * l + c])), r_mul(wr, r_f(colors[3u * r + c]))), r_add(wl, wr));
            colors[3u * i + c] = r_to_f(v);
        }
    }
}
