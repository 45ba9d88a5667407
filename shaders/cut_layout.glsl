// shaders/cut_layout.glsl - the buffers and push constants shared by the cut
// shaders (cut_init, cut_step, cut_scan, cut_write, cut_finish); the host
// side is mlodvk__cut_* in manylods_vk.h.  One descriptor set:
//   0 spheres  1 cones  2 views  3 list in  4 list out  5 status in
//   6 status out  7 acts  8 block sums  9 control  10 view offsets
// A list entry is uvec2(node, view); its status is a separate uint (low 3
// bits MLOD_STATUS_* or 0 = pending; bit 3: the merge check already failed
// in this call).  Rounds alternate list and status buffers A -> B -> A; the
// control block records where the current list lives, and cut_finish moves
// it back to A: between calls the cut is list A, status A, ctl.current
// entries, grouped by view in view order, each view's left to right.
// Control block (std430, 104 bytes): args[3] at 0, count[2] at 48, changed
// 56, overflow 60, done 64, rounds 68, input_is_b 72, needed 76, current 80,
// evaluated 88, steps 96.

#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

#define GROUP 256u

layout(std430, set = 0, binding = 0) readonly buffer tree_spheres { vec4 spheres[]; };
layout(std430, set = 0, binding = 1) readonly buffer tree_cones { vec4 cones[]; };
layout(std430, set = 0, binding = 2) readonly buffer view_frames { double views[]; };
layout(std430, set = 0, binding = 3) buffer list_in_buffer { uvec2 list_in[]; };
layout(std430, set = 0, binding = 4) buffer list_out_buffer { uvec2 list_out[]; };
layout(std430, set = 0, binding = 5) buffer status_in_buffer { uint status_in[]; };
layout(std430, set = 0, binding = 6) buffer status_out_buffer { uint status_out[]; };
layout(std430, set = 0, binding = 7) buffer acts_buffer { uint acts[]; };
layout(std430, set = 0, binding = 8) buffer block_sums_buffer { uint block_sums[]; };
layout(std430, set = 0, binding = 9) coherent buffer control_block {
    uvec4 args[3];      // indirect dispatch arguments: a slot per round parity, then cut_finish's
    uint count[2];      // entries of the list each slot's round reads
    uint changed;       // splits and merges of the running round
    uint overflow;      // the last round needed more than capacity entries
    uint done;          // converged: no round changed anything
    uint rounds;        // rounds that changed the list
    uint input_is_b;    // the current list is in buffer B
    uint needed;        // entries the overflowing round needed
    uint current;       // entries of the current list
    uint pad;
    uint64_t evaluated; // criterion evaluations
    uint64_t steps;     // splits and merges
} ctl;
layout(std430, set = 0, binding = 10) buffer view_offsets_buffer { uint view_offsets[]; };

layout(push_constant) uniform push_block {
    float epsilon;
    uint leaf_count;
    uint view_count;
    uint has_cones;
    uint trust;        // statuses of the input are current (not the first round of a call)
    uint merge;        // look for sibling pairs to merge (incremental, lazy)
    uint slot;         // round parity: args[slot], count[slot]
    uint capacity;     // entries the output list holds
    uint max_groups_x; // the device's maxComputeWorkGroupCount[0]
} pc;

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
