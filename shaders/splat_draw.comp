#version 450
// shaders/splat_draw.comp - one thread per cut entry (ctl.current, args[2]):
// a drawn entry (status DRAWN, OVERSIZE or COARSE) becomes the disc around
// its sphere's image, its radius times pc.disc_scale, in each sub-tile of its
// view that it reaches, as
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

// Clipped to the sub-tile of the view's sub-projection s (whole pixels:
// columns floor(x) .. floor(x + width) - 1, rows likewise).
void raster_disc(uint view, uint s, dvec4 disc, uint64_t entry)
{
    uint sub = sub_base(view, s);
    precise double sub_right = sd(sub, MLOD_IF_S_X) + sd(sub, MLOD_IF_S_WIDTH);
    precise double sub_bottom = sd(sub, MLOD_IF_S_Y) + sd(sub, MLOD_IF_S_HEIGHT);
    uint col_begin = uint(sd(sub, MLOD_IF_S_X)), col_end = uint(sub_right);
    uint row_begin = uint(sd(sub, MLOD_IF_S_Y)), row_end = uint(sub_bottom);
    double tile_h = double(tiles[4u * view + 3u]);
    precise double radius = disc.z * double(pc.disc_scale);
    precise double r2 = radius * radius;
    if (!(disc.z < 1e9LF) || isinf(disc.x) || isnan(disc.x) || isinf(disc.y) || isnan(disc.y)) return;
    uint64_t key = (uint64_t(ordered_bits(float(disc.w))) << 32) | entry;
    precise double y0 = floor(disc.y - radius), y1 = ceil(disc.y + radius);
    precise double x0 = floor(disc.x - radius), x1 = ceil(disc.x + radius);
    uint rb = y0 < double(row_begin) ? row_begin : (y0 >= double(row_end) ? row_end : uint(y0));
    uint re = y1 > double(row_end) ? row_end : (y1 <= double(row_begin) ? row_begin : uint(y1));
    uint cb = x0 < double(col_begin) ? col_begin : (x0 >= double(col_end) ? col_end : uint(x0));
    uint ce = x1 > double(col_end) ? col_end : (x1 <= double(col_begin) ? col_begin : uint(x1));
    // the band of mlod_splat's tasks that holds the disc's centre
    bool centre_inside = disc.x >= double(col_begin) && disc.x < double(col_end) && disc.y >= double(row_begin) &&
                         disc.y < double(row_end);
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
    dvec3 c = dvec3(s.xyz);
    dvec4 disc;
    uint reached = count == 1u ? 1u : reached_subs(view, s);
    for (uint k = 0u; k < count; k++)
        if (((reached >> k) & 1u) != 0u && image_disc(view, k, c, double(s.w), disc)) raster_disc(view, k, disc, uint64_t(i));
}
