#version 450
// shaders/mv_resolve.comp - pass 0: one thread per pixel of the level's
// slots (pc.items = slots x pixels): a view leaf's slot into its view's
// tile of the atlas: depth (+inf where nothing was drawn), and where the
// atlas has them the node's normal (its cone's axis) and colour (0 where
// nothing was drawn), as mlod__band_set writes them.  Pass 1: every atlas
// pixel (pc.items) empty, as mlod_atlas_create leaves the pixels outside
// the tiles.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_EXT_control_flow_attributes : require
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "mv_layout.glsl"

// An empty atlas pixel: +inf, normal and colour 0.
void empty_pixel(uint out_at)
{
    depth_out[out_at] = uintBitsToFloat(0x7f800000u);
    if (ctl.want_normal != 0u) normal_out[3u * out_at] = normal_out[3u * out_at + 1u] = normal_out[3u * out_at + 2u] = 0.0;
    if (ctl.want_color != 0u) color_out[3u * out_at] = color_out[3u * out_at + 1u] = color_out[3u * out_at + 2u] = 0.0;
}

void main()
{
    uint i = group_index() * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    if (i >= pc.items) return;
    if (pc.pass == 1u) { // the whole atlas, before the first level: pixels outside every tile stay so
        empty_pixel(i);
        return;
    }
    uint slot = i / ctl.pixels, p = i - slot * ctl.pixels, v = level[ctl.off_slot_nodes + slot];
    if (v < ctl.eye_leaves - 1u) return;
    uint view = level[ctl.off_sources + v - (ctl.eye_leaves - 1u)], width = 2u * ctl.resolution;
    uint row = p / width, col = p - row * width;
    uint x = level[ctl.off_tiles + 4u * view] + col, y = level[ctl.off_tiles + 4u * view + 1u] + row;
    uint out_at = y * ctl.atlas_width + x, at = MLOD_IF_MV_WORDS * i, ordered = maps[at], node = maps[at + 2u];
    if (ordered == MLOD_IF_MV_NONE) {
        empty_pixel(out_at);
        return;
    }
    depth_out[out_at] = uintBitsToFloat((ordered & 0x80000000u) != 0u ? ordered & 0x7fffffffu : ~ordered);
    if (ctl.want_normal != 0u) {
        normal_out[3u * out_at] = cones[node].x;
        normal_out[3u * out_at + 1u] = cones[node].y;
        normal_out[3u * out_at + 2u] = cones[node].z;
    }
    if (ctl.want_color != 0u) {
        color_out[3u * out_at] = colors[3u * node];
        color_out[3u * out_at + 1u] = colors[3u * node + 1u];
        color_out[3u * out_at + 2u] = colors[3u * node + 2u];
    }
}
