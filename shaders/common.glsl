// shaders/common.glsl - the criterion, culling and image disc of manylods.h,
// for the compute shaders of manylods_vk.h.
//
// Each function here is the twin of the C function its "C twin:" line names
// in manylods.h, which names it back ("GLSL twin:"), in the same order
// (tests/check_twins.sh checks both), operation for operation, in double
// precision through real.glsl (every operation an r_* call, rounded on its
// own: no fused multiply-add): the device's own doubles, or with
// MLOD_F64_EMULATED doubles from 32-bit integers (f64.glsl).  Either way
// the two compute the same bits (on a device whose doubles are IEEE, for
// the native form: lavapipe, most desktop GPUs), and the CPU and Vulkan
// cuts are equal node for node.  Change one, change both.
//
// The includer declares, before including this file:
//   vec4 spheres[]  (x, y, z, r per node)   in a buffer named tree_spheres
//   vec4 cones[]    (axis, half-angle)      in a buffer named tree_cones
//   uvec2 views[]   (MLOD_IF_VIEW_STRIDE doubles per view, as their bits:
//                    interface.h)
// and a macro MLOD_HAS_CONES (a bool expression) - or defines MLOD_NO_VIEWS
// (the refit shaders) and gets only the functions that need no view, or
// MLOD_NO_TREE (shaders/lookup.glsl) and declares views[] alone: the
// functions that read the tree's buffers (classify) are left out.  The
// includer enables GL_KHR_shader_subgroup_vote (plane_outside asks its
// subgroup before the exact path) unless it defines MLOD_NO_SUBGROUPS
// (the same results, without that shortcut).

#include "real.glsl"

// The view layout (MLOD_IF_V_*), kind and status codes come from
// interface.h, which the layout files include first.

#ifdef MLOD_F64_EMULATED
struct real4 {
    uvec2 x;
    uvec2 y;
    uvec2 z;
    uvec2 w;
};
#else
#define real4 dvec4
#endif

#ifndef MLOD_NO_VIEWS
// A view's field (MLOD_IF_V_*), and the first double of its sub-projection
// s, whose fields (MLOD_IF_S_*) sd and sd3 read.
#ifdef MLOD_MEGAVIEWS
// MegaViews (mv_layout.glsl): views[] holds one frame per kind of map at
// the eye (0, 0, 0), moved to mv_eye, which the caller sets: the eye, and
// each plane's k = n.eye + offset, i.e. n.mv_eye plus the stored k (=
// offset: n.0 + offset is offset, a zero offset +0), as mlod__plane_set
// computes it for that eye.
real3 mv_eye;
real dot3(real3 a, real3 b);
real vd(uint view, uint field)
{
    if (field == MLOD_IF_V_EYE) return mv_eye.x;
    if (field == MLOD_IF_V_EYE + 1u) return mv_eye.y;
    if (field == MLOD_IF_V_EYE + 2u) return mv_eye.z;
    return r_load(views[view * MLOD_IF_VIEW_STRIDE + field]);
}
real sd(uint sub, uint field)
{
    uint at = sub + field, f = (at % MLOD_IF_VIEW_STRIDE - MLOD_IF_V_SUBS) % MLOD_IF_SUB_STRIDE;
    real stored = r_load(views[at]);
    if (f < MLOD_IF_S_PLANES || (f - MLOD_IF_S_PLANES) % 5u != 3u) return stored;
    real3 n = real3(r_load(views[at - 3u]), r_load(views[at - 2u]), r_load(views[at - 1u]));
    return r_add(dot3(n, mv_eye), stored);
}
#else
real vd(uint view, uint field) { return r_load(views[view * MLOD_IF_VIEW_STRIDE + field]); }
real sd(uint sub, uint field) { return r_load(views[sub + field]); }
#endif
real3 vd3(uint view, uint field) { return real3(vd(view, field), vd(view, field + 1), vd(view, field + 2)); }
uint sub_count(uint view) { return r_to_u(vd(view, MLOD_IF_V_SUB_COUNT)); }
uint sub_base(uint view, uint s) { return view * MLOD_IF_VIEW_STRIDE + MLOD_IF_V_SUBS + s * MLOD_IF_SUB_STRIDE; }
real3 sd3(uint sub, uint field) { return real3(sd(sub, field), sd(sub, field + 1), sd(sub, field + 2)); }
int sub_kind(uint sub) { return int(r_to_u(sd(sub, MLOD_IF_S_KIND))); }

#endif // MLOD_NO_VIEWS

// ---------------------------- helpers and merges (refit needs them too) --

// C twin: mlod__float_up
// The smallest float >= x (x >= 0)
float float_up(real x)
{
    float f = r_to_f(x);
    if (r_lt(r_f(f), x)) f = uintBitsToFloat(floatBitsToUint(f) + 1u);
    return f;
}

// C twin: mlod__dot3
// ((x x' + y y') + z z'), one product and one sum a step (ROLLED)
real dot3(real3 a, real3 b)
{
    real sum = R_ZERO;
    ROLLED for (uint k = 0u; k < 3u; k++) {
        real p = r_mul(r3_at(a, k), r3_at(b, k));
        sum = k == 0u ? p : r_add(sum, p);
    }
    return sum;
}

// C twin: mlod__cross3
// component k: a[k + 1] b[k + 2] - a[k + 2] b[k + 1] (indices mod 3)
real3 cross_d(real3 a, real3 b)
{
    real c[3];
    ROLLED for (uint k = 0u; k < 3u; k++) {
        uint i = k == 2u ? 0u : k + 1u, j = k == 0u ? 2u : k - 1u;
        c[k] = r_sub(r_mul(r3_at(a, i), r3_at(b, j)), r_mul(r3_at(a, j), r3_at(b, i)));
    }
    return real3(c[0], c[1], c[2]);
}

// C twin: mlod__length3
real length_d(real3 a) { return r_sqrt(dot3(a, a)); }

// C twin: mlod__distance_f
real distance_f(vec3 a, vec3 b)
{
    real3 x = r3_sub(r3_f(a), r3_f(b));
    return r_sqrt(dot3(x, x));
}

// C twin: mlod__cos_even
// (and the five arrays after it: the same literals)
const real COS_EVEN[6] = real[](
    RK(0x3C1E542Bu, 0xA4020225u, 4.110317623312165e-19LF),
    RK(0x3D2AE7F3u, 0xE733B81Fu, 4.779477332387385e-14LF),
    RK(0x3E21EED8u, 0xEFF8D898u, 2.08767569878681e-09LF),
    RK(0x3EFA01A0u, 0x1A01A01Au, 2.48015873015873e-05LF),
    RK(0x3FA55555u, 0x55555555u, 0.041666666666666664LF),
    RK(0x3FF00000u, 0x00000000u, 1.0LF));

const real COS_ODD[6] = real[](
    RK(0x3B90CE39u, 0x6DB7F853u, 8.896791392450574e-22LF),
    RK(0x3CA68278u, 0x63B97D97u, 1.5619206968586225e-16LF),
    RK(0x3DA93974u, 0xA8C07C9Du, 1.1470745597729725e-11LF),
    RK(0x3E927E4Fu, 0xB7789F5Cu, 2.755731922398589e-07LF),
    RK(0x3F56C16Cu, 0x16C16C17u, 0.001388888888888889LF),
    RK(0x3FE00000u, 0x00000000u, 0.5LF));

const real SIN_EVEN[6] = real[](
    RK(0x3BD71B8Eu, 0xF6DCF572u, 1.9572941063391263e-20LF),
    RK(0x3CE952C7u, 0x7030AD4Au, 2.8114572543455206e-15LF),
    RK(0x3DE61246u, 0x13A86D09u, 1.6059043836821613e-10LF),
    RK(0x3EC71DE3u, 0xA556C734u, 2.7557319223985893e-06LF),
    RK(0x3F811111u, 0x11111111u, 0.008333333333333333LF),
    RK(0x3FF00000u, 0x00000000u, 1.0LF));

const real SIN_ODD[5] = real[](
    RK(0x3C62F49Bu, 0x46814157u, 8.22063524662433e-18LF),
    RK(0x3D6AE7F3u, 0xE733B81Fu, 7.647163731819816e-13LF),
    RK(0x3E5AE645u, 0x67F544E4u, 2.505210838544172e-08LF),
    RK(0x3F2A01A0u, 0x1A01A01Au, 0.0001984126984126984LF),
    RK(0x3FC55555u, 0x55555555u, 0.16666666666666666LF));

const real ATAN_EVEN[6] = real[](
    RK(0x3FA86186u, 0x18618618u, 0.047619047619047616LF),
    RK(0x3FAE1E1Eu, 0x1E1E1E1Eu, 0.058823529411764705LF),
    RK(0x3FB3B13Bu, 0x13B13B14u, 0.07692307692307693LF),
    RK(0x3FBC71C7u, 0x1C71C71Cu, 0.1111111111111111LF),
    RK(0x3FC99999u, 0x9999999Au, 0.2LF),
    RK(0x3FF00000u, 0x00000000u, 1.0LF));

const real ATAN_ODD[6] = real[](
    RK(0x3FA642C8u, 0x590B2164u, 0.043478260869565216LF),
    RK(0x3FAAF286u, 0xBCA1AF28u, 0.05263157894736842LF),
    RK(0x3FB11111u, 0x11111111u, 0.06666666666666667LF),
    RK(0x3FB745D1u, 0x745D1746u, 0.09090909090909091LF),
    RK(0x3FC24924u, 0x92492492u, 0.14285714285714285LF),
    RK(0x3FD55555u, 0x55555555u, 0.3333333333333333LF));

// C twin: mlod__sin_cos
void sin_cos(real a, out real sin_a, out real cos_a)
{
    real x = r_sub(a, R_HALF_PI);
    real y = r_mul(x, x);
    real z = r_mul(y, y);
    real ce = COS_EVEN[0];
    real co = COS_ODD[0];
    real se = SIN_EVEN[0];
    real so = SIN_ODD[0];
    ROLLED for (int k = 1; k < 6; k++) {
        ce = r_add(COS_EVEN[k], r_mul(z, ce));
        co = r_add(COS_ODD[k], r_mul(z, co));
        se = r_add(SIN_EVEN[k], r_mul(z, se));
    }
    ROLLED for (int k = 1; k < 5; k++) so = r_add(SIN_ODD[k], r_mul(z, so));
    sin_a = r_sub(ce, r_mul(y, co));
    real sine = r_sub(se, r_mul(y, so));
    cos_a = r_mul(r_neg(x), sine);
}

// C twin: mlod__atan2
// (y >= 0)
real atan2_d(real y, real x)
{
    real ax = r_abs(x);
    bool swap = r_gt(y, ax);
    if (!r_gt(y, R_ZERO) && !r_gt(ax, R_ZERO)) return r_lt(x, R_ZERO) ? R_PI : R_ZERO;
    real t = swap ? r_div(ax, y) : r_div(y, ax);
    real u = t;
    real base = R_ZERO;
    if (r_gt(t, RK(0x3FDA8279u, 0x99FCEF32u, 0.41421356237309504880LF))) {
        u = r_div(r_sub(t, R_ONE), r_add(t, R_ONE));
        base = RK(0x3FE921FBu, 0x54442D18u, 0.78539816339744830962LF);
    }
    real u2 = r_mul(u, u);
    real w = r_mul(u2, u2);
    real even = ATAN_EVEN[0];
    real odd = ATAN_ODD[0];
    ROLLED for (int k = 1; k < 6; k++) {
        even = r_add(ATAN_EVEN[k], r_mul(w, even));
        odd = r_add(ATAN_ODD[k], r_mul(w, odd));
    }
    real a = r_add(base, r_mul(u, r_sub(even, r_mul(u2, odd))));
    if (swap) a = r_sub(R_HALF_PI, a);
    return r_lt(x, R_ZERO) ? r_sub(R_PI, a) : a;
}

// C twin: mlod__angle
real angle_d(real3 a, real3 b) { return atan2_d(length_d(cross_d(a, b)), dot3(a, b)); }

// C twin: mlod__sphere_enclose
vec4 sphere_enclose(vec4 a, vec4 b)
{
    real d = distance_f(a.xyz, b.xyz);
    real ra = r_f(a.w), rb = r_f(b.w);
    vec3 c;
    if (r_le(r_add(d, rb), ra)) {
        c = a.xyz;
    } else if (r_le(r_add(d, ra), rb)) {
        c = b.xyz;
    } else {
        real t = r_div(r_sub(r_mul(r_add(r_add(d, ra), rb), R_HALF), ra), d);
        ROLLED for (uint k = 0u; k < 3u; k++) c[k] = r_to_f(r_add(r_f(a[k]), r_mul(r_sub(r_f(b[k]), r_f(a[k])), t)));
    }
    real needs[2];
    ROLLED for (uint k = 0u; k < 2u; k++) needs[k] = r_add(distance_f(c, k == 0u ? a.xyz : b.xyz), k == 0u ? ra : rb);
    real need_a = needs[0], need_b = needs[1];
    // (1 + 2^-20) (1 + 2^-50)
    real need = r_mul(r_mul(r_gt(need_a, need_b) ? need_a : need_b, RK(0x3FF00001u, 0x00000000u, 1.00000095367431640625LF)),
                      RK(0x3FF00000u, 0x00000004u, 1.00000000000000088817841970012523LF));
    return vec4(c, float_up(need));
}

// C twin: mlod__cone_full
vec4 cone_full(vec3 axis) { return vec4(axis, float_up(R_PI)); }

// C twin: mlod__cone_enclose
// (the stored axis is within MLOD__CONE_ROUNDING, 2^-22
// rad, of the merged one; nearly opposite axes, closer than
// MLOD__CONE_OPPOSITE, measure the stored axis against both cones)
vec4 cone_enclose(vec4 a, vec4 b)
{
    real aw = r_f(a.w), bw = r_f(b.w);
    if (r_ge(aw, R_PI) || r_ge(bw, R_PI)) return cone_full(a.xyz);
    real3 A = r3_f(a.xyz), B = r3_f(b.xyz), X;
    real theta = angle_d(A, B);
    real alpha;
    bool measure = false;
    if (r_le(r_add(theta, bw), aw)) {
        X = A;
        alpha = aw;
    } else if (r_le(r_add(theta, aw), bw)) {
        X = B;
        alpha = bw;
    } else {
        alpha = r_mul(r_add(r_add(theta, aw), bw), R_HALF);
        if (r_ge(alpha, R_PI)) return cone_full(a.xyz);
        real phi = r_sub(alpha, aw);
        real sin_phi, cos_phi;
        sin_cos(phi, sin_phi, cos_phi);
        real la = length_d(A), an[3];
        ROLLED for (uint k = 0u; k < 3u; k++) an[k] = r_div(r3_at(A, k), la);
        real3 An = real3(an[0], an[1], an[2]);
        real ab = dot3(An, B);
        real3 t = r3_sub(B, r3_scale(An, ab));
        real len = length_d(t);
        measure = !r_ge(len, RK(0x3F500000u, 0x00000000u, 0.0009765625LF)) && !r_gt(ab, R_ZERO);
        if (!r_gt(len, R_ZERO)) {
            real3 helper = real3(R_ZERO, R_ZERO, R_ZERO);
            if (r_lt(r_abs(An.x), R_HALF)) helper.x = R_ONE; else helper.y = R_ONE;
            t = cross_d(An, helper);
            len = length_d(t);
        }
        real xc[3];
        ROLLED for (uint k = 0u; k < 3u; k++)
            xc[k] = r_add(r_mul(r3_at(An, k), cos_phi), r_mul(r_div(r3_at(t, k), len), sin_phi));
        X = real3(xc[0], xc[1], xc[2]);
    }
    real lx = length_d(X);
    vec3 axis;
    ROLLED for (uint k = 0u; k < 3u; k++) axis[k] = r_to_f(r_div(r3_at(X, k), lx));
    // +0 for a zero component however it was reached: the compiler may fold
    // away the terms that decide the sign of a zero (x + 0 -> x), the CPU
    // does not; the test on the bits cannot be folded
    [[unroll]] for (int k = 0; k < 3; k++)
        if (floatBitsToUint(axis[k]) == 0x80000000u) axis[k] = 0.0;
    if (measure) {
        real3 S = r3_f(axis);
        real needs[2];
        ROLLED for (uint k = 0u; k < 2u; k++) needs[k] = r_add(angle_d(S, k == 0u ? A : B), k == 0u ? aw : bw);
        alpha = r_gt(needs[0], needs[1]) ? needs[0] : needs[1];
    }
    // + 2^-22 + 2^-20
    real stored = r_add(r_add(alpha, RK(0x3E900000u, 0x00000000u, 2.384185791015625e-07LF)),
                        RK(0x3EB00000u, 0x00000000u, 9.5367431640625e-07LF));
    if (r_ge(stored, R_PI)) return cone_full(axis);
    return vec4(axis, float_up(stored));
}

// C twin: mlod__depth_of
// (node < 2^32 - 1)
uint depth_of(uint node)
{
    return uint(findMSB(node + 1u));
}

// C twin: mlod__leaves_below
// Leaves under node i of the tree of n leaves (n <= 2^31).  In 32 bits:
// every quantity's true value is below 2^32 (the deepest level is at
// most 31), so wrapping arithmetic gives it; ceil(nodes / 2) without
// nodes + 1, which can reach 2^32.
uint leaves_below(uint i, uint n)
{
    uint last = 2u * n - 2u;
    uint k = depth_of(i), deepest = depth_of(last);
    uint span = deepest - k;
    uint lo = ((i + 1u) << span) - 1u, hi = ((i + 2u) << span) - 2u;
    uint at_deepest = lo > last ? 0u : (hi < last ? hi : last) - lo + 1u;
    uint nodes = ((1u << span) - 1u) + at_deepest;
    return nodes / 2u + (nodes & 1u);
}

// ------------------------------------------------ exact plane predicate --

// C twin: mlod__two_sum
void two_sum(real a, real b, out real s, out real err)
{
    real sum = r_add(a, b);
    real bv = r_sub(sum, a);
    real av = r_sub(sum, bv);
    err = r_add(r_sub(a, av), r_sub(b, bv));
    s = sum;
}

// C twin: mlod__split
void split_double(real a, out real hi, out real lo)
{
    real c = r_mul(RK(0x41A00000u, 0x02000000u, 134217729.0LF), a);
    real big = r_sub(c, a);
    real h = r_sub(c, big);
    lo = r_sub(a, h);
    hi = h;
}

// C twin: mlod__two_product
void two_product(real a, real b, out real p, out real err)
{
    real prod = r_mul(a, b);
    real hi[2], lo[2];
    ROLLED for (int k = 0; k < 2; k++) split_double(k == 0 ? a : b, hi[k], lo[k]);
    real ah = hi[0], al = lo[0], bh = hi[1], bl = lo[1];
    err = r_sub(r_mul(al, bl), r_sub(r_sub(r_sub(prod, r_mul(ah, bh)), r_mul(al, bh)), r_mul(ah, bl)));
    p = prod;
}

// C twin: mlod__exact_sign
// For the 9 terms of plane_outside: the same exact sign by the same
// expansion growth, without its zero elimination so that every
// index is a constant once the loops unroll (lavapipe then keeps the
// expansion in registers; the dynamic version costs every evaluation a
// factor of two even though it rarely runs).
int exact_sign9(real t[9])
{
    real e[9];
    ROLLED for (int i = 0; i < 9; i++) {
        real q = t[i], h;
        ROLLED for (int j = 0; j < i; j++) {
            two_sum(q, e[j], q, h);
            e[j] = h;
        }
        e[i] = q;
    }
    int sign = 0;
    ROLLED for (int i = 0; i < 9; i++)
        if (!r_eq(e[i], R_ZERO)) sign = r_gt(e[i], R_ZERO) ? 1 : -1; /* the largest nonzero component decides */
    return sign;
}

#ifndef MLOD_NO_VIEWS
// C twin: mlod__outside
// Is the sphere wholly outside the half-space at views[base]
// (n.c + l r < k, exactly)?
bool plane_outside(uint base, vec4 sphere)
{
    real k = sd(base, 3u), factors[4] = real[](sd(base, 0u), sd(base, 1u), sd(base, 2u), sd(base, 4u));
    // s = ((t0 + t1) + t2) + t3 - k for the terms t_j = n_j c_j (and l r),
    // with their magnitudes' sum (ROLLED)
    real s = R_ZERO, mag = R_ZERO;
    ROLLED for (int j = 0; j < 4; j++) {
        real t = r_mul(factors[j], r_f(sphere[j]));
        s = j == 0 ? t : r_add(s, t);
        mag = j == 0 ? r_abs(t) : r_add(mag, r_abs(t));
    }
    s = r_sub(s, k);
    // 2^-48 of the terms' magnitudes
    real bound = r_mul(r_add(mag, r_abs(k)), RK(0x3CF00000u, 0x00000000u, 3.552713678800501e-15LF));
    bool below = r_lt(s, r_neg(bound)), above = r_gt(s, bound);
    // The exact path runs where the filter cannot decide, which is rare;
    // asking the whole subgroup first keeps SIMD devices (lavapipe runs
    // every lane of a divergent branch) from paying for it every time.
#ifndef MLOD_NO_SUBGROUPS
    if (!subgroupAny(!below && !above)) return below;
#endif
    if (below) return true;
    if (above) return false;
    real t[9];
    ROLLED for (int j = 0; j < 4; j++) two_product(factors[j], r_f(sphere[j]), t[2 * j], t[2 * j + 1]);
    t[8] = r_neg(k);
    return exact_sign9(t) < 0;
}

// ------------------------------------------------------------ criterion --

// C twin: mlod__backfacing
bool backfacing(uint view, real3 x, real d2, real r, vec4 cone)
{
    real c0 = r_f(cone.x), c1 = r_f(cone.y), c2 = r_f(cone.z);
    real3 c = real3(c0, c1, c2);
    if (!r_lt(r_f(cone.w), r_mul(R_HALF, R_PI))) return false;
    // the C twin's two branches (orthographic: the axis w, no tangent)
    // with one copy of each step
    bool ortho = sub_kind(sub_base(view, 0u)) == MLOD_IF_KIND_ORTHOGRAPHIC;
    if (!ortho && r_le(d2, r_mul(r, r))) return false;
    real away = r_neg(dot3(c, ortho ? sd3(sub_base(view, 0u), MLOD_IF_S_FORWARD) : x));
    if (!r_lt(away, R_ZERO)) return false;
    real len = r_sqrt(dot3(c, c)), tangent = R_ZERO, sa, ca;
    if (!ortho) tangent = r_sqrt(r_sub(d2, r_mul(r, r)));
    sin_cos(r_f(cone.w), sa, ca);
    real along = r_div(away, len);
    if (ortho) return r_gt(ca, R_ZERO) && r_lt(along, r_neg(sa));
    real lhs = r_sub(r_mul(ca, tangent), r_mul(sa, r));
    real rhs = r_neg(r_add(r_mul(sa, tangent), r_mul(ca, r)));
    return r_gt(lhs, R_ZERO) && r_lt(along, rhs);
}

#endif // MLOD_NO_VIEWS

// C twin: mlod__paraboloid_diameter
real paraboloid_diameter(real r, real xw, real tangent)
{
    real den = r_add(xw, tangent);
    return r_gt(den, R_ZERO) ? r_div(r_mul(R_TWO, r), den) : r_inf();
}

#ifndef MLOD_NO_VIEWS
// C twin: mlod__sub_diameter
// The diameter of the sphere's image in the sub-projection at views[sub],
// in pixels (tangent: 0 for orthographic views).
real sub_diameter(uint sub, real3 x, real d2, real r, real tangent)
{
    real xw = dot3(x, sd3(sub, MLOD_IF_S_FORWARD));
    real scale = sd(sub, MLOD_IF_S_SCALE);
    int kind = sub_kind(sub);
    if (kind == MLOD_IF_KIND_PERSPECTIVE) {
        if (r_le(xw, r)) return r_inf();
        return r_div(r_mul(r_mul(r_mul(scale, R_TWO), r), tangent), r_mul(r_sub(xw, r), r_add(xw, r)));
    }
    if (kind == MLOD_IF_KIND_PARABOLOID) {
        if (r_le(d2, r_mul(r, r))) return r_inf();
        return r_mul(scale, paraboloid_diameter(r, xw, tangent));
    }
    return r_mul(r_mul(scale, R_TWO), r);
}

// C twin: mlod__reached
// Which sub-projections the sphere reaches: bit s for sub-projection s.
uint reached_subs(uint view, vec4 sphere)
{
    uint reached = 0u, count = sub_count(view);
    for (uint s = 0u; s < count; s++) {
        uint sub = sub_base(view, s), planes = r_to_u(sd(sub, MLOD_IF_S_PLANE_COUNT));
        bool inside = true;
        for (uint k = 0u; k < planes && inside; k++)
            if (plane_outside(sub + MLOD_IF_S_PLANES + 5u * k, sphere)) inside = false;
        if (inside) reached |= 1u << s;
    }
    return reached;
}

// C twin: mlod__evaluate
// c(node, view) in pixels; culled set when culled.
real evaluate(uint view, vec4 sphere, bool use_cone, vec4 cone, out bool culled)
{
    // one sub-projection: its planes first; several: the back faces first
    // (the C twin's order; either culls the same nodes), with one call of
    // reached_subs (ROLLED)
    uint count = sub_count(view), reached = 0u;
    real3 x = real3(R_ZERO, R_ZERO, R_ZERO);
    real d2 = R_ZERO, r = R_ZERO, tangent = R_ZERO;
    culled = true;
    ROLLED for (uint step = 0u; step < 2u; step++) {
        if ((step == 0u) == (count == 1u)) {
            reached = reached_subs(view, sphere);
            if (reached == 0u) return R_ZERO;
            continue;
        }
        x = r3_sub(r3_f(sphere.xyz), vd3(view, MLOD_IF_V_EYE));
        d2 = dot3(x, x);
        r = r_f(sphere.w);
        real t2 = r_sub(d2, r_mul(r, r));
        tangent = r_sqrt(r_gt(t2, R_ZERO) ? t2 : R_ZERO);
        if (sub_kind(sub_base(view, 0u)) == MLOD_IF_KIND_ORTHOGRAPHIC) tangent = R_ZERO;
        if (use_cone && !r_eq(vd(view, MLOD_IF_V_BACKFACES), R_ZERO) && backfacing(view, x, d2, r, cone)) return R_ZERO;
    }
    culled = false;
    real c = R_ZERO;
    for (uint s = 0u; s < count; s++)
        if (((reached >> s) & 1u) != 0u) {
            real d = sub_diameter(sub_base(view, s), x, d2, r, tangent);
            if (r_gt(d, c)) c = d;
        }
    return c;
}

#ifdef MLOD_HAS_FILTERS
// The float filter (the includer declares vec4 filters[], each view's
// MLOD_IF_FILTER_STRIDE floats: interface.h).  The C twins' bounds assume
// correctly rounded float operations; Vulkan rounds +, -, * correctly but
// lets sqrt err by a few ulp (inherited from 1 / inversesqrt).  That adds
// about 9 u (u = 2^-24) to t and to the cone axis' length: the diameter
// thresholds' margin of 4096 u keeps over 3000 u to spare, the planes'
// 2^-20 margin scales with a reach off by 9 u, and only the back-face
// test's (40 u against 28 u of error) would not do: the shader takes 80 u
// there.  A wider margin only leaves more node-views to the exact path, so
// the cuts stay the CPU's node for node (a decided status is the exact
// path's on either side).  Fused multiply-adds round less: the bounds hold.
// The filter is read four floats at a time: a SIMD device (lavapipe) loads
// a buffer word lane by lane, so each load costs it a loop over the lanes.

// The four floats of the filters buffer from float i on (i a multiple of 4).
vec4 fl4(uint i) { return filters[i >> 2]; }

// C twin: mlod__fast_backfacing
// 1 culled, 0 not, -1 unsure; x = centre - eye, t the tangent length, r
// the radius ((t, r) = (1, 0) and x unused for an orthographic view, w its
// axis).
int fast_backfacing(bool ortho, vec3 w, vec3 x, float t, float r, vec4 cone)
{
    float a = cone.w;
    if (!(a < uintBitsToFloat(0x3FC90FDBu))) return 0; // pi / 2 rounded to float, as the C twin's
    if (!(a >= 0.0)) return -1;
    vec3 axis = cone.xyz;
    float away = ortho ? -(axis.x * w.x + axis.y * w.y + axis.z * w.z) : -(axis.x * x.x + axis.y * x.y + axis.z * x.z);
    float len = sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
    float a2 = a * a;
    float sa = a * (1.0 - a2 * (uintBitsToFloat(0x3E2AAAABu) - a2 * uintBitsToFloat(0x3C088889u))); // 1/6, 1/120
    // 1/24, 1/720
    float ca = 1.0 - a2 * (0.5 - a2 * (uintBitsToFloat(0x3D2AAAABu) - a2 * uintBitsToFloat(0x3AB60B61u)));
    float e = a2 * a2 * a2 * a * uintBitsToFloat(0x39500D01u) + 80.0 * uintBitsToFloat(0x33800000u); // 1/5040; u
    float m1 = (t + r) * e;
    float z2 = away + len * (sa * t + ca * r);
    if (z2 > len * m1) return 0;
    float z1 = ca * t - sa * r;
    if (z1 < -m1) return 0;
    if (z1 > m1 && z2 < -len * m1) return 1;
    return -1;
}

// C twin: mlod__fast_status
// The status of a node-view by the float filter: MLOD_IF_STATUS_CULLED,
// _DRAWN, _COARSE (not valid: the caller tells an oversize leaf) or 0
// (unsure).  Views whose eye is not exactly a float take the exact path.
// One pass over the sub-projections decides what the C twin's two do, in
// its order: a plane the filter is unsure of first, then culled (no
// sub-projection reached, or back-facing), then the first reached
// sub-projection whose size test is unsure or too large, then drawn.
uint fast_status(uint view, vec4 sphere, bool use_cone, vec4 cone)
{
    uint f = view * MLOD_IF_FILTER_STRIDE;
    vec4 head = fl4(f + MLOD_IF_F_OK), eye = fl4(f + MLOD_IF_F_EYE); // OK, BACKFACES, ORTHO, SUB_COUNT; EYE, FLOAT_EYE
    if (head.x == 0.0 || eye.w == 0.0) return 0u;
    vec3 x = vec3(sphere.x - eye.x, sphere.y - eye.y, sphere.z - eye.z), w0 = vec3(0.0);
    float r = sphere.w, d2 = x.x * x.x + x.y * x.y + x.z * x.z, t = 1.0, twice = r + r, reach;
    bool ortho = head.z != 0.0, all_valid = true;
    uint reached = 0u, count = uint(head.w), size_status = MLOD_IF_STATUS_DRAWN;
    if (!(d2 >= uintBitsToFloat(0x2B800000u) && d2 <= uintBitsToFloat(0x67800000u))) return 0u; // 2^-40, 2^80
    if (!(r == 0.0 || (r >= uintBitsToFloat(0x2B800000u) && r <= uintBitsToFloat(0x53800000u)))) return 0u; // 2^40
    if (!ortho) {
        float t2 = d2 - r * r;
        if (!(4.0 * t2 >= d2)) return 0u;
        t = sqrt(t2);
        reach = t + twice; // >= |x| + r
    } else {
        reach = sqrt(d2) + r;
    }
    for (uint s = 0u; s < count; s++) {
        uint fs = f + MLOD_IF_F_SUBS + s * MLOD_IF_F_SUB_STRIDE, j;
        vec4 sub = fl4(fs + MLOD_IF_FS_KIND); // KIND, PLANE_COUNT, VALID, INVALID
        vec3 w = fl4(fs + MLOD_IF_FS_W).xyz;
        uint planes = uint(sub.y);
        if (s == 0u) w0 = w;
        for (j = 0u; j < planes; j++) {
            uint p = fs + MLOD_IF_FS_PLANES + j * MLOD_IF_FP_STRIDE;
            vec4 n = fl4(p + MLOD_IF_FP_N), k = fl4(p + MLOD_IF_FP_N + 4u); // n, l; k - n.eye, slope, error
            float v = n.x * x.x + n.y * x.y + n.z * x.z + n.w * r - k.x;
            float m = k.y * reach + k.z;
            if (v < -m) break;
            if (!(v > m)) return 0u;
        }
        if (j < planes) continue; // missed
        reached |= 1u << s;
        if (size_status != MLOD_IF_STATUS_DRAWN) continue; // decided by an earlier sub-projection
        int kind = int(sub.x);
        float xw = x.x * w.x + x.y * w.y + x.z * w.z;
        float lhs, rhs;
        if (kind == MLOD_IF_KIND_PERSPECTIVE) {
            float near_side = xw - r;
            if (!(near_side > 0.0 && 256.0 * near_side * near_side >= d2)) {
                size_status = 0u;
                continue;
            }
            lhs = twice * t;
            rhs = near_side * (xw + r);
        } else if (kind == MLOD_IF_KIND_PARABOLOID) {
            rhs = xw + t;
            if (!(rhs > 0.0 && 256.0 * rhs * rhs >= d2)) {
                size_status = 0u;
                continue;
            }
            lhs = twice;
        } else {
            lhs = twice;
            rhs = 1.0;
        }
        if (lhs * sub.w > rhs) size_status = MLOD_IF_STATUS_COARSE;
        else if (!(lhs * sub.z <= rhs)) all_valid = false;
    }
    if (reached == 0u) return MLOD_IF_STATUS_CULLED;
    if (head.y != 0.0 && use_cone) {
        int b = fast_backfacing(ortho, w0, x, t, ortho ? 0.0 : r, cone);
        if (b != 0) return b > 0 ? MLOD_IF_STATUS_CULLED : 0u;
    }
    if (size_status != MLOD_IF_STATUS_DRAWN) return size_status;
    return all_valid ? MLOD_IF_STATUS_DRAWN : 0u;
}
#endif

// C twin: mlod__is_valid
bool status_valid(uint s) { return s == MLOD_IF_STATUS_DRAWN || s == MLOD_IF_STATUS_CULLED; }

#ifndef MLOD_NO_TREE
#ifdef MLOD_HAS_FILTERS
// classify's first step, the float filter alone: the status, or 0 where
// the filter is unsure (cut_step and cut_finish then list the entry for
// their exact pass: defer_entry).
uint classify_fast(uint view, uint node, uint leaf_count)
{
    vec4 cone = MLOD_HAS_CONES ? cones[node] : vec4(0.0);
    uint st = fast_status(view, spheres[node], MLOD_HAS_CONES, cone);
    if (st == MLOD_IF_STATUS_COARSE && node >= leaf_count - 1u) st = MLOD_IF_STATUS_OVERSIZE;
    return st;
}
#endif

// C twin: mlod__classify
uint classify(uint view, uint node, real epsilon, uint leaf_count)
{
    bool culled;
#ifdef MLOD_HAS_FILTERS
    // the exact path below only where the filter is unsure (rare): asked
    // of the whole subgroup first, since SIMD devices (lavapipe) run a
    // divergent branch for every lane
    uint st = classify_fast(view, node, leaf_count);
    if (!subgroupAny(st == 0u)) return st; // the same for the whole subgroup: a branch it skips together
    if (st != 0u) return st;
#endif
    vec4 cone = MLOD_HAS_CONES ? cones[node] : vec4(0.0);
    real c = evaluate(view, spheres[node], MLOD_HAS_CONES, cone, culled);
    if (culled) return MLOD_IF_STATUS_CULLED;
    if (r_le(c, epsilon)) return MLOD_IF_STATUS_DRAWN;
    return node >= leaf_count - 1u ? MLOD_IF_STATUS_OVERSIZE : MLOD_IF_STATUS_COARSE;
}
#endif // MLOD_NO_TREE

// ----------------------------------------------------------- image disc --

// C twin: mlod__image_discs (one of its lanes)
// The disc around the image of sphere (centre, r) in sub-projection s of
// the view's tile (pixels), and the depth of its centre.  Returns false
// when unbounded.
bool image_disc(uint view, uint s, real3 centre, real r, out real4 disc)
{
    disc = real4(R_ZERO, R_ZERO, R_ZERO, R_ZERO);
    uint sub = sub_base(view, s);
    real3 u = sd3(sub, MLOD_IF_S_RIGHT), v = sd3(sub, MLOD_IF_S_UP);
    real3 w = sd3(sub, MLOD_IF_S_FORWARD);
    real3 x = r3_sub(centre, vd3(view, MLOD_IF_V_EYE));
    real scale = sd(sub, MLOD_IF_S_SCALE), left = sd(sub, MLOD_IF_S_X), top = sd(sub, MLOD_IF_S_Y);
    real width = sd(sub, MLOD_IF_S_WIDTH), height = sd(sub, MLOD_IF_S_HEIGHT);
    real mid_x = r_add(left, r_mul(R_HALF, width));
    real mid_y = r_add(top, r_mul(R_HALF, height));
    int kind = sub_kind(sub);
    if (kind == MLOD_IF_KIND_ORTHOGRAPHIC) {
        real px = r_add(mid_x, r_mul(sd(sub, MLOD_IF_S_SCALE_X), dot3(x, u)));
        real py = r_sub(mid_y, r_mul(sd(sub, MLOD_IF_S_SCALE_Y), dot3(x, v)));
        disc = real4(px, py, r_mul(r, scale), dot3(x, w));
        return true;
    }
    real d = r_sqrt(dot3(x, x));
    if (!r_gt(d, r)) return false;
    real a = r_div(dot3(x, u), d);
    real b = r_div(dot3(x, v), d);
    real cos_t = r_div(dot3(x, w), d);
    real sin_t = r_sqrt(r_add(r_mul(a, a), r_mul(b, b)));
    real sin_b = r_div(r, d);
    real cos_b = r_sqrt(r_sub(R_ONE, r_mul(sin_b, sin_b)));
    real dir_x = R_ZERO, dir_y = R_ZERO;
    if (r_gt(sin_t, R_ZERO)) {
        dir_x = r_div(a, sin_t);
        dir_y = r_div(b, sin_t);
    }
    real s_hi = r_add(r_mul(sin_t, cos_b), r_mul(cos_t, sin_b));
    real c_hi = r_sub(r_mul(cos_t, cos_b), r_mul(sin_t, sin_b));
    real s_lo = r_sub(r_mul(sin_t, cos_b), r_mul(cos_t, sin_b));
    real c_lo = r_add(r_mul(cos_t, cos_b), r_mul(sin_t, sin_b));
    real hi, lo, px, py, depth;
    if (kind == MLOD_IF_KIND_PERSPECTIVE) {
        if (!r_gt(c_hi, R_ZERO)) return false;
        hi = r_div(s_hi, c_hi);
        lo = r_div(s_lo, c_lo);
        px = r_add(mid_x, r_mul(r_mul(r_mul(scale, R_HALF), r_add(hi, lo)), dir_x));
        py = r_sub(mid_y, r_mul(r_mul(r_mul(scale, R_HALF), r_add(hi, lo)), dir_y));
        depth = dot3(x, w);
    } else {
        real one_hi = r_add(R_ONE, c_hi);
        if (!r_gt(one_hi, R_ZERO) || !(r_gt(s_hi, R_ZERO) || r_gt(c_hi, R_ZERO))) return false;
        hi = r_div(s_hi, one_hi);
        lo = r_div(s_lo, r_add(R_ONE, c_lo));
        real mean = r_mul(R_HALF, r_add(hi, lo));
        px = r_add(left, r_mul(r_mul(R_HALF, width), r_add(R_ONE, r_mul(mean, dir_x))));
        py = r_add(top, r_mul(r_mul(R_HALF, height), r_sub(R_ONE, r_mul(mean, dir_y))));
        depth = d;
    }
    disc = real4(px, py, r_mul(r_mul(scale, R_HALF), r_sub(hi, lo)), depth);
    return true;
}

// --------------------------------------------------------- tangent discs --

// C twin: mlod__centre_ray
// The ray through the centre of tile pixel (col, row) in the
// sub-projection at views[sub], of this kind, relative to the eye: origin
// eye + o, direction dir (not unit), and the factor that turns the ray's
// parameter into depth (1 + q for paraboloids, else 1).  False when the
// centre lies outside a paraboloid's disc.
bool centre_ray(uint sub, int kind, uint col, uint row, out real3 o, out real3 dir, out real depth_per_t)
{
    real x = r_add(r_u(col), R_HALF), y = r_add(r_u(row), R_HALF);
    real3 u = sd3(sub, MLOD_IF_S_RIGHT), v = sd3(sub, MLOD_IF_S_UP), w = sd3(sub, MLOD_IF_S_FORWARD);
    real left = sd(sub, MLOD_IF_S_X), top = sd(sub, MLOD_IF_S_Y);
    real width = sd(sub, MLOD_IF_S_WIDTH), height = sd(sub, MLOD_IF_S_HEIGHT);
    real px, py, tw = R_ZERO;
    bool parab = kind == MLOD_IF_KIND_PARABOLOID, ortho = kind == MLOD_IF_KIND_ORTHOGRAPHIC;
    depth_per_t = R_ONE;
    // the C twin's three branches with one copy of each step (ROLLED):
    // perspective and orthographic, (x - mid) times 1 / scale per axis
    // (perspective: one scale for both); a paraboloid, (x - left) times
    // 2 / width, less 1, as 2 px, 2 py
    if (!parab) {
        real inv[2];
        ROLLED for (uint k = 0u; k < 2u; k++)
            inv[k] = r_div(R_ONE, sd(sub, !ortho ? MLOD_IF_S_SCALE : (k == 0u ? MLOD_IF_S_SCALE_X : MLOD_IF_S_SCALE_Y)));
        px = r_mul(r_sub(x, r_add(left, r_mul(R_HALF, width))), inv[0]);
        py = r_mul(r_sub(r_add(top, r_mul(R_HALF, height)), y), inv[1]);
    } else {
        px = r_sub(r_mul(r_sub(x, left), r_div(R_TWO, width)), R_ONE);
        py = r_sub(R_ONE, r_mul(r_sub(y, top), r_div(R_TWO, height)));
        real q = r_add(r_mul(px, px), r_mul(py, py));
        if (!r_le(q, R_ONE)) {
            o = real3(R_ZERO, R_ZERO, R_ZERO);
            dir = w;
            return false;
        }
        px = r_mul(R_TWO, px);
        py = r_mul(R_TWO, py);
        tw = r_sub(R_ONE, q);
        depth_per_t = r_add(R_ONE, q);
    }
    // perspective: dir = (w + px u) + py v; orthographic: o = px u + py v,
    // dir = w; paraboloid: dir = (2 px u + 2 py v) + (1 - q) w
    real oc[3], dc[3];
    ROLLED for (uint k = 0u; k < 3u; k++) {
        real pu = r_mul(px, r3_at(u, k)), pv = r_mul(py, r3_at(v, k)), wk = r3_at(w, k);
        real sum = r_add(kind == MLOD_IF_KIND_PERSPECTIVE ? wk : pu, kind == MLOD_IF_KIND_PERSPECTIVE ? pu : pv);
        if (kind == MLOD_IF_KIND_PERSPECTIVE) sum = r_add(sum, pv);
        else if (parab) sum = r_add(sum, r_mul(tw, wk));
        oc[k] = ortho ? sum : R_ZERO;
        dc[k] = ortho ? wk : sum;
    }
    o = real3(oc[0], oc[1], oc[2]);
    dir = real3(dc[0], dc[1], dc[2]);
    return true;
}

// Whether the node draws as a tangent disc (mlod__has_plane): its cone's
// half-angle is below pi.
bool has_plane(vec4 cone) { return r_lt(r_f(cone.w), R_PI); }

// C twin: mlod__plane_hit
// Where the ray eye + o + t dir meets the plane through the sphere's
// centre (x = centre - eye) normal to the cone's axis: t; whether that
// point lies within rr of the centre, in front of the eye (ortho: anywhere
// on the line).
bool plane_hit(real3 x, vec4 cone, real3 o, real3 dir, real rr, bool ortho, out real t)
{
    real3 n = r3_f(cone.xyz);
    t = r_div(dot3(n, r3_sub(x, o)), dot3(n, dir));
    real ec[3];
    ROLLED for (uint k = 0u; k < 3u; k++) ec[k] = r_sub(r_add(r3_at(o, k), r_mul(t, r3_at(dir, k))), r3_at(x, k));
    real3 e = real3(ec[0], ec[1], ec[2]);
    return (ortho || r_gt(t, R_ZERO)) && r_le(dot3(e, e), r_mul(rr, rr));
}

// C twin: mlod__tangent_hit
// MLOD_SPLAT_TANGENT at tile pixel (col, row) of the view's sub-projection
// s: whether the ray through its centre meets the node's tangent disc (its
// radius times ds) and, if so, the depth there (t times the depth per
// unit of t).
bool tangent_hit(uint view, uint s, vec4 sphere, vec4 cone, float ds, uint col, uint row, out float depth)
{
    uint sub = sub_base(view, s);
    int kind = sub_kind(sub);
    real3 o, dir;
    real t, per_t;
    depth = 0.0;
    if (!centre_ray(sub, kind, col, row, o, dir, per_t)) return false;
    real3 x = r3_sub(r3_f(sphere.xyz), vd3(view, MLOD_IF_V_EYE));
    if (!plane_hit(x, cone, o, dir, r_mul(r_f(sphere.w), r_f(ds)), kind == MLOD_IF_KIND_ORTHOGRAPHIC, t)) return false;
    depth = r_to_f(r_mul(t, per_t));
    return true;
}

#ifdef MLOD_MEGAVIEWS
// ------------------------------------------------------------ MegaViews --
//
// The pair test of mlod_megaviews_render.  The includer (mv_layout.glsl)
// declares besides the scene tree's buffers the view tree's eye_spheres[]
// and eye_cones[], the level block level[] (half fields of view as float
// bits at ctl.off_fovs) and the control block ctl.

#define MV_2M30 RK(0x3E100000u, 0x00000000u, 9.3132257461547852e-10LF) // 2^-30
#define MV_1E12 RK(0x3D719799u, 0x812DEA11u, 1e-12LF)
#define MV_PAIR_CULL 0u
#define MV_PAIR_DRAW 1u
#define MV_PAIR_DRAW_LEAF 2u
#define MV_PAIR_SPLIT_SCENE 3u
#define MV_PAIR_SPLIT_VIEW 4u

// C twin: mlod__outside_cone
// (its arc tangents from the caller, pair_action: angle, the angle of x to
// the cone's axis, and spread_g = atan2(g, sqrt((d - g) (d + g))))
bool outside_cone(real d, real g, vec4 cone, real theta, real margin, real angle, real spread_g)
{
    if (!r_gt(d, g) || !r_lt(r_f(cone.w), R_PI)) return false;
    real reach = r_add(r_add(r_add(r_f(cone.w), theta), spread_g), margin);
    if (!r_lt(reach, R_PI)) return false;
    return r_gt(angle, reach);
}

// C twin: mlod__within_cone
// (its arc tangents from the caller, pair_action: angle, of x to the
// cone's axis, turn = atan2(rho, sqrt((d - rho) (d + rho))) and seen =
// atan2(r, sqrt((d + rho - r) (d + rho + r))), taken where r > 0)
bool within_cone(real d, real r, real rho, real spread, real limit, real angle, real turn, real seen)
{
    if (!r_gt(d, rho)) return false;
    real seen_r = r_gt(r, R_ZERO) ? seen : R_ZERO;
    return r_le(r_add(r_add(r_add(angle, spread), turn), MV_2M30), r_add(limit, seen_r));
}

// C twin: mlod__map_coords
// (the maps' frame: the right, up and forward of frame 0's first
// sub-projection, MLOD_IF_S_RIGHT, _UP, _FORWARD 3 apart; x itself where
// they are the default's, (-1, 0, 0), (0, 1, 0), (0, 0, 1): the C job's
// `oriented` 0.  One loop, not unrolled: one copy of dot3, which matters
// where doubles are emulated; its products are not read by default.)
real3 map_coords(real3 x)
{
    uint sub = sub_base(0u, 0u);
    real m[3];
    bool standard = true;
    [[dont_unroll]] for (uint k = 0u; k < 3u; k++) {
        real3 a = sd3(sub, MLOD_IF_S_RIGHT + 3u * k);
        standard = standard && r_eq(a.x, k == 0u ? r_neg(R_ONE) : R_ZERO) && r_eq(a.y, k == 1u ? R_ONE : R_ZERO) &&
                   r_eq(a.z, k == 2u ? R_ONE : R_ZERO);
        m[k] = dot3(x, a);
    }
    return standard ? x : real3(m[0], m[1], m[2]);
}

// C twin: mlod__ball_diameters
void ball_diameters(real S, real3 x, real d, real r, real rho, out real cmax, out real cmin)
{
    real closest = r_sub(d, rho), farthest = r_add(d, rho), least_near = r_inf(), least_far = r_inf();
    bool some = false, every = false;
    cmax = R_ZERO;
    cmin = R_ZERO;
    if (!r_gt(farthest, r)) {
        cmax = r_inf();
        cmin = r_inf();
        return;
    }
    real t_closest = r_gt(closest, r) ? r_sqrt(r_mul(r_sub(closest, r), r_add(closest, r))) : R_ZERO;
    real t_farthest = r_sqrt(r_mul(r_sub(farthest, r), r_add(farthest, r)));
    for (int h = 0; h < 2; h++) {
        real xw = h != 0 ? r_neg(x.z) : x.z;
        if (r_ge(r_add(r_add(xw, rho), r), R_ZERO)) {
            real den = r_add(r_sub(xw, rho), t_closest);
            some = true;
            if (!r_gt(closest, r) || !r_gt(den, R_ZERO)) den = R_ZERO;
            if (r_lt(den, least_near)) least_near = den;
        }
        if (r_ge(r_add(r_sub(xw, rho), r), R_ZERO)) {
            real den = r_add(r_add(xw, rho), t_farthest);
            every = true;
            if (!r_gt(den, R_ZERO)) den = R_ZERO;
            if (r_lt(den, least_far)) least_far = den;
        }
    }
    if (some) cmax = r_gt(least_near, R_ZERO) ? r_div(r_mul(r_mul(S, R_TWO), r), least_near) : r_inf();
    if (every) cmin = r_gt(least_far, R_ZERO) ? r_div(r_mul(r_mul(S, R_TWO), r), least_far) : r_inf();
    cmax = r_mul(cmax, RK(0x3FF00000u, 0x00001000u, 1.0000000000009095LF)); // 1 + 2^-40
    cmin = r_mul(cmin, RK(0x3FEFFFFFu, 0xFFFFE000u, 0.99999999999909051LF)); // 1 - 2^-40
}

// C twin: mlod__ball_motion
real ball_motion(real S, real3 x, real d, real r, real rho)
{
    real closest = r_sub(d, r), g = r_add(r, rho), least = r_inf();
    if (r_eq(rho, R_ZERO)) return R_ZERO;
    if (!r_gt(closest, rho) || !r_gt(d, g)) return r_inf();
    real turn = r_div(rho, r_sqrt(r_mul(r_sub(closest, rho), r_add(closest, rho))));
    real sin_b = r_div(g, d);
    real cos_b = r_div(r_sqrt(r_mul(r_sub(d, g), r_add(d, g))), d);
    real sin_phi = r_div(r_sqrt(r_add(r_mul(x.x, x.x), r_mul(x.y, x.y))), d);
    real cos_w = r_div(x.z, d);
    for (int h = 0; h < 2; h++) {
        real cos_phi = h != 0 ? r_neg(cos_w) : cos_w;
        if (r_lt(r_add(r_mul(cos_phi, cos_b), r_mul(sin_phi, sin_b)), r_neg(MV_1E12))) continue;
        real sin_sum = r_add(r_mul(sin_phi, cos_b), r_mul(cos_phi, sin_b));
        real cos_sum = r_sub(r_mul(cos_phi, cos_b), r_mul(sin_phi, sin_b));
        if (!(r_gt(sin_sum, MV_1E12) || r_gt(cos_sum, R_ZERO)) || !r_gt(r_add(R_ONE, cos_sum), R_ZERO)) return r_inf();
        if (r_lt(r_add(R_ONE, cos_sum), least)) least = r_add(R_ONE, cos_sum);
    }
    return r_lt(least, r_inf()) ? r_mul(r_div(r_mul(S, turn), least), RK(0x3FF00001u, 0x00000000u, 1.0000009536743164LF))
                                : R_ZERO; // (1 + 2^-20)
}

// C twin: mlod__below_floor (the floors at ctl.off_floors, two per view node; none where -inf)
bool below_floor(uint v, real3 x, real d, real r, real radius, real3 va)
{
    float fl = uintBitsToFloat(level[ctl.off_floors + 2u * v]);
    real len = length_d(va);
    if (!(fl >= -3.40282347e38) || !r_gt(len, R_ZERO)) return false;
    real floor_h = r_f(fl), spread = r_f(uintBitsToFloat(level[ctl.off_floors + 2u * v + 1u]));
    real g = r_add(r, radius);
    real up = r_div(dot3(x, va), len);
    real high = r_add(r_sub(r_add(up, r), floor_h), r_mul(r_add(d, g), spread));
    return r_lt(r_add(high, r_mul(r_add(r_add(d, g), r_abs(floor_h)), MV_2M30)), R_ZERO);
}

// C twin: mlod__pair_action
// What the traversal does with (scene node s, view node v), by the exact
// tests alone: the C function's mlod__surely_* shortcuts answer only where
// their margins (1e-9, 1e-8) put the answer beyond the exact tests' doubt,
// so both give the same action.  A view leaf or group classifies with
// frame 0 or 1 (views[]: the map's frame, with and without back-face
// culling) moved to its centre.  The five arc tangents the cone tests take
// (mlod__angle's two among them) are computed first, in one loop that is
// not unrolled: one copy of the arithmetic, which matters where doubles
// are emulated (each operation inlined where it is written); those a test
// does not reach are not read.
uint pair_action(uint v, uint s)
{
    vec4 vs = eye_spheres[v];
    real3 centre = r3_f(vs.xyz);
    real radius = r_f(vs.w);
    real epsilon = r_load(ctl.epsilon), delta = r_load(ctl.delta), group_radius = r_load(ctl.group_radius);
    bool leaf = v >= ctl.eye_leaves - 1u;
    bool group = !leaf && r_gt(group_radius, R_ZERO) && r_le(radius, group_radius);
    bool has_cone = ctl.has_view_cones != 0u;
    bool backfaces = (ctl.flags & 1u) != 0u && ctl.has_cones != 0u;
    vec4 vcone = has_cone ? eye_cones[v] : vec4(0.0);
    vec4 cone = backfaces ? cones[s] : vec4(0.0);
    real least_fov = R_PI, most_fov = R_PI;
    if (ctl.has_fovs != 0u) {
        least_fov = r_f(uintBitsToFloat(level[ctl.off_fovs + 2u * v]));
        most_fov = r_f(uintBitsToFloat(level[ctl.off_fovs + 2u * v + 1u]));
    }
    vec4 sphere = spheres[s];
    real r = r_f(sphere.w);
    real3 x = r3_sub(r3_f(sphere.xyz), centre);
    real3 away = real3(r_neg(x.x), r_neg(x.y), r_neg(x.z));
    real d = length_d(x), g = r_add(r, radius), reach = r_add(d, radius);
    // atan2 arguments: angle(x, view axis), angle(away, normal axis), the sphere grown by the ball,
    // the ball's turn, the sphere seen from the farthest eye
    real3 va = r3_f(vcone.xyz), na = r3_f(cone.xyz);
    real ys[5], xs[5], at[5];
    ys[0] = length_d(cross_d(x, va));
    xs[0] = dot3(x, va);
    ys[1] = length_d(cross_d(away, na));
    xs[1] = dot3(away, na);
    ys[2] = g;
    xs[2] = r_sqrt(r_mul(r_sub(d, g), r_add(d, g)));
    ys[3] = radius;
    xs[3] = r_sqrt(r_mul(r_sub(d, radius), r_add(d, radius)));
    ys[4] = r;
    xs[4] = r_sqrt(r_mul(r_sub(reach, r), r_add(reach, r)));
    [[dont_unroll]] for (uint k = 0u; k < 5u; k++) at[k] = atan2_d(ys[k], xs[k]);
    if (has_cone && outside_cone(d, g, vcone, most_fov, leaf ? R_ZERO : MV_2M30, at[0], at[2])) return MV_PAIR_CULL;
    if (!leaf && has_cone && ctl.has_fovs != 0u && below_floor(v, x, d, r, radius, va)) return MV_PAIR_CULL;
    real half_pi = r_mul(R_HALF, R_PI);
    if (!leaf && backfaces && outside_cone(d, g, cone, half_pi, MV_2M30, at[1], at[2])) return MV_PAIR_CULL;
    if (leaf || group) { // (a leaf before the back-face test, which it leaves to its classification)
        mv_eye = centre;
        uint st = classify(leaf ? 0u : 1u, s, epsilon, ctl.scene_leaves);
        if (leaf && st == MLOD_IF_STATUS_CULLED) return MV_PAIR_CULL;
        return st == MLOD_IF_STATUS_COARSE ? MV_PAIR_SPLIT_SCENE : MV_PAIR_DRAW;
    }
    real S = r_load(ctl.scale), cmax, cmin;
    real3 xm = map_coords(x);
    ball_diameters(S, xm, d, r, radius, cmax, cmin);
    if (r_le(cmax, epsilon) || s >= ctl.scene_leaves - 1u) {
        if (!r_le(ball_motion(S, xm, d, r, radius), delta)) return MV_PAIR_SPLIT_VIEW;
        if (has_cone && r_eq(delta, R_ZERO) &&
            !within_cone(d, r, radius, r_f(vcone.w), least_fov, at[0], at[3], at[4]))
            return MV_PAIR_SPLIT_VIEW;
        if (backfaces && r_lt(r_f(cone.w), half_pi) &&
            !within_cone(d, r, radius, R_ZERO, r_add(half_pi, r_f(cone.w)), at[1], at[3], at[4]))
            return MV_PAIR_SPLIT_VIEW;
        return r_le(cmax, epsilon) ? MV_PAIR_DRAW : MV_PAIR_DRAW_LEAF;
    }
    if (r_gt(cmin, epsilon)) return MV_PAIR_SPLIT_SCENE;
    if (r_gt(delta, R_ZERO)) {
        vec4 left = spheres[2u * s + 1u], right = spheres[2u * s + 2u];
        if (r_ge(r_f(left.w < right.w ? left.w : right.w), radius)) return MV_PAIR_SPLIT_SCENE;
    }
    return MV_PAIR_SPLIT_VIEW;
}

// C twin: mlod__node_distance
float node_distance(uint node, real3 centre)
{
    real3 x = r3_sub(r3_f(spheres[node].xyz), centre);
    return r_to_f(length_d(x));
}

// C twin: mlod__remeasure
// A scene node's depth at pixel (col, row) of the map at mv_eye (frame 0,
// its two halves' columns [0, R) and [R, 2 R), R = ctl.resolution), as the
// fusion measures again a node drawn into an ancestor's map: sphere discs
// (or no cone axis, or no ray), the distance d to its centre; tangent
// discs, the depth where the pixel centre's ray meets its tangent disc of
// the sphere's radius, and where it misses, that depth on the plane
// clamped to [d - r, d + r] (d + r with the plane behind the eye).
float remeasure(uint node, uint col, uint row, bool tangent)
{
    vec4 sphere = spheres[node];
    uint sub = sub_base(0u, col < ctl.resolution ? 0u : 1u);
    real3 x = r3_sub(r3_f(sphere.xyz), vd3(0u, MLOD_IF_V_EYE)), o, dir;
    real d = length_d(x), t, per_t;
    if (!tangent) return r_to_f(d);
    vec4 cone = cones[node];
    if (!has_plane(cone) || !centre_ray(sub, sub_kind(sub), col, row, o, dir, per_t)) return r_to_f(d);
    if (plane_hit(x, cone, o, dir, r_f(sphere.w), false, t)) return r_to_f(r_mul(t, per_t));
    real lo = r_sub(d, r_f(sphere.w)), hi = r_add(d, r_f(sphere.w));
    real v = r_gt(t, R_ZERO) ? r_mul(t, per_t) : hi;
    if (!r_ge(v, lo)) v = lo;
    if (r_gt(v, hi)) v = hi;
    return r_to_f(v);
}

#endif // MLOD_MEGAVIEWS

#endif // MLOD_NO_VIEWS
