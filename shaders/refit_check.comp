#version 450
// shaders/refit_check.comp - what mlod_refit_mesh checks before it writes
// anything (mlod__check_mesh, the growth test), over the user's vertex
// buffers: thread i checks vertex i (i < pc.count: finite positions within
// 1e36, finite normals and colours) and triangle i (i < pc.first: its area
// over its area at build, for triangles that had area).  The host reads the
// findings and refits only when they are clean.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_EXT_control_flow_attributes : require
#define MLOD_NO_VIEWS
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "refit_layout.glsl"
#include "common.glsl"
#include "refit_mesh.glsl"

bool finite3(dvec3 v) { return !any(isinf(v)) && !any(isnan(v)); }

void main()
{
    uint i = group_index() * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    if (i < pc.count) {
        uint flags = 0u;
        dvec3 p = vertex_attribute(0u, i);
        if (!finite3(p)) flags |= 1u;
        else if (any(greaterThan(abs(p), dvec3(1e36LF)))) flags |= 2u;
        if (pc.normal_stride != 0u && !finite3(vertex_attribute(1u, i))) flags |= 4u;
        if (pc.color_stride != 0u && !finite3(vertex_attribute(2u, i))) flags |= 8u;
        if (flags != 0u) {
            atomicOr(findings.flags, flags);
            atomicMin(findings.first_vertex, i);
        }
    }
    if (i < pc.first && triangle_areas[i] > 0.0LF) {
        precise double g = triangle_area(i) / triangle_areas[i];
        if (!isnan(g)) atomicMax(findings.growth_bits, doubleBitsToUint64(g));
    }
}
