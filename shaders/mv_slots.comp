#version 450
// shaders/mv_slots.comp - one thread per view node of the level (pc.items):
// a map slot (ctl.slots counts them out) for a view leaf, a node that drew
// something, or a node whose parent has a map (MLOD_IF_MV_NONE otherwise),
// the slot's node, the most pairs of one node; the node's pair count and
// drawn flag are zeroed for the level after next, which reuses them.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_EXT_control_flow_attributes : require
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "mv_layout.glsl"

void main()
{
    uint j = group_index() * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    if (j >= pc.items) return;
    uint v = ctl.first + j;
    bool inherits = v > 0u && level[ctl.off_prev_slots + (v - 1u) / 2u - ctl.prev_first] != MLOD_IF_MV_NONE;
    uint slot = MLOD_IF_MV_NONE;
    if (v >= ctl.eye_leaves - 1u || inherits || level[ctl.off_drawn + j] != 0u) {
        slot = atomicAdd(ctl.slots, 1u);
        level[ctl.off_slot_nodes + slot] = v;
    }
    level[ctl.off_slots + j] = slot;
    atomicMax(ctl.node_pairs, level[ctl.off_pairs + j]);
    level[ctl.off_pairs + j] = 0u;
    level[ctl.off_drawn + j] = 0u;
}
