#version 450
// shaders/mv_draw.comp - one thread per draw of the level (pc.items; lists
// from ctl.next_capacity): the disc around the scene node's image in each
// half of the view node's map that the node reaches (frame 0 at the view
// node's centre: common.glsl's image_disc), rastered as
// mlod__raster_disc rasters it into a band of the whole map: pixels whose
// centre lies in the disc (radius times ctl.disc_scale), at its centre's
// depth, or, at disc scale 1 when none does, the pixel holding the disc's
// centre; with ctl.tangent (tangent discs) those pixels whose centre's ray
// meets the node's tangent disc, at that point's depth (common.glsl:
// tangent_hit; a node whose cone has no axis: all of them, at its
// centre's depth), and no fallback pixel.  Pass pc.pass of three
// (mv_layout.glsl): the nearest depth, a draw nearer than what it finds
// taking the pixel from the inherited node (`who` that node after
// mv_inherit); the least node at that depth, the inherited one among
// them (mlod__wins); the node whose `who` won.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_EXT_control_flow_attributes : require
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "mv_layout.glsl"

void plot(uint slot, uint row, uint col, uint depth_bits, uint who, uint node)
{
    uint at = MLOD_IF_MV_WORDS * (slot * ctl.pixels + row * 2u * ctl.resolution + col);
    if (pc.pass == 0u) {
        // the inherited node keeps a pixel whose nearest depth is still its own: a nearer draw takes it
        if (atomicMin(maps[at], depth_bits) > depth_bits) maps[at + 1u] = MLOD_IF_MV_NONE;
    } else if (maps[at] == depth_bits) {
        if (pc.pass == 1u)
            atomicMin(maps[at + 1u], who);
        else if (maps[at + 1u] == who)
            maps[at + 2u] = node;
    }
}

void raster(uint slot, uint k, vec4 sphere, real4 disc, uint node, uint who)
{
    uint sub = sub_base(0u, k);
    uint col_begin = r_to_u(sd(sub, MLOD_IF_S_X)), col_end = r_to_u(r_add(sd(sub, MLOD_IF_S_X), sd(sub, MLOD_IF_S_WIDTH)));
    uint row_begin = r_to_u(sd(sub, MLOD_IF_S_Y)), row_end = r_to_u(r_add(sd(sub, MLOD_IF_S_Y), sd(sub, MLOD_IF_S_HEIGHT)));
    if (row_end > ctl.resolution) row_end = ctl.resolution;
    real radius = r_mul(disc.z, r_f(ctl.disc_scale));
    real r2 = r_mul(radius, radius);
    if (!r_lt(disc.z, RK(0x41CDCD65u, 0x00000000u, 1e9LF)) || r_isinf(disc.x) || r_isnan(disc.x) || r_isinf(disc.y) ||
        r_isnan(disc.y))
        return;
    if (row_begin >= row_end) return;
    uint depth_bits = mv_ordered(r_to_f(disc.w));
    real y0 = r_floor(r_sub(disc.y, radius)), y1 = r_ceil(r_add(disc.y, radius));
    real x0 = r_floor(r_sub(disc.x, radius)), x1 = r_ceil(r_add(disc.x, radius));
    real rb_ = r_u(row_begin), re_ = r_u(row_end), cb_ = r_u(col_begin), ce_ = r_u(col_end);
    uint rb = r_lt(y0, rb_) ? row_begin : (r_ge(y0, re_) ? row_end : r_to_u(y0));
    uint re = r_gt(y1, re_) ? row_end : (r_le(y1, rb_) ? row_begin : r_to_u(y1));
    uint cb = r_lt(x0, cb_) ? col_begin : (r_ge(x0, ce_) ? col_end : r_to_u(x0));
    uint ce = r_gt(x1, ce_) ? col_end : (r_le(x1, cb_) ? col_begin : r_to_u(x1));
    bool hit = false, tangent = ctl.tangent != 0u, plane = tangent && has_plane(cones[node]);
    // the pixels whose centre lies in the disc; then, at disc scale 1 when none does (not with tangent
    // discs), once more over the pixel holding the disc's centre, taken whole: one place that plots
    // (emulated doubles inline each operation where it is written)
    bool fallback = false;
    [[dont_unroll]] for (int attempt = 0; attempt < 2; attempt++) {
        if (attempt == 1) {
            if (hit || tangent ||
                !(ctl.disc_scale >= 1.0 && r_ge(disc.x, cb_) && r_lt(disc.x, ce_) && r_ge(disc.y, rb_) &&
                  r_lt(disc.y, re_)))
                break;
            fallback = true;
            rb = r_to_u(r_floor(disc.y));
            re = rb + 1u;
            cb = r_to_u(r_floor(disc.x));
            ce = cb + 1u;
        }
        for (uint row = rb; row < re; row++) {
            real dy = r_sub(r_add(r_u(row), R_HALF), disc.y);
            for (uint col = cb; col < ce; col++) {
                real dx = r_sub(r_add(r_u(col), R_HALF), disc.x);
                float at = 0.0;
                if (!fallback && (!r_le(r_add(r_mul(dx, dx), r_mul(dy, dy)), r2) ||
                                  (plane && !tangent_hit(0u, k, sphere, cones[node], ctl.disc_scale, col, row, at))))
                    continue;
                plot(slot, row, col, plane ? mv_ordered(at) : depth_bits, who, node);
                hit = true;
            }
        }
    }
}

void main()
{
    uint i = group_index() * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    if (i >= pc.items) return;
    uvec2 e = lists[ctl.next_capacity + i];
    uint v = e.x, s = e.y, slot = level[ctl.off_slots + v - ctl.first];
    uint who = s; // equal depths: the lower node index wins
    vec4 sphere = spheres[s];
    real3 c = r3_f(sphere.xyz);
    real4 disc;
    mv_eye = r3_f(eye_spheres[v].xyz);
    uint reached = reached_subs(0u, sphere);
    [[dont_unroll]] for (uint k = 0u; k < 2u; k++)
        if (((reached >> k) & 1u) != 0u && image_disc(0u, k, c, r_f(sphere.w), disc)) raster(slot, k, sphere, disc, s, who);
}
