#version 450
// shaders/cut_write.comp - one round of the cut, third pass: every entry
// writes its outputs (cut_step's action) at its block's offset (cut_scan)
// plus its rank among the block's outputs, so each view's list stays in
// left-to-right order, as on the CPU.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_EXT_control_flow_attributes : require
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "cut_layout.glsl"

shared uint prefix[MLOD_IF_GROUP];

void main()
{
    uint n = ctl.count[pc.slot];
    uint group = group_index();
    uint t = gl_LocalInvocationID.x;
    uint i = group * MLOD_IF_GROUP + t;
    uint act = i < n ? acts[i] : 0u;
    // the entry's rank among the workgroup's outputs: within its subgroup,
    // plus the outputs of the subgroups before it
    uint count = act & 3u, before = subgroupExclusiveAdd(count), total = subgroupAdd(count);
    if (subgroupElect()) prefix[gl_SubgroupID] = total;
    barrier();
    uint base;
    SUBGROUP_WORDS_SUM(prefix, gl_SubgroupID, base);
    if (i >= n) return;
    uint at = block_sums[group] + base + before;
    uvec2 e = list_in[i];
    uint kind = (act >> 2) & 3u;
    // the first output of any kind but a drop by one store, the second
    // (a split's right child) by another: a SIMD device (lavapipe) runs
    // every branch, and each store is a loop over its lanes there
    uint first = kind == ACT_SPLIT ? 2u * e.x + 1u : kind == ACT_PARENT ? (e.x - 1u) / 2u : e.x;
    if (kind != ACT_DROP) {
        list_out[at] = uvec2(first, e.y);
        status_out[at] = kind == ACT_SPLIT ? 0u : act >> 4;
    }
    if (kind == ACT_SPLIT) {
        list_out[at + 1u] = uvec2(first + 1u, e.y);
        status_out[at + 1u] = 0u;
    }
}
