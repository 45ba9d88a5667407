#version 450
// shaders/splat_draw.comp - one thread per cut entry (ctl.current, args[2]):
// a drawn entry (status DRAWN, OVERSIZE or COARSE) becomes the disc around
// its sphere's image, its radius times pc.disc_scale, in each sub-tile of its
// view that it reaches, as
// mlod__draw_nodes and mlod__raster_disc in manylods.h: pixels whose centre
// lies in the disc, at its centre's depth, or, at disc_scale 1, when none
// of the 64-row band holding the disc's centre does, the pixel holding the
// centre (MLOD_SPLAT_SPHERES); with pc.tangent (MLOD_SPLAT_TANGENT) those
// pixels whose centre's ray meets the node's tangent disc, at that point's
// depth (common.glsl: tangent_hit; a node whose cone has no axis: all of
// them, at its centre's depth), and no fallback pixel.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_EXT_control_flow_attributes : require
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#ifndef MLOD_F64_EMULATED
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#define MLOD_SPLAT_KEY uint64_t
#endif
#include "splat_layout.glsl"
#define MLOD_HAS_CONES (pc.has_cones != 0u)
#include "common.glsl"

#define BAND_ROWS RK(0x40500000u, 0x00000000u, 64.0LF)

// A depth as a 32-bit pattern whose unsigned order is the depth's order.
uint ordered_bits(float depth)
{
    uint bits = floatBitsToUint(depth + 0.0);
    return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}

// The least key (splat_layout.glsl): one 64-bit atomicMin, or with
// emulated doubles pass 0 the nearest depth, pass 1 the least node at it
// (mlod__wins in manylods.h).
void plot(uint view, uint row, uint col, uint depth_bits, uint node)
{
    uint x = tiles[4u * view] + col, y = tiles[4u * view + 1u] + row, p = y * pc.atlas_width + x;
#ifdef MLOD_F64_EMULATED
    if (pc.pass == 0u)
        atomicMin(keys[2u * p + 1u], depth_bits);
    else if (keys[2u * p + 1u] == depth_bits)
        atomicMin(keys[2u * p], node);
#else
    atomicMin(keys[p], (uint64_t(depth_bits) << 32) | uint64_t(node));
#endif
}

// Clipped to the sub-tile of the view's sub-projection s (whole pixels:
// columns floor(x) .. floor(x + width) - 1, rows likewise).
void raster_disc(uint view, uint s, real4 disc, uint node)
{
    uint sub = sub_base(view, s);
    real sub_right = r_add(sd(sub, MLOD_IF_S_X), sd(sub, MLOD_IF_S_WIDTH));
    real sub_bottom = r_add(sd(sub, MLOD_IF_S_Y), sd(sub, MLOD_IF_S_HEIGHT));
    uint col_begin = r_to_u(sd(sub, MLOD_IF_S_X)), col_end = r_to_u(sub_right);
    uint row_begin = r_to_u(sd(sub, MLOD_IF_S_Y)), row_end = r_to_u(sub_bottom);
    real tile_h = r_u(tiles[4u * view + 3u]);
    real radius = r_mul(disc.z, r_f(pc.disc_scale));
    real r2 = r_mul(radius, radius);
    if (!r_lt(disc.z, RK(0x41CDCD65u, 0x00000000u, 1e9LF)) || r_isinf(disc.x) || r_isnan(disc.x) || r_isinf(disc.y) ||
        r_isnan(disc.y))
        return;
    uint depth_bits = ordered_bits(r_to_f(disc.w));
    real y0 = r_floor(r_sub(disc.y, radius)), y1 = r_ceil(r_add(disc.y, radius));
    real x0 = r_floor(r_sub(disc.x, radius)), x1 = r_ceil(r_add(disc.x, radius));
    real rb_ = r_u(row_begin), re_ = r_u(row_end), cb_ = r_u(col_begin), ce_ = r_u(col_end);
    uint rb = r_lt(y0, rb_) ? row_begin : (r_ge(y0, re_) ? row_end : r_to_u(y0));
    uint re = r_gt(y1, re_) ? row_end : (r_le(y1, rb_) ? row_begin : r_to_u(y1));
    uint cb = r_lt(x0, cb_) ? col_begin : (r_ge(x0, ce_) ? col_end : r_to_u(x0));
    uint ce = r_gt(x1, ce_) ? col_end : (r_le(x1, cb_) ? col_begin : r_to_u(x1));
    // the band of mlod_splat's tasks that holds the disc's centre
    bool centre_inside = r_ge(disc.x, cb_) && r_lt(disc.x, ce_) && r_ge(disc.y, rb_) && r_lt(disc.y, re_);
    real band_begin = centre_inside ? r_mul(r_floor(r_div(disc.y, BAND_ROWS)), BAND_ROWS) : R_ZERO;
    real band_top = r_add(band_begin, BAND_ROWS);
    real band_end = r_lt(tile_h, band_top) ? tile_h : band_top; // GLSL's min
    bool hit_in_band = false, plane = pc.tangent != 0u && has_plane(cones[node]);
    for (uint row = rb; row < re; row++) {
        real dy = r_sub(r_add(r_u(row), R_HALF), disc.y);
        for (uint col = cb; col < ce; col++) {
            real dx = r_sub(r_add(r_u(col), R_HALF), disc.x);
            float at = 0.0;
            if (!r_le(r_add(r_mul(dx, dx), r_mul(dy, dy)), r2) ||
                (plane && !tangent_hit(view, s, spheres[node], cones[node], pc.disc_scale, col, row, at)))
                continue;
            plot(view, row, col, plane ? ordered_bits(at) : depth_bits, node);
            if (r_ge(r_u(row), band_begin) && r_lt(r_u(row), band_end)) hit_in_band = true;
        }
    }
    if (pc.tangent == 0u && !hit_in_band && centre_inside && pc.disc_scale >= 1.0)
        plot(view, r_to_u(r_floor(disc.y)), r_to_u(r_floor(disc.x)), depth_bits, node);
}

// As mlod__draw_nodes: in every sub-projection the sphere reaches (a view
// of one sub-projection: its drawn entries all reach it).
void main()
{
    uint i = group_index() * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    if (i >= ctl.current) return;
    uvec2 e = list[i];
    if (status[i] == MLOD_IF_STATUS_CULLED) return;
    uint view = e.y, node = e.x, count = sub_count(view);
    vec4 s = spheres[node];
    real3 c = r3_f(s.xyz);
    real4 disc;
    uint reached = count == 1u ? 1u : reached_subs(view, s);
    for (uint k = 0u; k < count; k++)
        if (((reached >> k) & 1u) != 0u && image_disc(view, k, c, r_f(s.w), disc)) raster_disc(view, k, disc, node);
}
