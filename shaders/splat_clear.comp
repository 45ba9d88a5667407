#version 450
// shaders/splat_clear.comp - every atlas pixel's key to empty.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "splat_layout.glsl"

void main()
{
    uint p = group_index() * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    if (p < pc.pixel_count) keys[2u * p] = keys[2u * p + 1u] = EMPTY_WORD;
}
