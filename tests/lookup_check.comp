#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_vote : require
// tests/lookup_check.comp - shaders/lookup.glsl on a Vulkan device, for
// tests/test_lookup_vulkan.c (compiled there, with and without
// -DMLOD_F64_EMULATED): one invocation per query, which runs
// mlod_atlas_lookup and mlod_atlas_shadow and writes their results as bits.
// A query is three uvec4:
//   the point (x, y, z as float bits), the view whose frame it reads
//   the normal (float bits), has_normal
//   the index of the tile it passes (another view's: a tile of another
//   size), then mlod_shadow_params (filter, bias and slope_bias bits)
// and its results five uvec4:
//   lookup's return value, pixel x, pixel y, depth (float bits)
//   map_depth, the shadow's lit fraction (float bits), 0, 0
// then the doubles within (bits, low word first), which the floats above
// round away but for a rare ulp, for the twins' own comparison:
//   frame_project's return value, its sub-projection, x
//   y, depth
//   lookup_footprint's at (x, y) where the point lies in the frame's tile
//   (else 0), that condition, 0
// (with the device's doubles only: with emulated ones, zeros.  A second
// frame_project and footprint would add half again to the time lavapipe
// takes to compile the module, and the source they run is the same: the
// native form checks it, and tests/test_f64_vulkan.c that f64.glsl gives
// the same bits as the device's doubles.)
layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) readonly buffer frame_buffer { uvec2 views[]; };
layout(std430, set = 0, binding = 1) readonly buffer depth_buffer { float atlas_depth[]; };
layout(std430, set = 0, binding = 2) readonly buffer tile_buffer { uvec4 tiles[]; };
layout(std430, set = 0, binding = 3) readonly buffer query_buffer { uvec4 queries[]; };
layout(std430, set = 0, binding = 4) writeonly buffer result_buffer { uvec4 results[]; };
layout(push_constant) uniform push_block {
    uint count;
    uint atlas_width;
} pc;

#include "lookup.glsl"

void main()
{
    uint q = gl_GlobalInvocationID.x;
    if (q >= pc.count) return;
    uvec4 a = queries[3u * q], b = queries[3u * q + 1u], c = queries[3u * q + 2u];
    vec3 point = uintBitsToFloat(a.xyz), normal = uintBitsToFloat(b.xyz);
    uvec4 tile = tiles[c.x];
    vec2 pixel;
    float depth, map_depth;
    bool inside = mlod_atlas_lookup(a.w, tile, pc.atlas_width, point, pixel, depth, map_depth);
    mlod_shadow_params params = mlod_shadow_params(c.y, uintBitsToFloat(c.z), uintBitsToFloat(c.w));
    float lit = mlod_atlas_shadow(a.w, tile, pc.atlas_width, point, b.w != 0u, normal, params);
    results[5u * q] = uvec4(inside ? 1u : 0u, floatBitsToUint(pixel), floatBitsToUint(depth));
    results[5u * q + 1u] = uvec4(floatBitsToUint(map_depth), floatBitsToUint(lit), 0u, 0u);

#ifdef MLOD_F64_EMULATED
    results[5u * q + 2u] = uvec4(0u);
    results[5u * q + 3u] = uvec4(0u);
    results[5u * q + 4u] = uvec4(0u);
#else
    uint s;
    real x, y, z, fp = R_ZERO;
    int projected = frame_project(a.w, point, s, x, y, z);
    bool in_tile = projected == 1 && r_ge(x, R_ZERO) && r_lt(x, vd(a.w, MLOD_IF_V_WIDTH)) && r_ge(y, R_ZERO) &&
                   r_lt(y, vd(a.w, MLOD_IF_V_HEIGHT));
    if (in_tile) {
        uint sub = sub_base(a.w, s);
        fp = lookup_footprint(sub, lookup_sub_pixels(sub), r3_sub(r3_f(point), vd3(a.w, MLOD_IF_V_EYE)), x, y);
    }
    results[5u * q + 2u] = uvec4(uint(projected), s, r_bits(x));
    results[5u * q + 3u] = uvec4(r_bits(y), r_bits(z));
    results[5u * q + 4u] = uvec4(r_bits(fp), in_tile ? 1u : 0u, 0u);
#endif
}
