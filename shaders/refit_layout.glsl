// shaders/refit_layout.glsl - buffers and push constants of the refit
// shaders (refit_check, refit_leaves, refit_merge); host side:
// mlodvk_refit_mesh in manylods_vk.h.  The refit is mlod_refit_mesh's:
// every leaf from its triangle and barycentrics (mlod__mesh_leaf), then
// every internal node from its children, one dispatch per depth, deepest
// first (mlod__merge_nodes).
#include "interface.h"

layout(std430, set = 0, binding = MLOD_IF_REFIT_SPHERES) buffer tree_spheres { vec4 spheres[]; };
layout(std430, set = 0, binding = MLOD_IF_REFIT_CONES) buffer tree_cones { vec4 cones[]; };
layout(std430, set = 0, binding = MLOD_IF_REFIT_COLORS) buffer tree_colors { float colors[]; };
layout(std430, set = 0, binding = MLOD_IF_REFIT_LEAF_SOURCES) readonly buffer leaf_sources_buffer { uint leaf_sources[]; };
layout(std430, set = 0, binding = MLOD_IF_REFIT_BARYCENTRICS) readonly buffer barycentrics_buffer { vec2 barycentrics[]; };
layout(std430, set = 0, binding = MLOD_IF_REFIT_TRIANGLE_AREAS) readonly buffer triangle_areas_buffer { uvec2 triangle_areas[]; }; // doubles, as their bits
layout(std430, set = 0, binding = MLOD_IF_REFIT_INDICES) readonly buffer indices_buffer { uint indices[]; };
layout(std430, set = 0, binding = MLOD_IF_REFIT_POSITIONS) readonly buffer positions_buffer { float positions[]; };
layout(std430, set = 0, binding = MLOD_IF_REFIT_NORMALS) readonly buffer normals_buffer { float normals[]; };
layout(std430, set = 0, binding = MLOD_IF_REFIT_VERTEX_COLORS) readonly buffer vertex_colors_buffer { float vertex_colors[]; };
layout(std430, set = 0, binding = MLOD_IF_REFIT_FINDINGS) buffer findings_buffer { MLOD_IF_FINDINGS(MLOD_IF_DECLARE) } findings;

layout(push_constant) uniform push_block { MLOD_IF_REFIT_PUSH(MLOD_IF_DECLARE) } pc;

uint group_index() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

// Attribute `which` of a vertex (0 position, 1 normal, 2 colour): floats.
vec3 vertex_float3(uint which, uint vertex)
{
    if (which == 0u) {
        uint at = vertex * pc.position_stride;
        return vec3(positions[at], positions[at + 1u], positions[at + 2u]);
    }
    if (which == 1u) {
        uint at = vertex * pc.normal_stride;
        return vec3(normals[at], normals[at + 1u], normals[at + 2u]);
    }
    uint at = vertex * pc.color_stride;
    return vec3(vertex_colors[at], vertex_colors[at + 1u], vertex_colors[at + 2u]);
}
