// shaders/cut_step.glsl - the body of one round's first pass, compiled
// twice.  Every entry of the input list decides its action (one-edge move
// at most) and its output count; each workgroup sums its counts into
// block_sums for cut_scan.  Actions, as mlod__lazy_segment in manylods.h:
// an invalid internal node splits into its two children; a valid node next
// to its sibling merges into their parent when the parent is valid (the
// left child emits it, the right one emits nothing); anything else keeps
// its place.
//   cut_step.comp (MLOD_CUT_PASS_FILTER): statuses by the float filter
//     alone.  An entry with a status the filter is unsure of (its own or
//     its parent's) writes nothing and counts nothing: it lists itself for
//     cut_exact (defer_entry, ctl.args[3]; the list in status_out).
//   cut_step_basic.comp (MLOD_CUT_PASS_FILTER, MLOD_CUT_NO_MERGE): the
//     same for updates that merge nothing (basic mode), with the merge
//     check left out: a SIMD device (lavapipe) runs every branch a
//     workgroup's code has, taken or not, and the check's second filter
//     was an eighth of the basic cut's time there.
//   cut_exact.comp: only the listed entries, each taken again with
//     classify (the filter, then the exact path where it is unsure); it
//     adds their outputs to their blocks' sums.
// The exact path's double arithmetic is most of a shader that has it: kept
// out of the pass that every entry takes, it costs only where it is used.
// On lavapipe its mere presence tripled the pass's time; taking again
// only the entries the filter is unsure of (about 0.2 % of them), not
// their whole workgroups, took the exact pass from a third of the cut's
// time to a small share.
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#define MLOD_CUT_COUNTS
#include "cut_layout.glsl"
#define MLOD_HAS_CONES (pc.has_cones != 0u)
#include "common.glsl"

#ifdef MLOD_CUT_PASS_FILTER
#define STATUS_OF(view, node) classify_fast(view, node, pc.leaf_count)
#else
#define STATUS_OF(view, node) classify(view, node, epsilon, pc.leaf_count)
#endif

// Entry i of the round's n input entries: its status and action written
// (status_in[i], acts[i]), and its output entries, evaluations and steps
// added to the counts.  Returns false, writing and counting nothing, when
// the float filter (MLOD_CUT_PASS_FILTER) is unsure of a status it needs.
bool step_entry(uint i, uint n, inout uint out_count, inout uint evaluated, inout uint steps)
{
#ifndef MLOD_CUT_PASS_FILTER
    real epsilon = r_f(pc.epsilon);
#endif
    uvec2 e = list_in[i];
    uint node = e.x, view = e.y, raw = status_in[i], s = raw & 7u, act, evals = 0u, moves = 0u;
    if (s == MLOD_IF_STATUS_PENDING || pc.trust == 0u) {
        s = STATUS_OF(view, node);
        if (s == 0u) return false;
        evals++;
        raw = s;
    }
    act = (ACT_KEEP << 2) | 1u | (raw << 4);
    if (s == MLOD_IF_STATUS_COARSE) {
        act = (ACT_SPLIT << 2) | 2u;
        moves++;
    }
#ifndef MLOD_CUT_NO_MERGE
    else if (pc.merge != 0u && status_valid(s) && node > 0u && (raw & 8u) == 0u) {
        bool left = (node & 1u) != 0u;
        bool paired = left ? (i + 1u < n && list_in[i + 1u] == uvec2(node + 1u, view))
                           : (i > 0u && list_in[i - 1u] == uvec2(node - 1u, view));
        if (paired) {
            uint ps = STATUS_OF(view, (node - 1u) / 2u);
            if (ps == 0u) return false;
            evals++;
            if (status_valid(ps)) {
                act = left ? ((ACT_PARENT << 2) | 1u | (ps << 4)) : (ACT_DROP << 2);
                if (left) moves++;
            } else {
                raw |= 8u; // the parent stays invalid for the rest of this call
                act = (ACT_KEEP << 2) | 1u | (raw << 4);
            }
        }
    }
#endif
    status_in[i] = raw;
    acts[i] = act;
    out_count += act & 3u;
    evaluated += evals;
    steps += moves;
    return true;
}

void main()
{
    uint n = ctl.count[pc.slot], out_count = 0u, evaluated = 0u, steps = 0u;
#ifdef MLOD_CUT_PASS_FILTER
    uint group = group_index();
    if (group * MLOD_IF_GROUP >= n) return; // the whole workgroup alike
    uint i = group * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    if (i < n && !step_entry(i, n, out_count, evaluated, steps)) status_out[defer_entry()] = i;
    count_workgroup(out_count, evaluated, steps, group);
#else
    // the deferred entries, args[3].x workgroups of them at a time
    uint listed = ctl.args[3].w;
    for (uint g = gl_WorkGroupID.x; g * MLOD_IF_GROUP < listed; g += gl_NumWorkGroups.x) {
        uint k = g * MLOD_IF_GROUP + gl_LocalInvocationID.x, block_count = 0u;
        if (k < listed) {
            uint i = status_out[k];
            step_entry(i, n, block_count, evaluated, steps);
            if (block_count != 0u) atomicAdd(block_sums[i / MLOD_IF_GROUP], block_count);
        }
    }
    count_workgroup(0u, evaluated, steps, MLOD_NO_BLOCK); // the outputs went to their blocks above
#endif
}
