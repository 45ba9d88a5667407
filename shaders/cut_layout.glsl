// shaders/cut_layout.glsl - the buffers and push constants shared by the cut
// shaders (cut_init, cut_step, cut_scan, cut_write, cut_finish); the host
// side is mlodvk__cut_* in manylods_vk.h.  One descriptor set:
//   0 spheres  1 cones  2 views  3 list in  4 list out  5 status in
//   6 status out  7 acts  8 block sums  9 control  10 view offsets
//   11 view filters (vec4s: the float filter, interface.h)
// A list entry is uvec2(node, view); its status is a separate uint (low 3
// bits MLOD_STATUS_* or 0 = pending; bit 3: the merge check already failed
// in this call).  Rounds alternate list and status buffers A -> B -> A; the
// control block records where the current list lives, and cut_finish moves
// it back to A: between calls the cut is list A, status A, ctl.current
// entries, grouped by view in view order, each view's left to right.
// The bindings, the control block and the push constants: interface.h.

#include "interface.h"

layout(std430, set = 0, binding = MLOD_IF_CUT_SPHERES) readonly buffer tree_spheres { vec4 spheres[]; };
layout(std430, set = 0, binding = MLOD_IF_CUT_CONES) readonly buffer tree_cones { vec4 cones[]; };
layout(std430, set = 0, binding = MLOD_IF_CUT_VIEWS) readonly buffer view_frames { uvec2 views[]; }; // doubles, as their bits (real.glsl: r_load)
layout(std430, set = 0, binding = MLOD_IF_CUT_LIST_IN) buffer list_in_buffer { uvec2 list_in[]; };
layout(std430, set = 0, binding = MLOD_IF_CUT_LIST_OUT) buffer list_out_buffer { uvec2 list_out[]; };
layout(std430, set = 0, binding = MLOD_IF_CUT_STATUS_IN) buffer status_in_buffer { uint status_in[]; };
layout(std430, set = 0, binding = MLOD_IF_CUT_STATUS_OUT) buffer status_out_buffer { uint status_out[]; };
layout(std430, set = 0, binding = MLOD_IF_CUT_ACTS) buffer acts_buffer { uint acts[]; };
layout(std430, set = 0, binding = MLOD_IF_CUT_BLOCK_SUMS) buffer block_sums_buffer { uint block_sums[]; };
layout(std430, set = 0, binding = MLOD_IF_CUT_CONTROL) coherent buffer control_block { MLOD_IF_CONTROL(MLOD_IF_DECLARE, MLOD_IF_DECLARE_ARRAY) } ctl;
layout(std430, set = 0, binding = MLOD_IF_CUT_VIEW_OFFSETS) buffer view_offsets_buffer { uint view_offsets[]; };
layout(std430, set = 0, binding = MLOD_IF_CUT_FILTERS) readonly buffer view_filters { vec4 filters[]; };
#define MLOD_HAS_FILTERS // common.glsl's classify tries the float filter first (fast_status)

layout(push_constant) uniform push_block { MLOD_IF_CUT_PUSH(MLOD_IF_DECLARE) } pc;

// Add v to a 64-bit count of the control block (two words, low first)
// with 32-bit atomics: the carry goes to the high word.
#define MLOD_IF_COUNT64(count, v)                                                                                      \
    {                                                                                                                  \
        uint add_ = (v), was_ = atomicAdd(count[0], add_);                                                             \
        if (was_ + add_ < was_) atomicAdd(count[1], 1u);                                                               \
    }

// List an entry for the exact pass that follows (cut_exact after cut_step,
// cut_exact with pc.settle after cut_finish), which runs args[3].x
// workgroups over the args[3].w entries listed.  Returns the entry's place in the list, which
// the caller writes: status_out[k] in a round (free until cut_write
// fills it), acts[k] in cut_finish (free after the last round).
uint defer_entry()
{
    uint k = atomicAdd(ctl.args[3].w, 1u);
    if (k % MLOD_IF_GROUP == 0u && k / MLOD_IF_GROUP < pc.max_groups_x) atomicMax(ctl.args[3].x, k / MLOD_IF_GROUP + 1u);
    atomicAdd(ctl.deferred, 1u);
    return k;
}

// The sum of words[k] over k < limit, words a shared array with a word
// per subgroup, in every invocation of the calling subgroup, all of whose
// invocations must call it.  The subgroup's invocations read the words
// together, each every gl_SubgroupSize-th one, and add them with one
// subgroupAdd: a loop over every word in every invocation costs a SIMD
// device (lavapipe) a load per invocation and word, which was a fifth of
// the cut's time there.
#define SUBGROUP_WORDS_SUM(words, limit, sum)                                                                          \
    {                                                                                                                  \
        uint part_ = 0u;                                                                                               \
        for (uint k_ = gl_SubgroupInvocationID; k_ < (limit); k_ += gl_SubgroupSize) part_ += words[k_];               \
        sum = subgroupAdd(part_);                                                                                      \
    }

#ifdef MLOD_CUT_COUNTS
// The workgroup's counts, a word per subgroup (count_workgroup).
shared uint sum_count[MLOD_IF_GROUP];
shared uint sum_evaluated[MLOD_IF_GROUP];
shared uint sum_steps[MLOD_IF_GROUP];

#define MLOD_NO_BLOCK 0xffffffffu

// Add the workgroup's evaluations and steps to the call's counts (and the
// steps to the round's changes), and its output entries to
// block_sums[block] unless block is MLOD_NO_BLOCK (cut_exact adds its
// outputs entry by entry; cut_finish has none).  Every invocation calls it.
void count_workgroup(uint out_count, uint evaluated, uint steps, uint block)
{
    uint count_sg = subgroupAdd(out_count), evaluated_sg = subgroupAdd(evaluated), steps_sg = subgroupAdd(steps);
    if (subgroupElect()) {
        sum_count[gl_SubgroupID] = count_sg;
        sum_evaluated[gl_SubgroupID] = evaluated_sg;
        sum_steps[gl_SubgroupID] = steps_sg;
    }
    barrier();
    if (gl_SubgroupID == 0u) { // the first subgroup adds the sums up
        uint count_wg, evaluated_wg, steps_wg;
        SUBGROUP_WORDS_SUM(sum_count, gl_NumSubgroups, count_wg);
        SUBGROUP_WORDS_SUM(sum_evaluated, gl_NumSubgroups, evaluated_wg);
        SUBGROUP_WORDS_SUM(sum_steps, gl_NumSubgroups, steps_wg);
        if (subgroupElect()) {
            if (block != MLOD_NO_BLOCK) block_sums[block] = count_wg;
            if (evaluated_wg != 0u) MLOD_IF_COUNT64(ctl.evaluated, evaluated_wg);
            if (steps_wg != 0u) {
                MLOD_IF_COUNT64(ctl.steps, steps_wg);
                atomicAdd(ctl.changed, steps_wg);
            }
        }
    }
}
#endif

#define ACT_KEEP 0u
#define ACT_SPLIT 1u
#define ACT_PARENT 2u
#define ACT_DROP 3u

uint group_index() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

// Indirect dispatch arguments for `groups` workgroups.
uvec4 dispatch_of(uint groups)
{
    if (groups == 0u) return uvec4(0u, 1u, 1u, 0u);
    uint x = min(groups, pc.max_groups_x);
    return uvec4(x, (groups + x - 1u) / x, 1u, 0u);
}
