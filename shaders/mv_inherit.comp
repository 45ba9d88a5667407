#version 450
// shaders/mv_inherit.comp - one thread per pixel of the level's slots
// (pc.items = slots x pixels): the pixel from the parent's map (where it
// holds a node; `who` that node), its depth measured again from this node's
// centre (common.glsl: node_distance, or with tangent discs remeasure:
// along the pixel's ray), as mlod__mv_inherit; empty otherwise.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_EXT_control_flow_attributes : require
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "mv_layout.glsl"

void main()
{
    uint i = group_index() * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    if (i >= pc.items) return;
    uint slot = i / ctl.pixels, p = i - slot * ctl.pixels, v = level[ctl.off_slot_nodes + slot];
    uint parent = v > 0u ? level[ctl.off_prev_slots + (v - 1u) / 2u - ctl.prev_first] : MLOD_IF_MV_NONE;
    uint at = MLOD_IF_MV_WORDS * i;
    maps[at] = maps[at + 1u] = maps[at + 2u] = MLOD_IF_MV_NONE;
    if (parent == MLOD_IF_MV_NONE) return;
    uint from = MLOD_IF_MV_WORDS * (parent * ctl.pixels + p);
    if (prev_maps[from] == MLOD_IF_MV_NONE) return;
    uint node = prev_maps[from + 2u], row = p / (2u * ctl.resolution), col = p - row * 2u * ctl.resolution;
    mv_eye = r3_f(eye_spheres[v].xyz);
    maps[at] = mv_ordered(ctl.tangent != 0u ? remeasure(node, col, row, true) : node_distance(node, mv_eye));
    maps[at + 1u] = node;
    maps[at + 2u] = node;
}
