#version 450
// shaders/mv_pairs.comp - one round over pairs_in (pc.items pairs of this
// level's view nodes): each pair's action (common.glsl: pair_action), and
// its outcome appended: split scene nodes' children to pairs_out, split
// view nodes' children to the next level (lists, from 0), draws to the
// level's draws (lists, from ctl.next_capacity), with the counts of
// mlod_megaviews_stats.  The host sizes the lists for the worst case (two
// pairs out per pair in) before each round.
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
    uint v = pairs_in[i].x, s = pairs_in[i].y, j = v - ctl.first;
    atomicAdd(level[ctl.off_pairs + j], 1u);
    atomicAdd(ctl.pairs, 1u);
    uint action = pair_action(v, s);
    if (action == MV_PAIR_CULL) {
        atomicAdd(ctl.culled, 1u);
    } else if (action == MV_PAIR_DRAW || action == MV_PAIR_DRAW_LEAF) {
        uint at = atomicAdd(ctl.draw_count, 1u);
        lists[ctl.next_capacity + at] = uvec2(v, s);
        level[ctl.off_drawn + j] = 1u;
        if (v >= ctl.eye_leaves - 1u) {
            atomicAdd(ctl.leaf_draws, 1u);
        } else {
            uint below = leaves_below(v, ctl.eye_leaves);
            atomicAdd(ctl.shared_draws, 1u);
            if (action == MV_PAIR_DRAW_LEAF) atomicAdd(ctl.shared_leaves, 1u);
            if (atomicAdd(ctl.shared_views_low, below) > 0xffffffffu - below) atomicAdd(ctl.shared_views_high, 1u);
        }
    } else if (action == MV_PAIR_SPLIT_SCENE) {
        uint at = atomicAdd(ctl.out_count, 2u);
        pairs_out[at] = uvec2(v, 2u * s + 1u);
        pairs_out[at + 1u] = uvec2(v, 2u * s + 2u);
    } else {
        uint at = atomicAdd(ctl.next_count, 2u);
        lists[at] = uvec2(2u * v + 1u, s);
        lists[at + 1u] = uvec2(2u * v + 2u, s);
    }
}
