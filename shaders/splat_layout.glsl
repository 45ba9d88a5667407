// shaders/splat_layout.glsl - buffers and push constants of the splat
// shaders (splat_clear, splat_draw, splat_resolve); host side:
// mlodvk_splat in manylods_vk.h.  Each atlas pixel holds a key of two words
// while drawing: the node's index, then the depth as an order-preserving
// 32-bit pattern (as a uint64: the depth above the node).  The least key
// wins: the nearest depth and, among equal depths, the lower node index
// (as mlod_splat: mlod__wins), whatever order the draws come in.
// splat_draw keeps it with one 64-bit atomicMin where the device's
// doubles are used (those devices have shaderInt64 and 64-bit buffer
// atomics: manylods_vk.h, DOUBLES), and with 32-bit atomics in two passes
// with emulated doubles (MLOD_F64_EMULATED): the nearest depth, then the
// least node at that depth.  splat_resolve turns keys into depth, normal
// and colour.  The includer may declare the keys' element type first
// (MLOD_SPLAT_KEY: uint, two a pixel, unless splat_draw's one 64-bit word).
#ifndef MLOD_SPLAT_KEY
#define MLOD_SPLAT_KEY uint
#endif

#include "interface.h"

layout(std430, set = 0, binding = MLOD_IF_SPLAT_SPHERES) readonly buffer tree_spheres { vec4 spheres[]; };
layout(std430, set = 0, binding = MLOD_IF_SPLAT_CONES) readonly buffer tree_cones { vec4 cones[]; };
layout(std430, set = 0, binding = MLOD_IF_SPLAT_VIEWS) readonly buffer view_frames { uvec2 views[]; }; // doubles, as their bits (real.glsl: r_load)
layout(std430, set = 0, binding = MLOD_IF_SPLAT_LIST) readonly buffer cut_list { uvec2 list[]; };
layout(std430, set = 0, binding = MLOD_IF_SPLAT_STATUS) readonly buffer cut_status { uint status[]; };
layout(std430, set = 0, binding = MLOD_IF_SPLAT_COLORS) readonly buffer tree_colors { float colors[]; };
layout(std430, set = 0, binding = MLOD_IF_SPLAT_TILES) readonly buffer atlas_tiles { uint tiles[]; };
layout(std430, set = 0, binding = MLOD_IF_SPLAT_KEYS) buffer atlas_keys { MLOD_SPLAT_KEY keys[]; };
layout(std430, set = 0, binding = MLOD_IF_SPLAT_DEPTH) writeonly buffer atlas_depth { float depth_out[]; };
layout(std430, set = 0, binding = MLOD_IF_SPLAT_NORMAL) writeonly buffer atlas_normal { float normal_out[]; };
layout(std430, set = 0, binding = MLOD_IF_SPLAT_COLOR) writeonly buffer atlas_color { float color_out[]; };
layout(std430, set = 0, binding = MLOD_IF_SPLAT_CONTROL) readonly buffer control_block { MLOD_IF_CONTROL(MLOD_IF_DECLARE, MLOD_IF_DECLARE_ARRAY) } ctl;

layout(push_constant) uniform push_block { MLOD_IF_SPLAT_PUSH(MLOD_IF_DECLARE) } pc;

uint group_index() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

#define EMPTY_WORD 0xffffffffu // both words of an empty pixel's key
