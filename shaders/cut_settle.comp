#version 450
// shaders/cut_settle.comp - after cut_finish, dispatched with args[3]: the
// entries it left pending (the float filter unsure of them) and listed in
// acts, classified with the exact path.  Counted as evaluated by
// cut_finish already.
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
    uint listed = ctl.args[3].w;
    for (uint g = gl_WorkGroupID.x; g * MLOD_IF_GROUP < listed; g += gl_NumWorkGroups.x) {
        uint k = g * MLOD_IF_GROUP + gl_LocalInvocationID.x;
        if (k < listed) {
            uint i = acts[k];
            status_in[i] = classify(list_in[i].y, list_in[i].x, r_f(pc.epsilon), pc.leaf_count);
        }
    }
}
