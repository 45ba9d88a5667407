#version 450
// shaders/cut_settle.comp - after cut_finish, dispatched with args[3]: in
// the workgroups cut_finish listed, the entries it left pending (the float
// filter unsure of them) classified with the exact path.  Counted as
// evaluated by cut_finish already.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_EXT_control_flow_attributes : require
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "cut_layout.glsl"
#define MLOD_HAS_CONES (pc.has_cones != 0u)
#include "common.glsl"

void main()
{
    for (uint k = gl_WorkGroupID.x; k < ctl.args[3].w; k += gl_NumWorkGroups.x) {
        uint i = DEFERRED_BLOCK(k) * MLOD_IF_GROUP + gl_LocalInvocationID.x;
        if (i < ctl.current && status_in[i] == MLOD_IF_STATUS_PENDING)
            status_in[i] = classify(list_in[i].y, list_in[i].x, r_f(pc.epsilon), pc.leaf_count);
    }
}
