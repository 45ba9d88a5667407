// shaders/mv_layout.glsl - buffers and push constants of the MegaViews
// shaders (mv_pairs, mv_slots, mv_inherit, mv_draw, mv_resolve); host side:
// mlodvk_megaviews_render in manylods_vk.h, which runs
// mlod_megaviews_render's traversal level by level of the view tree:
//
//   mv_pairs    rounds over the level's pairs (view node, scene node): each
//               pair's action (common.glsl: pair_action); a split scene node
//               gives the round's output two pairs, a split view node the
//               next level two, a draw the level's draw list
//   mv_slots    a map slot for every node of the level that is a view leaf,
//               drew something, or whose parent has a map
//   mv_inherit  each slot's pixels from the parent's map, their depths
//               measured again from this node's centre (with tangent
//               discs along the pixel's ray: common.glsl's remeasure; else
//               empty)
//   mv_draw     the draws' discs (or tangent discs), as mlod__draw_nodes
//               draws them, into their node's slot, in three passes of
//               32-bit atomics
//   mv_resolve  the view leaves' slots into their tiles of the atlas
//
// A map pixel is three words (MLOD_IF_MV_WORDS): the depth as a pattern
// whose unsigned order is the depth's, the least scene node at that depth
// (`who`; MLOD_IF_MV_NONE: none yet), and the node.  As on the CPU
// (mlod__wins), a pixel holds the least (depth, node) of the node
// inherited from the parent's map and the draws, whatever their order.
// Pass 0 keeps the nearest depth, and a draw that finds a farther one sets
// `who` to none (the inherited node then no longer holds the nearest
// depth), pass 1 the least node at it (the inherited node's index among
// them), pass 2 writes the winner's node.
#include "interface.h"

layout(std430, set = 0, binding = MLOD_IF_MV_SCENE_SPHERES) readonly buffer tree_spheres { vec4 spheres[]; };
layout(std430, set = 0, binding = MLOD_IF_MV_SCENE_CONES) readonly buffer tree_cones { vec4 cones[]; };
layout(std430, set = 0, binding = MLOD_IF_MV_SCENE_COLORS) readonly buffer tree_colors { float colors[]; };
layout(std430, set = 0, binding = MLOD_IF_MV_EYE_SPHERES) readonly buffer eye_tree_spheres { vec4 eye_spheres[]; };
layout(std430, set = 0, binding = MLOD_IF_MV_EYE_CONES) readonly buffer eye_tree_cones { vec4 eye_cones[]; };
layout(std430, set = 0, binding = MLOD_IF_MV_FRAMES) readonly buffer view_frames { uvec2 views[]; }; // doubles, as their bits
layout(std430, set = 0, binding = MLOD_IF_MV_PAIRS_IN) readonly buffer pairs_in_buffer { uvec2 pairs_in[]; };
layout(std430, set = 0, binding = MLOD_IF_MV_PAIRS_OUT) writeonly buffer pairs_out_buffer { uvec2 pairs_out[]; };
layout(std430, set = 0, binding = MLOD_IF_MV_LISTS) buffer lists_buffer { uvec2 lists[]; };
layout(std430, set = 0, binding = MLOD_IF_MV_LEVEL) buffer level_buffer { uint level[]; };
layout(std430, set = 0, binding = MLOD_IF_MV_MAPS) buffer maps_buffer { uint maps[]; };
layout(std430, set = 0, binding = MLOD_IF_MV_PREV_MAPS) readonly buffer prev_maps_buffer { uint prev_maps[]; };
layout(std430, set = 0, binding = MLOD_IF_MV_CONTROL) buffer control_block { MLOD_IF_MV_CONTROL_BLOCK(MLOD_IF_DECLARE) } ctl;
layout(std430, set = 0, binding = MLOD_IF_MV_DEPTH) writeonly buffer atlas_depth { float depth_out[]; };
layout(std430, set = 0, binding = MLOD_IF_MV_NORMAL) writeonly buffer atlas_normal { float normal_out[]; };
layout(std430, set = 0, binding = MLOD_IF_MV_COLOR) writeonly buffer atlas_color { float color_out[]; };

layout(push_constant) uniform push_block { MLOD_IF_MV_PUSH(MLOD_IF_DECLARE) } pc;

uint group_index() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

#define MLOD_HAS_CONES (ctl.has_cones != 0u)
#define MLOD_MEGAVIEWS
#include "common.glsl"

// A depth as a 32-bit pattern whose unsigned order is the depth's.
uint mv_ordered(float depth)
{
    uint bits = floatBitsToUint(depth + 0.0);
    return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}
