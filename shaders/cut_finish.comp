#version 450
// shaders/cut_finish.comp - after the last round of a submission: move the
// current list to buffers A if it lives in B, classify entries still
// pending (the children of a lazy call's last splits) by the float filter,
// clear the working bits, and record where each view's list begins (every
// view has at least one entry; the list is grouped by view, in view
// order): view_offsets[v] .. view_offsets[v + 1].  Dispatched with
// args[2].  An entry the filter is unsure of stays pending and is listed
// for cut_exact with pc.settle (as cut_step's for cut_exact: the exact
// path is kept out of a pass that every entry takes).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_EXT_control_flow_attributes : require
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#define MLOD_CUT_COUNTS
#include "cut_layout.glsl"
#define MLOD_HAS_CONES (pc.has_cones != 0u)
#include "common.glsl"

void main()
{
    uint n = ctl.current;
    bool in_b = ctl.input_is_b != 0u;
    uint group = group_index();
    uint i = group * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    uint evaluated = 0u;
    if (i < n) {
        uvec2 e = in_b ? list_out[i] : list_in[i];
        uint s = (in_b ? status_out[i] : status_in[i]) & 7u;
        uint previous_view = i == 0u ? 0xffffffffu : (in_b ? list_out[i - 1u].y : list_in[i - 1u].y);
        if (s == MLOD_IF_STATUS_PENDING) {
            s = classify_fast(e.y, e.x, pc.leaf_count); // 0 (still pending) when unsure
            evaluated = 1u; // cut_exact (settle) does not count it again
            if (s == 0u) acts[defer_entry()] = i;
        }
        if (in_b) list_in[i] = e;
        status_in[i] = s;
        if (previous_view != e.y) view_offsets[e.y] = i;
        if (i + 1u == n) view_offsets[pc.view_count] = n;
    }
    count_workgroup(0u, evaluated, 0u, MLOD_NO_BLOCK);
}
