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
//     adds their outputs to their blocks' sums.  With pc.settle, after
//     cut_finish, the entries it left pending instead (listed in acts):
//     their statuses alone, counted as evaluated by cut_finish already
//     (one pipeline for both: each copy of the exact path is seconds of a
//     driver's compiling with emulated doubles).
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

// Whether entry i (node of view, its status s and raw byte) may merge with
// its sibling: valid, beside it in the list (the left child's right
// neighbour), its parent not already found invalid in this call.
bool may_merge(uint i, uint n, uint node, uint view, uint s, uint raw)
{
#ifdef MLOD_CUT_NO_MERGE
    return false;
#else
    if (!(pc.merge != 0u && status_valid(s) && node > 0u && (raw & 8u) == 0u)) return false;
    return (node & 1u) != 0u ? (i + 1u < n && list_in[i + 1u] == uvec2(node + 1u, view))
                             : (i > 0u && list_in[i - 1u] == uvec2(node - 1u, view));
#endif
}

// Entry i of the round's n input entries: its status and action written
// (status_in[i], acts[i]), and its output entries, evaluations and steps
// added to the counts.  Returns false, writing and counting nothing, when
// the float filter (MLOD_CUT_PASS_FILTER) is unsure of a status it needs.
// settle (cut_exact with pc.settle): its status alone, into status_in[i].
bool step_entry(uint i, uint n, bool settle, inout uint out_count, inout uint evaluated, inout uint steps)
{
#ifndef MLOD_CUT_PASS_FILTER
    real epsilon = r_f(pc.epsilon);
#endif
    uvec2 e = list_in[i];
    uint node = e.x, view = e.y, raw = status_in[i], s = raw & 7u, ps = 0u, act, evals = 0u, moves = 0u;
    bool own = settle || s == MLOD_IF_STATUS_PENDING || pc.trust == 0u, paired = false;
    // the statuses it needs: its own (when pending, or not trusted), then
    // its parent's (when it may merge)
#ifdef MLOD_CUT_PASS_FILTER
    if (own) {
        s = raw = STATUS_OF(view, node);
        if (s == 0u) return false;
        evals++;
    }
    paired = may_merge(i, n, node, view, s, raw);
    if (paired) {
        ps = STATUS_OF(view, (node - 1u) / 2u);
        if (ps == 0u) return false;
        evals++;
    }
#else
    // the same in a loop around one call: the driver inlines each call, and
    // with emulated doubles each copy of the exact path costs lavapipe
    // seconds of compiling (cut_exact's pipeline: 21 s with one, 36 s with
    // two); not for the float filter, which the loop slows by a sixth
    [[dont_unroll]] for (uint round = 0u; round < 2u; round++) {
        if (round == 0u && !own) continue;
        if (round == 1u && (settle || !(paired = may_merge(i, n, node, view, s, raw)))) break;
        uint st = STATUS_OF(view, round == 0u ? node : (node - 1u) / 2u);
        if (st == 0u) return false;
        evals++;
        if (round == 0u) s = raw = st;
        else ps = st;
    }
    if (settle) {
        status_in[i] = raw;
        return true;
    }
#endif
    act = (ACT_KEEP << 2) | 1u | (raw << 4);
    if (s == MLOD_IF_STATUS_COARSE) {
        act = (ACT_SPLIT << 2) | 2u;
        moves++;
    } else if (paired) {
        bool left = (node & 1u) != 0u;
        if (status_valid(ps)) {
            act = left ? ((ACT_PARENT << 2) | 1u | (ps << 4)) : (ACT_DROP << 2);
            if (left) moves++;
        } else {
            raw |= 8u; // the parent stays invalid for the rest of this call
            act = (ACT_KEEP << 2) | 1u | (raw << 4);
        }
    }
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
    if (i < n && !step_entry(i, n, false, out_count, evaluated, steps)) status_out[defer_entry()] = i;
    count_workgroup(out_count, evaluated, steps, group);
#else
    // the deferred entries (or with pc.settle cut_finish's pending ones),
    // args[3].x workgroups of them at a time
    uint listed = ctl.args[3].w;
    bool settle = pc.settle != 0u;
    for (uint g = gl_WorkGroupID.x; g * MLOD_IF_GROUP < listed; g += gl_NumWorkGroups.x) {
        uint k = g * MLOD_IF_GROUP + gl_LocalInvocationID.x, block_count = 0u;
        if (k < listed) {
            uint i = settle ? acts[k] : status_out[k];
            step_entry(i, n, settle, block_count, evaluated, steps);
            if (block_count != 0u) atomicAdd(block_sums[i / MLOD_IF_GROUP], block_count);
        }
    }
    if (!settle) count_workgroup(0u, evaluated, steps, MLOD_NO_BLOCK); // the outputs went to their blocks above
#endif
}
