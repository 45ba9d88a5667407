#version 450
// shaders/cut_init.comp - a cut from the root: entry v of list A is (root,
// view v), pending; the control block is armed for the first round.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "cut_layout.glsl"

void main()
{
    uint v = group_index() * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    if (v < pc.view_count) {
        list_in[v] = uvec2(0u, v);
        status_in[v] = 0u;
    }
}
