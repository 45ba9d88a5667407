// shaders/cut_step.glsl - the body of one round's first pass, compiled
// twice.  Every entry of the input list decides its action (one-edge move
// at most) and its output count; each workgroup sums its counts into
// block_sums for cut_scan.  Actions, as mlod__lazy_segment in manylods.h:
// an invalid internal node splits into its two children; a valid node next
// to its sibling merges into their parent when the parent is valid (the
// left child emits it, the right one emits nothing); anything else keeps
// its place.
//   cut_step.comp (MLOD_CUT_PASS_FILTER): statuses by the float filter
//     alone.  A workgroup with a status the filter is unsure of writes
//     nothing: it leaves its entries as they were and lists itself for
//     cut_exact (DEFERRED_BLOCK, ctl.args[3]).
//   cut_exact.comp: only the listed workgroups, each taken again whole
//     with classify (the filter, then the exact path where it is unsure).
// The exact path's double arithmetic is most of a shader that has it: kept
// out of the pass that every workgroup takes, it costs only where it is
// used.  On lavapipe its mere presence tripled the pass's time, and even
// an empty dispatch of it costs about 20 us a workgroup: cut_exact runs
// only as many workgroups as were deferred.
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "cut_layout.glsl"
#define MLOD_HAS_CONES (pc.has_cones != 0u)
#include "common.glsl"

shared uint sum_count[MLOD_IF_GROUP];
shared uint sum_evaluated[MLOD_IF_GROUP];
shared uint sum_steps[MLOD_IF_GROUP];
shared uint sum_unsure[MLOD_IF_GROUP];

#ifdef MLOD_CUT_PASS_FILTER
#define STATUS_OF(view, node) classify_fast(view, node, pc.leaf_count)
#else
#define STATUS_OF(view, node) classify(view, node, epsilon, pc.leaf_count)
#endif

// The entries of workgroup `group` of the round's input (its block).
void step_block(uint group)
{
    uint n = ctl.count[pc.slot];
#ifndef MLOD_CUT_PASS_FILTER
    real epsilon = r_f(pc.epsilon);
#endif
    uint i = group * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    uint out_count = 0u, evaluated = 0u, steps = 0u, raw = 0u, act = 0u;
    bool unsure = false;
    if (i < n) {
        uvec2 e = list_in[i];
        uint node = e.x, view = e.y, s;
        raw = status_in[i];
        s = raw & 7u;
        if (s == MLOD_IF_STATUS_PENDING || pc.trust == 0u) {
            s = STATUS_OF(view, node);
            unsure = s == 0u;
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
                uint ps = STATUS_OF(view, (node - 1u) / 2u);
                unsure = unsure || ps == 0u;
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
        out_count = act & 3u;
    }
    // workgroup sums: subgroup sums, then the first invocation adds those
    uint count_sg = subgroupAdd(out_count), evaluated_sg = subgroupAdd(evaluated), steps_sg = subgroupAdd(steps);
    bool unsure_sg = subgroupAny(unsure);
    if (subgroupElect()) {
        sum_count[gl_SubgroupID] = count_sg;
        sum_evaluated[gl_SubgroupID] = evaluated_sg;
        sum_steps[gl_SubgroupID] = steps_sg;
        sum_unsure[gl_SubgroupID] = unsure_sg ? 1u : 0u;
    }
    barrier();
#ifdef MLOD_CUT_PASS_FILTER
    {
        uint any_unsure;
        SUBGROUP_WORDS_SUM(sum_unsure, gl_NumSubgroups, any_unsure);
        if (any_unsure != 0u) { // the whole workgroup alike: listed for cut_exact
            if (gl_LocalInvocationID.x == 0u) defer_block(group);
            return;
        }
    }
#endif
    if (i < n) {
        status_in[i] = raw;
        acts[i] = act;
    }
    if (gl_SubgroupID == 0u) { // the first subgroup adds the sums up
        uint count_wg, evaluated_wg, steps_wg;
        SUBGROUP_WORDS_SUM(sum_count, gl_NumSubgroups, count_wg);
        SUBGROUP_WORDS_SUM(sum_evaluated, gl_NumSubgroups, evaluated_wg);
        SUBGROUP_WORDS_SUM(sum_steps, gl_NumSubgroups, steps_wg);
        if (subgroupElect()) {
            block_sums[group] = count_wg;
            if (evaluated_wg != 0u) MLOD_IF_COUNT64(ctl.evaluated, evaluated_wg);
            if (steps_wg != 0u) {
                MLOD_IF_COUNT64(ctl.steps, steps_wg);
                atomicAdd(ctl.changed, steps_wg);
            }
        }
    }
}

void main()
{
#ifdef MLOD_CUT_PASS_FILTER
    uint group = group_index();
    if (group * MLOD_IF_GROUP < ctl.count[pc.slot]) step_block(group);
#else
    // the deferred workgroups, args[3].x of them at a time
    for (uint k = gl_WorkGroupID.x; k < ctl.args[3].w; k += gl_NumWorkGroups.x) {
        step_block(DEFERRED_BLOCK(k));
        barrier(); // the shared sums are free again
    }
#endif
}
