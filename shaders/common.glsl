// shaders/common.glsl - the criterion, culling and image disc of manylods.h,
// for the compute shaders of manylods_vk.h.
//
// Each function here is the twin of the C function its "C twin:" line names
// in manylods.h, which names it back ("GLSL twin:"), in the same order
// (tests/check_twins.sh checks both), operation for operation, in double
// precision, every temporary `precise` (no fused multiply-add): on a
// device whose double arithmetic is IEEE (lavapipe; most desktop GPUs) the
// two compute the same bits, and the CPU and Vulkan cuts are equal node for
// node.  Change one, change both.
//
// The includer declares, before including this file:
//   vec4 spheres[]  (x, y, z, r per node)   in a buffer named tree_spheres
//   vec4 cones[]    (axis, half-angle)      in a buffer named tree_cones
//   double views[]  (MLOD_IF_VIEW_STRIDE doubles per view: interface.h)
// and a macro MLOD_HAS_CONES (a bool expression) - or defines MLOD_NO_VIEWS
// (the refit shaders) and gets only the functions that need no view.

#define MLOD_PI 3.14159265358979323846LF

// The view layout (MLOD_IF_V_*), kind and status codes come from
// interface.h, which the layout files include first.

#ifndef MLOD_NO_VIEWS
// A view's field (MLOD_IF_V_*), and the first double of its sub-projection
// s, whose fields (MLOD_IF_S_*) sd and sd3 read.
double vd(uint view, uint field) { return views[view * MLOD_IF_VIEW_STRIDE + field]; }
dvec3 vd3(uint view, uint field) { return dvec3(vd(view, field), vd(view, field + 1), vd(view, field + 2)); }
uint sub_count(uint view) { return uint(vd(view, MLOD_IF_V_SUB_COUNT)); }
uint sub_base(uint view, uint s) { return view * MLOD_IF_VIEW_STRIDE + MLOD_IF_V_SUBS + s * MLOD_IF_SUB_STRIDE; }
double sd(uint sub, uint field) { return views[sub + field]; }
dvec3 sd3(uint sub, uint field) { return dvec3(sd(sub, field), sd(sub, field + 1), sd(sub, field + 2)); }
int sub_kind(uint sub) { return int(sd(sub, MLOD_IF_S_KIND)); }

#endif // MLOD_NO_VIEWS

// ---------------------------- helpers and merges (refit needs them too) --

// C twin: mlod__float_up
// The smallest float >= x (x >= 0)
float float_up(double x)
{
    float f = float(x);
    if (double(f) < x) f = uintBitsToFloat(floatBitsToUint(f) + 1u);
    return f;
}

// C twin: mlod__dot3
double dot3(dvec3 a, dvec3 b)
{
    precise double s = a.x * b.x + a.y * b.y + a.z * b.z;
    return s;
}

// C twin: mlod__cross3
dvec3 cross_d(dvec3 a, dvec3 b)
{
    precise double x = a.y * b.z - a.z * b.y;
    precise double y = a.z * b.x - a.x * b.z;
    precise double z = a.x * b.y - a.y * b.x;
    return dvec3(x, y, z);
}

// C twin: mlod__length3
double length_d(dvec3 a) { return sqrt(dot3(a, a)); }

// C twin: mlod__distance_f
double distance_f(vec3 a, vec3 b)
{
    precise double dx = double(a.x) - double(b.x);
    precise double dy = double(a.y) - double(b.y);
    precise double dz = double(a.z) - double(b.z);
    precise double d = sqrt(dx * dx + dy * dy + dz * dz);
    return d;
}

// C twin: mlod__cos_even
// (and the five arrays after it: the same literals)
const double COS_EVEN[6] = double[](
    4.110317623312165e-19LF, 4.779477332387385e-14LF, 2.08767569878681e-09LF, 2.48015873015873e-05LF,
    0.041666666666666664LF, 1.0LF);

const double COS_ODD[6] = double[](
    8.896791392450574e-22LF, 1.5619206968586225e-16LF, 1.1470745597729725e-11LF, 2.755731922398589e-07LF,
    0.001388888888888889LF, 0.5LF);

const double SIN_EVEN[6] = double[](
    1.9572941063391263e-20LF, 2.8114572543455206e-15LF, 1.6059043836821613e-10LF, 2.7557319223985893e-06LF,
    0.008333333333333333LF, 1.0LF);

const double SIN_ODD[5] = double[](
    8.22063524662433e-18LF, 7.647163731819816e-13LF, 2.505210838544172e-08LF, 0.0001984126984126984LF,
    0.16666666666666666LF);

const double ATAN_EVEN[6] = double[](
    0.047619047619047616LF, 0.058823529411764705LF, 0.07692307692307693LF, 0.1111111111111111LF, 0.2LF, 1.0LF);

const double ATAN_ODD[6] = double[](
    0.043478260869565216LF, 0.05263157894736842LF, 0.06666666666666667LF, 0.09090909090909091LF,
    0.14285714285714285LF, 0.3333333333333333LF);

// C twin: mlod__sin_cos
void sin_cos(double a, out double sin_a, out double cos_a)
{
    precise double x = a - 1.57079632679489661923LF;
    precise double y = x * x;
    precise double z = y * y;
    precise double ce = COS_EVEN[0];
    precise double co = COS_ODD[0];
    precise double se = SIN_EVEN[0];
    precise double so = SIN_ODD[0];
    [[unroll]] for (int k = 1; k < 6; k++) {
        ce = COS_EVEN[k] + z * ce;
        co = COS_ODD[k] + z * co;
        se = SIN_EVEN[k] + z * se;
    }
    [[unroll]] for (int k = 1; k < 5; k++) so = SIN_ODD[k] + z * so;
    sin_a = ce - y * co;
    precise double sine = se - y * so;
    cos_a = -x * sine;
}

// C twin: mlod__atan2
// (y >= 0)
double atan2_d(double y, double x)
{
    precise double ax = abs(x);
    bool swap = y > ax;
    if (!(y > 0.0LF) && !(ax > 0.0LF)) return x < 0.0LF ? MLOD_PI : 0.0LF;
    precise double t = swap ? ax / y : y / ax;
    precise double u = t;
    precise double base = 0.0LF;
    if (t > 0.41421356237309504880LF) {
        u = (t - 1.0LF) / (t + 1.0LF);
        base = 0.78539816339744830962LF;
    }
    precise double u2 = u * u;
    precise double w = u2 * u2;
    precise double even = ATAN_EVEN[0];
    precise double odd = ATAN_ODD[0];
    [[unroll]] for (int k = 1; k < 6; k++) {
        even = ATAN_EVEN[k] + w * even;
        odd = ATAN_ODD[k] + w * odd;
    }
    precise double a = base + u * (even - u2 * odd);
    if (swap) a = 1.57079632679489661923LF - a;
    precise double result = x < 0.0LF ? MLOD_PI - a : a;
    return result;
}

// C twin: mlod__angle
double angle_d(dvec3 a, dvec3 b) { return atan2_d(length_d(cross_d(a, b)), dot3(a, b)); }

// C twin: mlod__sphere_enclose
vec4 sphere_enclose(vec4 a, vec4 b)
{
    precise double d = distance_f(a.xyz, b.xyz);
    double ra = double(a.w), rb = double(b.w);
    vec3 c;
    if (d + rb <= ra) {
        c = a.xyz;
    } else if (d + ra <= rb) {
        c = b.xyz;
    } else {
        precise double t = ((d + ra + rb) * 0.5LF - ra) / d;
        precise double cx = double(a.x) + (double(b.x) - double(a.x)) * t;
        precise double cy = double(a.y) + (double(b.y) - double(a.y)) * t;
        precise double cz = double(a.z) + (double(b.z) - double(a.z)) * t;
        c = vec3(float(cx), float(cy), float(cz));
    }
    precise double need_a = distance_f(c, a.xyz) + ra;
    precise double need_b = distance_f(c, b.xyz) + rb;
    precise double need = (need_a > need_b ? need_a : need_b) * (1.0LF + 1.0LF / 1048576.0LF) *
                          (1.0LF + 1.0LF / 1125899906842624.0LF);
    return vec4(c, float_up(need));
}

// C twin: mlod__cone_full
vec4 cone_full(vec3 axis) { return vec4(axis, float_up(MLOD_PI)); }

// C twin: mlod__cone_enclose
// (the stored axis is within MLOD__CONE_ROUNDING, 2^-22
// rad, of the merged one; nearly opposite axes, closer than
// MLOD__CONE_OPPOSITE, measure the stored axis against both cones)
vec4 cone_enclose(vec4 a, vec4 b)
{
    if (double(a.w) >= MLOD_PI || double(b.w) >= MLOD_PI) return cone_full(a.xyz);
    dvec3 A = dvec3(a.xyz), B = dvec3(b.xyz), X;
    precise double theta = angle_d(A, B);
    precise double alpha;
    bool measure = false;
    if (theta + double(b.w) <= double(a.w)) {
        X = A;
        alpha = double(a.w);
    } else if (theta + double(a.w) <= double(b.w)) {
        X = B;
        alpha = double(b.w);
    } else {
        alpha = (theta + double(a.w) + double(b.w)) * 0.5LF;
        if (alpha >= MLOD_PI) return cone_full(a.xyz);
        precise double phi = alpha - double(a.w);
        double sin_phi, cos_phi;
        sin_cos(phi, sin_phi, cos_phi);
        precise double la = length_d(A);
        precise dvec3 An = dvec3(A.x / la, A.y / la, A.z / la);
        precise double ab = dot3(An, B);
        precise dvec3 t = dvec3(B.x - An.x * ab, B.y - An.y * ab, B.z - An.z * ab);
        precise double len = length_d(t);
        measure = !(len >= 1.0LF / 1024.0LF) && !(ab > 0.0LF);
        if (!(len > 0.0LF)) {
            dvec3 helper = dvec3(0.0LF);
            if (abs(An.x) < 0.5LF) helper.x = 1.0LF; else helper.y = 1.0LF;
            t = cross_d(An, helper);
            len = length_d(t);
        }
        precise dvec3 Xr = dvec3(An.x * cos_phi + t.x / len * sin_phi, An.y * cos_phi + t.y / len * sin_phi,
                                 An.z * cos_phi + t.z / len * sin_phi);
        X = Xr;
    }
    precise double lx = length_d(X);
    vec3 axis = vec3(float(X.x / lx), float(X.y / lx), float(X.z / lx));
    // +0 for a zero component however it was reached: the compiler may fold
    // away the terms that decide the sign of a zero (x + 0 -> x), the CPU
    // does not; the test on the bits cannot be folded
    [[unroll]] for (int k = 0; k < 3; k++)
        if (floatBitsToUint(axis[k]) == 0x80000000u) axis[k] = 0.0;
    if (measure) {
        dvec3 S = dvec3(axis);
        precise double need_a = angle_d(S, A) + double(a.w);
        precise double need_b = angle_d(S, B) + double(b.w);
        alpha = need_a > need_b ? need_a : need_b;
    }
    precise double stored = alpha + 1.0LF / 4194304.0LF + 1.0LF / 1048576.0LF;
    if (stored >= MLOD_PI) return cone_full(axis);
    return vec4(axis, float_up(stored));
}

// C twin: mlod__depth_of
uint depth_of(uint64_t node)
{
    uint64_t x = node + 1UL;
    uint hi = uint(x >> 32);
    return hi != 0u ? 32u + uint(findMSB(hi)) : uint(findMSB(uint(x)));
}

// C twin: mlod__leaves_below
// Leaves under node i of the tree of n leaves
uint leaves_below(uint i, uint n)
{
    uint64_t last = 2UL * uint64_t(n) - 2UL;
    uint k = depth_of(uint64_t(i)), deepest = depth_of(last);
    uint span = deepest - k;
    uint64_t lo = ((uint64_t(i) + 1UL) << span) - 1UL, hi = ((uint64_t(i) + 2UL) << span) - 2UL;
    uint64_t at_deepest = lo > last ? 0UL : (hi < last ? hi : last) - lo + 1UL;
    uint64_t nodes = ((1UL << span) - 1UL) + at_deepest;
    return uint((nodes + 1UL) / 2UL);
}

// ------------------------------------------------ exact plane predicate --

// C twin: mlod__two_sum
void two_sum(double a, double b, out double s, out double err)
{
    precise double sum = a + b;
    precise double bv = sum - a;
    precise double av = sum - bv;
    precise double e = (a - av) + (b - bv);
    s = sum;
    err = e;
}

// C twin: mlod__split
void split_double(double a, out double hi, out double lo)
{
    precise double c = 134217729.0LF * a;
    precise double big = c - a;
    precise double h = c - big;
    precise double l = a - h;
    hi = h;
    lo = l;
}

// C twin: mlod__two_product
void two_product(double a, double b, out double p, out double err)
{
    precise double prod = a * b;
    double ah, al, bh, bl;
    split_double(a, ah, al);
    split_double(b, bh, bl);
    precise double e = al * bl - (((prod - ah * bh) - al * bh) - ah * bl);
    p = prod;
    err = e;
}

// C twin: mlod__exact_sign
// For the 9 terms of plane_outside: the same exact sign by the same
// expansion growth, without its zero elimination so that every
// index is a constant once the loops unroll (lavapipe then keeps the
// expansion in registers; the dynamic version costs every evaluation a
// factor of two even though it rarely runs).
int exact_sign9(double t[9])
{
    double e[9];
    [[unroll]] for (int i = 0; i < 9; i++) {
        double q = t[i], h;
        [[unroll]] for (int j = 0; j < i; j++) {
            two_sum(q, e[j], q, h);
            e[j] = h;
        }
        e[i] = q;
    }
    int sign = 0;
    [[unroll]] for (int i = 0; i < 9; i++)
        if (e[i] != 0.0LF) sign = e[i] > 0.0LF ? 1 : -1; /* the largest nonzero component decides */
    return sign;
}

#ifndef MLOD_NO_VIEWS
// C twin: mlod__outside
// Is the sphere wholly outside the half-space at views[base]
// (n.c + l r < k, exactly)?
bool plane_outside(uint base, vec4 sphere)
{
    double n0 = views[base], n1 = views[base + 1], n2 = views[base + 2], k = views[base + 3], l = views[base + 4];
    precise double t0 = n0 * double(sphere.x);
    precise double t1 = n1 * double(sphere.y);
    precise double t2 = n2 * double(sphere.z);
    precise double t3 = l * double(sphere.w);
    precise double s = t0 + t1 + t2 + t3 - k;
    precise double bound = (abs(t0) + abs(t1) + abs(t2) + abs(t3) + abs(k)) * (1.0LF / 281474976710656.0LF);
    // The exact path runs where the filter cannot decide, which is rare;
    // asking the whole subgroup first keeps SIMD devices (lavapipe runs
    // every lane of a divergent branch) from paying for it every time.
    if (!subgroupAny(!(s < -bound) && !(s > bound))) return s < -bound;
    if (s < -bound) return true;
    if (s > bound) return false;
    double t[9];
    two_product(n0, double(sphere.x), t[0], t[1]);
    two_product(n1, double(sphere.y), t[2], t[3]);
    two_product(n2, double(sphere.z), t[4], t[5]);
    two_product(l, double(sphere.w), t[6], t[7]);
    t[8] = -k;
    return exact_sign9(t) < 0;
}

// ------------------------------------------------------------ criterion --

// C twin: mlod__backfacing
bool backfacing(uint view, dvec3 x, double d2, double r, vec4 cone)
{
    double c0 = double(cone.x), c1 = double(cone.y), c2 = double(cone.z);
    if (!(double(cone.w) < 0.5LF * MLOD_PI)) return false;
    double sa, ca;
    if (sub_kind(sub_base(view, 0u)) == MLOD_IF_KIND_ORTHOGRAPHIC) {
        dvec3 w = sd3(sub_base(view, 0u), MLOD_IF_S_FORWARD);
        precise double away = -(c0 * w.x + c1 * w.y + c2 * w.z);
        if (!(away < 0.0LF)) return false;
        precise double len = sqrt(c0 * c0 + c1 * c1 + c2 * c2);
        sin_cos(double(cone.w), sa, ca);
        precise double along = away / len;
        return ca > 0.0LF && along < -sa;
    }
    if (d2 <= r * r) return false;
    precise double away = -(c0 * x.x + c1 * x.y + c2 * x.z);
    if (!(away < 0.0LF)) return false;
    precise double len = sqrt(c0 * c0 + c1 * c1 + c2 * c2);
    precise double tangent = sqrt(d2 - r * r);
    sin_cos(double(cone.w), sa, ca);
    precise double lhs = ca * tangent - sa * r;
    precise double rhs = -(sa * tangent + ca * r);
    precise double along = away / len;
    return lhs > 0.0LF && along < rhs;
}

#endif // MLOD_NO_VIEWS

// C twin: mlod__paraboloid_diameter
double paraboloid_diameter(double r, double xw, double tangent)
{
    precise double den = xw + tangent;
    precise double c = 2.0LF * r / den;
    return den > 0.0LF ? c : 1.0LF / 0.0LF;
}

#ifndef MLOD_NO_VIEWS
// C twin: mlod__sub_diameter
// The diameter of the sphere's image in the sub-projection at views[sub],
// in pixels (tangent: 0 for orthographic views).
double sub_diameter(uint sub, dvec3 x, double d2, double r, double tangent)
{
    precise double xw = dot3(x, sd3(sub, MLOD_IF_S_FORWARD));
    double scale = sd(sub, MLOD_IF_S_SCALE);
    int kind = sub_kind(sub);
    if (kind == MLOD_IF_KIND_PERSPECTIVE) {
        if (xw <= r) return 1.0LF / 0.0LF;
        precise double c = scale * 2.0LF * r * tangent / ((xw - r) * (xw + r));
        return c;
    }
    if (kind == MLOD_IF_KIND_PARABOLOID) {
        if (d2 <= r * r) return 1.0LF / 0.0LF;
        precise double c = scale * paraboloid_diameter(r, xw, tangent);
        return c;
    }
    precise double c = scale * 2.0LF * r;
    return c;
}

// C twin: mlod__reached
// Which sub-projections the sphere reaches: bit s for sub-projection s.
uint reached_subs(uint view, vec4 sphere)
{
    uint reached = 0u, count = sub_count(view);
    for (uint s = 0u; s < count; s++) {
        uint sub = sub_base(view, s), planes = uint(sd(sub, MLOD_IF_S_PLANE_COUNT));
        bool inside = true;
        for (uint k = 0u; k < planes && inside; k++)
            if (plane_outside(sub + MLOD_IF_S_PLANES + 5u * k, sphere)) inside = false;
        if (inside) reached |= 1u << s;
    }
    return reached;
}

// C twin: mlod__evaluate
// c(node, view) in pixels; culled set when culled.
double evaluate(uint view, vec4 sphere, bool use_cone, vec4 cone, out bool culled)
{
    // one sub-projection: its planes first; several: the back faces first
    // (the C twin's order; either culls the same nodes)
    uint count = sub_count(view), reached = 0u;
    culled = true;
    if (count == 1u && (reached = reached_subs(view, sphere)) == 0u) return 0.0LF;
    dvec3 e = vd3(view, MLOD_IF_V_EYE);
    precise dvec3 x = dvec3(double(sphere.x) - e.x, double(sphere.y) - e.y, double(sphere.z) - e.z);
    precise double d2 = dot3(x, x);
    precise double r = double(sphere.w);
    precise double t2 = d2 - r * r;
    precise double tangent = sqrt(t2 > 0.0LF ? t2 : 0.0LF);
    if (sub_kind(sub_base(view, 0u)) == MLOD_IF_KIND_ORTHOGRAPHIC) tangent = 0.0LF;
    if (use_cone && vd(view, MLOD_IF_V_BACKFACES) != 0.0LF && backfacing(view, x, d2, r, cone)) return 0.0LF;
    if (count > 1u && (reached = reached_subs(view, sphere)) == 0u) return 0.0LF;
    culled = false;
    double c = 0.0LF;
    for (uint s = 0u; s < count; s++)
        if (((reached >> s) & 1u) != 0u) {
            double d = sub_diameter(sub_base(view, s), x, d2, r, tangent);
            if (d > c) c = d;
        }
    return c;
}

// C twin: mlod__is_valid
bool status_valid(uint s) { return s == MLOD_IF_STATUS_DRAWN || s == MLOD_IF_STATUS_CULLED; }

// C twin: mlod__classify
uint classify(uint view, uint node, double epsilon, uint leaf_count)
{
    bool culled;
    vec4 cone = MLOD_HAS_CONES ? cones[node] : vec4(0.0);
    double c = evaluate(view, spheres[node], MLOD_HAS_CONES, cone, culled);
    if (culled) return MLOD_IF_STATUS_CULLED;
    if (c <= epsilon) return MLOD_IF_STATUS_DRAWN;
    return node >= leaf_count - 1u ? MLOD_IF_STATUS_OVERSIZE : MLOD_IF_STATUS_COARSE;
}

// ----------------------------------------------------------- image disc --

// C twin: mlod__image_discs (one of its lanes)
// The disc around the image of sphere (centre, r) in sub-projection s of
// the view's tile (pixels), and the depth of its centre.  Returns false
// when unbounded.
bool image_disc(uint view, uint s, dvec3 centre, double r, out dvec4 disc)
{
    disc = dvec4(0.0LF);
    uint sub = sub_base(view, s);
    dvec3 e = vd3(view, MLOD_IF_V_EYE), u = sd3(sub, MLOD_IF_S_RIGHT), v = sd3(sub, MLOD_IF_S_UP);
    dvec3 w = sd3(sub, MLOD_IF_S_FORWARD);
    precise dvec3 x = dvec3(centre.x - e.x, centre.y - e.y, centre.z - e.z);
    double scale = sd(sub, MLOD_IF_S_SCALE), left = sd(sub, MLOD_IF_S_X), top = sd(sub, MLOD_IF_S_Y);
    double width = sd(sub, MLOD_IF_S_WIDTH), height = sd(sub, MLOD_IF_S_HEIGHT);
    precise double mid_x = left + 0.5LF * width;
    precise double mid_y = top + 0.5LF * height;
    int kind = sub_kind(sub);
    if (kind == MLOD_IF_KIND_ORTHOGRAPHIC) {
        precise double px = mid_x + sd(sub, MLOD_IF_S_SCALE_X) * dot3(x, u);
        precise double py = mid_y - sd(sub, MLOD_IF_S_SCALE_Y) * dot3(x, v);
        precise double radius = r * scale;
        disc = dvec4(px, py, radius, dot3(x, w));
        return true;
    }
    precise double d = sqrt(dot3(x, x));
    if (!(d > r)) return false;
    precise double a = dot3(x, u) / d;
    precise double b = dot3(x, v) / d;
    precise double cos_t = dot3(x, w) / d;
    precise double sin_t = sqrt(a * a + b * b);
    precise double sin_b = r / d;
    precise double cos_b = sqrt(1.0LF - sin_b * sin_b);
    precise double dir_x = 0.0LF, dir_y = 0.0LF;
    if (sin_t > 0.0LF) {
        dir_x = a / sin_t;
        dir_y = b / sin_t;
    }
    precise double s_hi = sin_t * cos_b + cos_t * sin_b;
    precise double c_hi = cos_t * cos_b - sin_t * sin_b;
    precise double s_lo = sin_t * cos_b - cos_t * sin_b;
    precise double c_lo = cos_t * cos_b + sin_t * sin_b;
    precise double hi, lo, px, py, depth;
    if (kind == MLOD_IF_KIND_PERSPECTIVE) {
        if (!(c_hi > 0.0LF)) return false;
        hi = s_hi / c_hi;
        lo = s_lo / c_lo;
        px = mid_x + scale * 0.5LF * (hi + lo) * dir_x;
        py = mid_y - scale * 0.5LF * (hi + lo) * dir_y;
        depth = dot3(x, w);
    } else {
        if (!(1.0LF + c_hi > 0.0LF) || !(s_hi > 0.0LF || c_hi > 0.0LF)) return false;
        hi = s_hi / (1.0LF + c_hi);
        lo = s_lo / (1.0LF + c_lo);
        px = left + 0.5LF * width * (1.0LF + 0.5LF * (hi + lo) * dir_x);
        py = top + 0.5LF * height * (1.0LF - 0.5LF * (hi + lo) * dir_y);
        depth = d;
    }
    precise double radius = scale * 0.5LF * (hi - lo);
    disc = dvec4(px, py, radius, depth);
    return true;
}

#endif // MLOD_NO_VIEWS
