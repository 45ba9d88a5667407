#version 450
// shaders/splat_clear.comp - every atlas pixel's key to empty.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
layout(local_size_x = 256) in;
#include "splat_layout.glsl"

void main()
{
    uint p = group_index() * GROUP + gl_LocalInvocationID.x;
    if (p < pc.pixel_count) keys[p] = EMPTY_KEY;
}
