#version 450
// shaders/refit_check.comp - what mlod_refit_mesh checks before it writes
// anything (mlod__check_mesh, the growth test), over the user's vertex
// buffers: thread i checks vertex i (i < pc.count: finite positions within
// 1e36, finite normals and colours) and triangle i (i < pc.first: its area
// over its area at build, for triangles that had area), in two passes for
// the largest growth with 32-bit atomics (interface.h: MLOD_IF_FINDINGS).
// The host reads the findings and refits only when they are clean.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_EXT_control_flow_attributes : require
#define MLOD_NO_VIEWS
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "refit_layout.glsl"
#include "common.glsl"
#include "refit_mesh.glsl"

// No component infinite or NaN (all exponent bits set), on the bits: a
// device's float comparisons may not keep NaNs.
bool finite3(vec3 v)
{
    uvec3 e = floatBitsToUint(v) & 0x7F800000u;
    return e.x != 0x7F800000u && e.y != 0x7F800000u && e.z != 0x7F800000u;
}

// Beyond 1e36 (in double, as the CPU compares)?
bool beyond(float x) { return r_gt(r_abs(r_f(x)), RK(0x476812F9u, 0xCF7920E3u, 1e36LF)); }

void main()
{
    uint i = group_index() * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    if (pc.pass == 0u && i < pc.count) {
        uint flags = 0u;
        vec3 p = vertex_float3(0u, i);
        if (!finite3(p)) flags |= 1u;
        else if (beyond(p.x) || beyond(p.y) || beyond(p.z)) flags |= 2u;
        if (pc.normal_stride != 0u && !finite3(vertex_float3(1u, i))) flags |= 4u;
        if (pc.color_stride != 0u && !finite3(vertex_float3(2u, i))) flags |= 8u;
        if (flags != 0u) {
            atomicOr(findings.flags, flags);
            atomicMin(findings.first_vertex, i);
        }
    }
    if (i < pc.first && r_gt(r_load(triangle_areas[i]), R_ZERO)) {
        real g = r_div(triangle_area(i), r_load(triangle_areas[i]));
        if (!r_isnan(g)) {
            uvec2 bits = r_bits(g); // g >= 0: its bits order as it does
            if (pc.pass == 0u)
                atomicMax(findings.growth_high, bits.y);
            else if (bits.y == findings.growth_high)
                atomicMax(findings.growth_low, bits.x);
        }
    }
}
