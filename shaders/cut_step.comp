#version 450
// shaders/cut_step.comp - one round of the cut, first pass: every entry of
// the input list decides its action (one-edge move at most) and its output
// count; each workgroup sums its counts into block_sums for cut_scan.
// Actions, as mlod__lazy_segment in manylods.h: an invalid internal node
// splits into its two children; a valid node next to its sibling merges
// into their parent when the parent is valid (the left child emits it, the
// right one emits nothing); anything else keeps its place.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_EXT_control_flow_attributes : require
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "cut_layout.glsl"
#define MLOD_HAS_CONES (pc.has_cones != 0u)
#include "common.glsl"

shared uint sum_count[MLOD_IF_GROUP];
shared uint sum_evaluated[MLOD_IF_GROUP];
shared uint sum_steps[MLOD_IF_GROUP];

void main()
{
    uint n = ctl.count[pc.slot];
    uint group = group_index();
    uint i = group * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    uint out_count = 0u, evaluated = 0u, steps = 0u;
    real epsilon = r_f(pc.epsilon);
    if (i < n) {
        uvec2 e = list_in[i];
        uint node = e.x, view = e.y, raw = status_in[i], s = raw & 7u, act;
        if (s == MLOD_IF_STATUS_PENDING || pc.trust == 0u) {
            s = classify(view, node, epsilon, pc.leaf_count);
            evaluated++;
            raw = s;
        }
        act = (ACT_KEEP << 2) | 1u | (raw << 4);
        if (s == MLOD_IF_STATUS_COARSE) {
            act = (ACT_SPLIT << 2) | 2u;
            steps++;
        } else if (pc.merge != 0u && status_valid(s) && node > 0u && (raw & 8u) == 0u) {
            bool left = (node & 1u) != 0u;
            bool paired = left ? (i + 1u < n && list_in[i + 1u] == uvec2(node + 1u, view))
                               : (i > 0u && list_in[i - 1u] == uvec2(node - 1u, view));
            if (paired) {
                uint ps = classify(view, (node - 1u) / 2u, epsilon, pc.leaf_count);
                evaluated++;
                if (status_valid(ps)) {
                    act = left ? ((ACT_PARENT << 2) | 1u | (ps << 4)) : (ACT_DROP << 2);
                    if (left) steps++;
                } else {
                    raw |= 8u; // the parent stays invalid for the rest of this call
                    act = (ACT_KEEP << 2) | 1u | (raw << 4);
                }
            }
        }
        status_in[i] = raw;
        acts[i] = act;
        out_count = act & 3u;
    }
    // workgroup sums: subgroup sums, then the first invocation adds those
    uint count_sg = subgroupAdd(out_count), evaluated_sg = subgroupAdd(evaluated), steps_sg = subgroupAdd(steps);
    if (subgroupElect()) {
        sum_count[gl_SubgroupID] = count_sg;
        sum_evaluated[gl_SubgroupID] = evaluated_sg;
        sum_steps[gl_SubgroupID] = steps_sg;
    }
    barrier();
    if (gl_LocalInvocationID.x == 0u)
        for (uint k = 1u; k < gl_NumSubgroups; k++) {
            sum_count[0] += sum_count[k];
            sum_evaluated[0] += sum_evaluated[k];
            sum_steps[0] += sum_steps[k];
        }
    if (gl_LocalInvocationID.x == 0u && group * MLOD_IF_GROUP < n) {
        block_sums[group] = sum_count[0];
        if (sum_evaluated[0] != 0u) MLOD_IF_COUNT64(ctl.evaluated, sum_evaluated[0]);
        if (sum_steps[0] != 0u) {
            MLOD_IF_COUNT64(ctl.steps, sum_steps[0]);
            atomicAdd(ctl.changed, sum_steps[0]);
        }
    }
}
