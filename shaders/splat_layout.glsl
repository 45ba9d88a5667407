// shaders/splat_layout.glsl - buffers and push constants of the splat
// shaders (splat_clear, splat_draw, splat_resolve); host side:
// mlodvk_splat in manylods_vk.h.  Each atlas pixel holds a 64-bit key while
// drawing: the depth as an order-preserving 32-bit pattern, then the index
// of the cut entry, so that atomicMin keeps the nearest depth and, among
// equal depths, the entry first in cut order (as mlod_splat: the node drawn
// first).  splat_resolve turns keys into depth, normal and colour.

#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

#define GROUP 256u

layout(std430, set = 0, binding = 0) readonly buffer tree_spheres { vec4 spheres[]; };
layout(std430, set = 0, binding = 1) readonly buffer tree_cones { vec4 cones[]; };
layout(std430, set = 0, binding = 2) readonly buffer view_frames { double views[]; };
layout(std430, set = 0, binding = 3) readonly buffer cut_list { uvec2 list[]; };
layout(std430, set = 0, binding = 4) readonly buffer cut_status { uint status[]; };
layout(std430, set = 0, binding = 5) readonly buffer tree_colors { float colors[]; };
layout(std430, set = 0, binding = 6) readonly buffer atlas_tiles { uint tiles[]; };
layout(std430, set = 0, binding = 7) buffer atlas_keys { uint64_t keys[]; };
layout(std430, set = 0, binding = 8) writeonly buffer atlas_depth { float depth_out[]; };
layout(std430, set = 0, binding = 9) writeonly buffer atlas_normal { float normal_out[]; };
layout(std430, set = 0, binding = 10) writeonly buffer atlas_color { float color_out[]; };
layout(std430, set = 0, binding = 11) readonly buffer control_block {
    uvec4 args[3];
    uint count[2];
    uint changed, overflow, done, rounds, input_is_b, needed, current, pad;
    uint64_t evaluated, steps;
} ctl;

layout(push_constant) uniform push_block {
    uint atlas_width;
    uint pixel_count;
    uint has_cones;
    uint want_normal; // the atlas has normals (the tree has cones)
    uint want_color;  // the atlas has colours (the tree has colours)
    uint max_groups_x;
    float disc_scale; // drawn radius / image radius, in (0, 1]; below 1, no pixel-holding-the-centre fallback
} pc;

uint group_index() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

#define EMPTY_KEY 0xffffffffffffffffUL
