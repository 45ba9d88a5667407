#version 450
// shaders/cut_scan.comp - one round of the cut, second pass, one
// workgroup: the exclusive prefix sum of the block sums of cut_step (each
// block's first output entry), then the round's bookkeeping in the control
// block: a round that changed nothing ends the loop (its output is not
// written: the list stays where it is); one whose output exceeds the
// capacity sets overflow and the entries it needs and ends the loop with
// its input intact (the host grows the buffers and resumes); otherwise the
// next round's dispatch arguments and count are armed.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "cut_layout.glsl"

shared uint chunk_sum[MLOD_IF_GROUP];

void main()
{
    // cut_exact has run: its list starts empty for the next round
    if (gl_LocalInvocationID.x == 0u) ctl.args[3] = uvec4(0u, 1u, 1u, 0u);
    if (ctl.done != 0u || ctl.overflow != 0u) return; // the loop has ended
    uint n = ctl.count[pc.slot];
    uint blocks = (n + MLOD_IF_GROUP - 1u) / MLOD_IF_GROUP;
    uint per = (blocks + MLOD_IF_GROUP - 1u) / MLOD_IF_GROUP;
    uint t = gl_LocalInvocationID.x;
    uint begin = min(t * per, blocks), end = min(begin + per, blocks);
    uint s = 0u;
    for (uint b = begin; b < end; b++) s += block_sums[b];
    chunk_sum[t] = s;
    barrier();
    // inclusive scan of the chunk sums (Hillis-Steele)
    for (uint stride = 1u; stride < MLOD_IF_GROUP; stride <<= 1) {
        uint add = t >= stride ? chunk_sum[t - stride] : 0u;
        barrier();
        chunk_sum[t] += add;
        barrier();
    }
    uint running = t > 0u ? chunk_sum[t - 1u] : 0u;
    for (uint b = begin; b < end; b++) {
        uint v = block_sums[b];
        block_sums[b] = running;
        running += v;
    }
    if (t == 0u) {
        uint total = chunk_sum[MLOD_IF_GROUP - 1u];
        uint next = pc.slot ^ 1u;
        ctl.current = n;
        if (ctl.changed == 0u) {
            ctl.done = 1u;
            ctl.args[pc.slot] = dispatch_of(0u);
            ctl.args[next] = dispatch_of(0u);
        } else if (total > pc.capacity) {
            ctl.overflow = 1u;
            ctl.needed = total;
            ctl.args[pc.slot] = dispatch_of(0u);
            ctl.args[next] = dispatch_of(0u);
        } else {
            ctl.current = total;
            ctl.count[next] = total;
            ctl.args[next] = dispatch_of((total + MLOD_IF_GROUP - 1u) / MLOD_IF_GROUP);
            ctl.input_is_b ^= 1u;
            ctl.rounds += 1u;
        }
        ctl.changed = 0u;
        ctl.args[2] = dispatch_of((ctl.current + MLOD_IF_GROUP - 1u) / MLOD_IF_GROUP);
    }
}
