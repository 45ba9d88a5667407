// shaders/lookup.glsl - the shadow lookups of manylods.h (mlod_atlas_lookup,
// mlod_atlas_shadow) for your own shaders: the same bits as the CPU.
//
// Each function here is the twin of the C function its "C twin:" line
// names in manylods.h, which names it back ("GLSL twin:"), in the same
// order (tests/check_twins.sh), operation for operation in double precision
// through real.glsl, as shaders/common.glsl is (whose centre_ray,
// plane_outside, dot3 and length_d it uses): the device's own doubles, or
// with MLOD_F64_EMULATED doubles from 32-bit integers (f64.glsl).  On a
// device whose doubles are IEEE (lavapipe, most desktop GPUs), or with
// emulated doubles on any device, mlod_atlas_lookup and mlod_atlas_shadow
// below return what the C functions return for the same atlas, frame,
// point, normal and params, bit for bit (tests/test_lookup_vulkan.c checks
// both forms on lavapipe).
//
// USE
//   #version 450
//   #extension GL_GOOGLE_include_directive : require
//   #extension GL_EXT_control_flow_attributes : require
//   #extension GL_KHR_shader_subgroup_vote : require   (or #define MLOD_NO_SUBGROUPS:
//                                                       a fragment shader on a device
//                                                       without subgroups there)
//   layout(std430, binding = 0) readonly buffer frames { uvec2 views[]; };
//   layout(std430, binding = 1) readonly buffer depths { float atlas_depth[]; };
//   #include "lookup.glsl"
// compiled with -I path/to/manylods/shaders, and -DMLOD_F64_EMULATED for a
// device without shaderFloat64 (the native form needs shaderFloat64 enabled
// on the VkDevice; the emulated one no 64-bit type at all).
//
// The includer declares, before including this file:
//   uvec2 views[]   the views' frames: MLOD_IF_VIEW_STRIDE (296) doubles per
//                   view, an mlod_view_frame (mlod_view_frame_of) as it is,
//                   its doubles as their bits (interface.h); view v's frame
//                   at v * 296.  manylods_vk.h's cut holds its views' frames
//                   so (mlodvk_cut_get_buffers: views), or upload your own.
//   the atlas depth: float atlas_depth[] (row by row, atlas width floats a
//                   row: mlodvk_atlas_get_buffers: depth, or mlod_atlas's
//                   depth uploaded), or a macro MLOD_ATLAS_DEPTH(i) that
//                   reads pixel i (any source: a texel fetch).
// The functions take the view's tile (mlod_atlas.tiles[4 v .. 4 v + 3]: x,
// y, width, height) and the atlas width, where the C functions read the
// atlas.  This file includes interface.h and common.glsl (which brings
// real.glsl and its names: real, r_*, dot3, ...), with MLOD_NO_TREE: do not
// include common.glsl again.
//
// What the C functions check and these cannot: the view is below the
// atlas's view count (pass a view whose frame views[] holds), and
// pointers (a NULL normal is has_normal = false).  The tile's size is
// checked against the frame's as in C (0 and NaN otherwise), and params as
// in C (NaN for a filter above MLOD_SHADOW_MAX_FILTER or a bias or slope
// bias that is negative or not finite).

#include "interface.h"
#ifndef MLOD_NO_TREE
#define MLOD_NO_TREE
#endif
#include "common.glsl"

#ifndef MLOD_ATLAS_DEPTH
#define MLOD_ATLAS_DEPTH(i) atlas_depth[i]
#endif

// manylods.h's MLOD_SHADOW_MAX_FILTER and MLOD_SHADOW_MAX_SLOPE
#define MLOD_SHADOW_MAX_FILTER 16u
#define MLOD_SHADOW_MAX_SLOPE RK(0x40200000u, 0x00000000u, 8.0LF)

// mlod_shadow_params, with the same std430 layout as the C struct (12
// bytes: an array of them uploads as it is); filter_width is C's filter
// (a word GLSL reserves).
struct mlod_shadow_params {
    uint filter_width;
    float bias;
    float slope_bias;
};

// C twin: mlod__frame_project
// Where world point `point` lands in view `view`: in the sub-projection
// whose axis is closest to its direction, its index s, the tile position
// (x, y) and depth.  1 when a sub-projection's planes reach the point, 0
// when none does; -1 where the projection is undefined (at the eye, or
// behind a perspective or paraboloid sub-projection).
int frame_project(uint view, vec3 point, out uint s, out real x, out real y, out real depth)
{
    real3 e = r3_sub(r3_f(point), vd3(view, MLOD_IF_V_EYE));
    real best = R_ZERO;
    uint subs = sub_count(view), found = 0u;
    s = 0u;
    x = R_ZERO;
    y = R_ZERO;
    depth = R_ZERO;
    for (uint k = 0u; k < subs; k++) {
        real xw = dot3(e, sd3(sub_base(view, k), MLOD_IF_S_FORWARD));
        if (k == 0u || r_gt(xw, best)) {
            best = xw;
            found = k;
        }
    }
    uint v = sub_base(view, found);
    real3 u = sd3(v, MLOD_IF_S_RIGHT), up = sd3(v, MLOD_IF_S_UP), w = sd3(v, MLOD_IF_S_FORWARD);
    real left = sd(v, MLOD_IF_S_X), top = sd(v, MLOD_IF_S_Y);
    real width = sd(v, MLOD_IF_S_WIDTH), height = sd(v, MLOD_IF_S_HEIGHT);
    int kind = sub_kind(v);
    if (kind == MLOD_IF_KIND_ORTHOGRAPHIC) {
        x = r_add(r_add(left, r_mul(R_HALF, width)), r_mul(sd(v, MLOD_IF_S_SCALE_X), dot3(e, u)));
        y = r_sub(r_add(top, r_mul(R_HALF, height)), r_mul(sd(v, MLOD_IF_S_SCALE_Y), dot3(e, up)));
        depth = dot3(e, w);
    } else {
        real d = length_d(e);
        if (!r_gt(d, R_ZERO)) return -1;
        real a = r_div(dot3(e, u), d);
        real b = r_div(dot3(e, up), d);
        real cos_t = r_div(dot3(e, w), d);
        real sin_t = r_sqrt(r_add(r_mul(a, a), r_mul(b, b)));
        real dir_x = R_ZERO, dir_y = R_ZERO, hi;
        if (r_gt(sin_t, R_ZERO)) {
            dir_x = r_div(a, sin_t);
            dir_y = r_div(b, sin_t);
        }
        if (kind == MLOD_IF_KIND_PERSPECTIVE) {
            if (!r_gt(cos_t, R_ZERO)) return -1;
            hi = r_div(sin_t, cos_t);
            real reach = r_mul(r_mul(sd(v, MLOD_IF_S_SCALE), R_HALF), r_add(hi, hi));
            x = r_add(r_add(left, r_mul(R_HALF, width)), r_mul(reach, dir_x));
            y = r_add(r_add(top, r_mul(R_HALF, height)), r_mul(reach, r_neg(dir_y)));
            depth = dot3(e, w);
        } else {
            real one_cos = r_add(R_ONE, cos_t);
            if (!r_gt(one_cos, R_ZERO) || !(r_gt(sin_t, R_ZERO) || r_gt(cos_t, R_ZERO))) return -1;
            hi = r_div(sin_t, one_cos);
            real mean = r_mul(R_HALF, r_add(hi, hi));
            x = r_add(left, r_mul(r_mul(R_HALF, width), r_add(R_ONE, r_mul(mean, dir_x))));
            y = r_add(top, r_mul(r_mul(R_HALF, height), r_sub(R_ONE, r_mul(mean, dir_y))));
            depth = d;
        }
    }
    s = found;
    vec4 sphere = vec4(point, 0.0);
    for (uint k = 0u; k < subs; k++) {
        uint sub = sub_base(view, k), planes = r_to_u(sd(sub, MLOD_IF_S_PLANE_COUNT)), j;
        for (j = 0u; j < planes; j++)
            if (plane_outside(sub + MLOD_IF_S_PLANES + 5u * j, sphere)) break;
        if (j == planes) return 1;
    }
    return 0;
}

// C twin: mlod__lookup_tile
// Whether the tile (x, y, width, height) is the frame's size.
bool lookup_tile(uint view, uvec4 tile)
{
    return r_eq(r_u(tile.z), vd(view, MLOD_IF_V_WIDTH)) && r_eq(r_u(tile.w), vd(view, MLOD_IF_V_HEIGHT));
}

// C twin: mlod__lookup_depth
// The depth the tile holds at its pixel (i, j), clamped into the
// sub-tile's columns [c.x, c.y) and rows [c.z, c.w).
real lookup_depth(uvec4 tile, uint atlas_width, real i, real j, real4 c)
{
    if (r_lt(i, c.x)) i = c.x;
    if (r_gt(i, r_sub(c.y, R_ONE))) i = r_sub(c.y, R_ONE);
    if (r_lt(j, c.z)) j = c.z;
    if (r_gt(j, r_sub(c.w, R_ONE))) j = r_sub(c.w, R_ONE);
    return r_f(MLOD_ATLAS_DEPTH((tile.y + r_to_u(j)) * atlas_width + tile.x + r_to_u(i)));
}

// C twin: mlod__lookup_sub_pixels
// The pixels of the sub-projection at views[sub]: columns c.x .. c.y - 1,
// rows c.z .. c.w - 1.
real4 lookup_sub_pixels(uint sub)
{
    real left = sd(sub, MLOD_IF_S_X), top = sd(sub, MLOD_IF_S_Y);
    return real4(r_u(r_to_u(left)), r_u(r_to_u(r_add(left, sd(sub, MLOD_IF_S_WIDTH)))), r_u(r_to_u(top)),
                 r_u(r_to_u(r_add(top, sd(sub, MLOD_IF_S_HEIGHT)))));
}

// C twin: mlod_atlas_lookup
// Where world point `point` lands in view `view`'s tile (x, y, width,
// height: mlod_atlas.tiles) of an atlas atlas_width pixels wide: pixel
// (tile pixels from its top-left), depth as the view measures it, and
// map_depth the depth the tile holds at that pixel.  True when the point
// lies inside the view and its pixel in the tile, else false (outputs 0);
// false for a tile of another size than the frame.
bool mlod_atlas_lookup(uint view, uvec4 tile, uint atlas_width, vec3 point, out vec2 pixel, out float depth,
                       out float map_depth)
{
    uint s;
    real x, y, z;
    pixel = vec2(0.0);
    depth = 0.0;
    map_depth = 0.0;
    if (!lookup_tile(view, tile) || frame_project(view, point, s, x, y, z) != 1) return false;
    x = r_floor(x);
    y = r_floor(y);
    real4 c = lookup_sub_pixels(sub_base(view, s));
    if (!(r_ge(x, R_ZERO) && r_lt(x, r_u(tile.z)) && r_ge(y, R_ZERO) && r_lt(y, r_u(tile.w)))) return false;
    pixel = vec2(r_to_f(x), r_to_f(y));
    depth = r_to_f(z);
    map_depth = r_to_f(lookup_depth(tile, atlas_width, x, y, c));
    return true;
}

// (|a - b|^2 summed with the C twin's order, one component: lookup_footprint)
real lookup_sq(real sum, real a, real b)
{
    real d = r_sub(a, b);
    return r_add(sum, r_mul(d, d));
}

// C twin: mlod__footprint
// The footprint at point p (e: p - eye) in the sub-projection at
// views[sub] (pixels c) at tile position (x, y): the rays of the centre of
// the pixel holding it and of its right neighbour (the left one past the
// sub-tile or the disc), unit directions, |o1 - o0| + |e - o0| |d1 - d0|;
// 0 when neither neighbour has a ray.
real lookup_footprint(uint sub, real4 c, real3 e, real x, real y)
{
    real3 o0, d0, o1, d1;
    real per_t, cx = r_add(r_floor(x), R_HALF);
    uint col = r_to_u(r_floor(x)), row = r_to_u(r_floor(y)); // the centre ray's (col + 0.5, row + 0.5)
    int kind = sub_kind(sub);
    if (!centre_ray(sub, kind, col, row, o0, d0, per_t)) return R_ZERO;
    if (!(r_lt(r_add(cx, R_ONE), c.y) && centre_ray(sub, kind, col + 1u, row, o1, d1, per_t)) &&
        !(r_gt(r_sub(cx, R_ONE), c.x) && centre_ray(sub, kind, col - 1u, row, o1, d1, per_t)))
        return R_ZERO;
    real l0 = length_d(d0), l1 = length_d(d1), oo = R_ZERO, ee = R_ZERO, dd = R_ZERO;
    oo = lookup_sq(oo, o1.x, o0.x);
    ee = lookup_sq(ee, e.x, o0.x);
    dd = lookup_sq(dd, r_div(d1.x, l1), r_div(d0.x, l0));
    oo = lookup_sq(oo, o1.y, o0.y);
    ee = lookup_sq(ee, e.y, o0.y);
    dd = lookup_sq(dd, r_div(d1.y, l1), r_div(d0.y, l0));
    oo = lookup_sq(oo, o1.z, o0.z);
    ee = lookup_sq(ee, e.z, o0.z);
    dd = lookup_sq(dd, r_div(d1.z, l1), r_div(d0.z, l0));
    return r_add(r_sqrt(oo), r_mul(r_sqrt(ee), r_sqrt(dd)));
}

// C twin: mlod_atlas_shadow
// The lit fraction, in [0, 1], of world point `point` in view `view`'s
// tile (a shadow map; tile and atlas_width as for mlod_atlas_lookup):
// manylods.h's mlod_atlas_shadow, normal given where has_normal (C: not
// NULL).  1 for a point outside the view; NaN for a tile of another size
// than the frame or params out of range.
float mlod_atlas_shadow(uint view, uvec4 tile, uint atlas_width, vec3 point, bool has_normal, vec3 normal,
                        mlod_shadow_params params)
{
    // C's !(b >= 0.0f) || !(b <= FLT_MAX), from the bits (no float
    // comparison a device may take liberties with): +0 .. FLT_MAX, or -0
    uint b_bits = floatBitsToUint(params.bias), sb_bits = floatBitsToUint(params.slope_bias);
    if (!lookup_tile(view, tile) || params.filter_width > MLOD_SHADOW_MAX_FILTER ||
        !(b_bits < 0x7F800000u || b_bits == 0x80000000u) || !(sb_bits < 0x7F800000u || sb_bits == 0x80000000u))
        return uintBitsToFloat(0x7FC00000u);
    uint s;
    real x, y, z;
    int inside = frame_project(view, point, s, x, y, z);
    if (inside != 1 || !(r_ge(x, R_ZERO) && r_lt(x, r_u(tile.z)) && r_ge(y, R_ZERO) && r_lt(y, r_u(tile.w))))
        return 1.0;
    uint sub = sub_base(view, s);
    real4 c = lookup_sub_pixels(sub);
    real3 e = r3_sub(r3_f(point), vd3(view, MLOD_IF_V_EYE));
    real bias = r_f(params.bias), slope = R_ONE;
    if ((sb_bits & 0x7FFFFFFFu) != 0u) { // slope_bias > 0
        if (has_normal) {
            real3 n = r3_f(normal), l;
            if (sub_kind(sub) == MLOD_IF_KIND_ORTHOGRAPHIC) {
                real3 w = sd3(sub, MLOD_IF_S_FORWARD);
                l = real3(r_neg(w.x), r_neg(w.y), r_neg(w.z));
            } else {
                l = real3(r_neg(e.x), r_neg(e.y), r_neg(e.z));
            }
            real nl = dot3(n, l), nn = dot3(n, n), ll = dot3(l, l);
            real cos2 = r_div(r_mul(nl, nl), r_mul(nn, ll));
            real t2 = r_sub(r_div(R_ONE, cos2), R_ONE); // tan^2 = 1 / cos^2 - 1
            slope = r_le(t2, R_ZERO) ? R_ZERO : r_sqrt(t2);
            if (!r_le(slope, MLOD_SHADOW_MAX_SLOPE)) slope = MLOD_SHADOW_MAX_SLOPE; // NaN (a zero normal): the steepest
        }
        bias = r_add(bias, r_mul(r_mul(r_f(params.slope_bias), lookup_footprint(sub, c, e, x, y)), slope));
    }
    if (params.filter_width == 0u)
        return r_gt(z, r_add(lookup_depth(tile, atlas_width, r_floor(x), r_floor(y), c), bias)) ? 0.0 : 1.0;
    // the k x k square [x - k/2, x + k/2] x [y - k/2, y + k/2]: pixel (i, j)
    // covers [i, i + 1) x [j, j + 1)
    real half_k = r_mul(R_HALF, r_u(params.filter_width));
    real x0 = r_sub(x, half_k), x1 = r_add(x, half_k), y0 = r_sub(y, half_k), y1 = r_add(y, half_k);
    real lit = R_ZERO;
    for (real j = r_floor(y0); r_lt(j, y1); j = r_add(j, R_ONE)) {
        real j1 = r_add(j, R_ONE);
        real wy = r_sub(r_lt(j1, y1) ? j1 : y1, r_gt(j, y0) ? j : y0);
        for (real i = r_floor(x0); r_lt(i, x1); i = r_add(i, R_ONE)) {
            real i1 = r_add(i, R_ONE);
            real wx = r_sub(r_lt(i1, x1) ? i1 : x1, r_gt(i, x0) ? i : x0);
            if (!r_gt(z, r_add(lookup_depth(tile, atlas_width, i, j, c), bias))) lit = r_add(lit, r_mul(wx, wy));
        }
    }
    real k2 = r_mul(r_u(params.filter_width), r_u(params.filter_width));
    lit = r_div(lit, k2);
    return r_to_f(r_lt(lit, R_ONE) ? lit : R_ONE);
}
