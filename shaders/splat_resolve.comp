#version 450
// shaders/splat_resolve.comp - every atlas pixel's key to its depth (+inf
// where nothing was drawn) and, when the atlas has them, the winning node's
// normal (its cone's axis) and colour (0 where nothing was drawn).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "splat_layout.glsl"

void main()
{
    uint p = group_index() * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    if (p >= pc.pixel_count) return;
    uint node = keys[2u * p], ordered = keys[2u * p + 1u];
    if (ordered == EMPTY_WORD && node == EMPTY_WORD) {
        depth_out[p] = uintBitsToFloat(0x7f800000u);
        if (pc.want_normal != 0u) normal_out[3u * p] = normal_out[3u * p + 1u] = normal_out[3u * p + 2u] = 0.0;
        if (pc.want_color != 0u) color_out[3u * p] = color_out[3u * p + 1u] = color_out[3u * p + 2u] = 0.0;
        return;
    }
    uint bits = (ordered & 0x80000000u) != 0u ? ordered & 0x7fffffffu : ~ordered;
    depth_out[p] = uintBitsToFloat(bits);
    if (pc.want_normal != 0u) {
        vec4 cone = cones[node];
        normal_out[3u * p] = cone.x;
        normal_out[3u * p + 1u] = cone.y;
        normal_out[3u * p + 2u] = cone.z;
    }
    if (pc.want_color != 0u) {
        color_out[3u * p] = colors[3u * node];
        color_out[3u * p + 1u] = colors[3u * node + 1u];
        color_out[3u * p + 2u] = colors[3u * node + 2u];
    }
}
