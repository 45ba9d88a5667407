#version 450
// shaders/splat_draw.comp - one thread per cut entry (ctl.current, args[2]):
// a drawn entry (status DRAWN, OVERSIZE or COARSE) becomes the disc around
// its sphere's image, its radius times pc.disc_scale, in its view's tile, as
// mlod__draw_nodes and mlod__raster_disc in manylods.h: pixels whose centre
// lies in the disc, or, at disc_scale 1, when none of the 64-row band
// holding the disc's centre does, the pixel holding the centre.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_EXT_control_flow_attributes : require
#include "interface.h"
layout(local_size_x = MLOD_IF_GROUP) in;
#include "splat_layout.glsl"
#define MLOD_HAS_CONES (pc.has_cones != 0u)
#include "common.glsl"

#define BAND_ROWS 64.0LF

// A depth as a 32-bit pattern whose unsigned order is the depth's order.
uint ordered_bits(float depth)
{
    uint bits = floatBitsToUint(depth + 0.0);
    return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}

void plot(uint view, uint row, uint col, uint64_t key)
{
    uint x = tiles[4u * view] + col, y = tiles[4u * view + 1u] + row;
    atomicMin(keys[y * pc.atlas_width + x], key);
}

void raster_disc(uint view, dvec4 disc, uint64_t entry, uint col_begin, uint col_end)
{
    double tile_h = double(tiles[4u * view + 3u]);
    precise double radius = disc.z * double(pc.disc_scale);
    precise double r2 = radius * radius;
    if (!(disc.z < 1e9LF) || isinf(disc.x) || isnan(disc.x) || isinf(disc.y) || isnan(disc.y)) return;
    uint64_t key = (uint64_t(ordered_bits(float(disc.w))) << 32) | entry;
    precise double y0 = floor(disc.y - radius), y1 = ceil(disc.y + radius);
    precise double x0 = floor(disc.x - radius), x1 = ceil(disc.x + radius);
    uint rb = y0 < 0.0LF ? 0u : (y0 >= tile_h ? uint(tile_h) : uint(y0));
    uint re = y1 > tile_h ? uint(tile_h) : (y1 <= 0.0LF ? 0u : uint(y1));
    uint cb = x0 < double(col_begin) ? col_begin : (x0 >= double(col_end) ? col_end : uint(x0));
    uint ce = x1 > double(col_end) ? col_end : (x1 <= double(col_begin) ? col_begin : uint(x1));
    // the band of mlod_splat's tasks that holds the disc's centre
    bool centre_inside = disc.x >= double(col_begin) && disc.x < double(col_end) && disc.y >= 0.0LF && disc.y < tile_h;
    double band_begin = centre_inside ? floor(disc.y / BAND_ROWS) * BAND_ROWS : 0.0LF;
    double band_end = min(band_begin + BAND_ROWS, tile_h);
    bool hit_in_band = false;
    for (uint row = rb; row < re; row++) {
        precise double dy = double(row) + 0.5LF - disc.y;
        for (uint col = cb; col < ce; col++) {
            precise double dx = double(col) + 0.5LF - disc.x;
            if (dx * dx + dy * dy <= r2) {
                plot(view, row, col, key);
                if (double(row) >= band_begin && double(row) < band_end) hit_in_band = true;
            }
        }
    }
    if (!hit_in_band && centre_inside && pc.disc_scale >= 1.0) plot(view, uint(floor(disc.y)), uint(floor(disc.x)), key);
}

void main()
{
    uint i = group_index() * MLOD_IF_GROUP + gl_LocalInvocationID.x;
    if (i >= ctl.current) return;
    uvec2 e = list[i];
    if (status[i] == MLOD_IF_STATUS_CULLED) return;
    uint view = e.y, node = e.x, tile_w = tiles[4u * view + 2u];
    vec4 s = spheres[node];
    dvec3 c = dvec3(s.xyz);
    dvec4 disc;
    if (view_kind(view) != MLOD_IF_KIND_DUAL_PARABOLOID) {
        if (image_disc(view, c, double(s.w), 0u, disc)) raster_disc(view, disc, uint64_t(i), 0u, tile_w);
        return;
    }
    uint w = tile_w / 2u;
    for (uint half_index = 0u; half_index < 2u; half_index++) {
        if (plane_outside(view * MLOD_IF_VIEW_STRIDE + MLOD_IF_V_HALVES + 5u * half_index, s)) continue;
        if (image_disc(view, c, double(s.w), half_index, disc))
            raster_disc(view, disc, uint64_t(i), half_index != 0u ? w : 0u, half_index != 0u ? tile_w : w);
    }
}
