// shaders/refit_layout.glsl - buffers and push constants of the refit
// shaders (refit_check, refit_leaves, refit_merge); host side:
// mlodvk_refit_mesh in manylods_vk.h.  The refit is mlod_refit_mesh's:
// every leaf from its triangle and barycentrics (mlod__mesh_leaf), then
// every internal node from its children, one dispatch per depth, deepest
// first (mlod__merge_nodes).
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

#define GROUP 256u

layout(std430, set = 0, binding = 0) buffer tree_spheres { vec4 spheres[]; };
layout(std430, set = 0, binding = 1) buffer tree_cones { vec4 cones[]; };
layout(std430, set = 0, binding = 2) buffer tree_colors { float colors[]; };
layout(std430, set = 0, binding = 3) readonly buffer leaf_sources_buffer { uint leaf_sources[]; };
layout(std430, set = 0, binding = 4) readonly buffer barycentrics_buffer { vec2 barycentrics[]; };
layout(std430, set = 0, binding = 5) readonly buffer triangle_areas_buffer { double triangle_areas[]; };
layout(std430, set = 0, binding = 6) readonly buffer indices_buffer { uint indices[]; };
layout(std430, set = 0, binding = 7) readonly buffer positions_buffer { float positions[]; };
layout(std430, set = 0, binding = 8) readonly buffer normals_buffer { float normals[]; };
layout(std430, set = 0, binding = 9) readonly buffer vertex_colors_buffer { float vertex_colors[]; };
// refit_check's findings: [0] flags (1 a non-finite position, 2 a position
// beyond 1e36, 4 a non-finite normal, 8 a non-finite colour), [1] the first
// vertex flagged (atomicMin), then the largest growth of a triangle's area
// (a positive double, its bits ordered as a uint64).
layout(std430, set = 0, binding = 10) buffer findings_buffer {
    uint flags;
    uint first_vertex;
    uint64_t growth_bits;
} findings;

layout(push_constant) uniform push_block {
    double area_unit;     // tree->area_unit
    float radius_scale;   // tree->radius_scale
    uint leaf_count;
    uint count;           // items of this dispatch: vertices (check), leaves, or nodes of one depth
    uint first;           // refit_merge: the depth's first node; refit_check: triangles
    uint position_stride; // floats between consecutive vertices' attributes
    uint normal_stride;   // 0: no normals
    uint color_stride;    // 0: no colours
    uint has_cones;
    uint has_colors;
    uint max_groups_x;
} pc;

uint group_index() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

dvec3 vertex_attribute(uint which, uint vertex)
{
    if (which == 0u) {
        uint at = vertex * pc.position_stride;
        return dvec3(double(positions[at]), double(positions[at + 1u]), double(positions[at + 2u]));
    }
    if (which == 1u) {
        uint at = vertex * pc.normal_stride;
        return dvec3(double(normals[at]), double(normals[at + 1u]), double(normals[at + 2u]));
    }
    uint at = vertex * pc.color_stride;
    return dvec3(double(vertex_colors[at]), double(vertex_colors[at + 1u]), double(vertex_colors[at + 2u]));
}

