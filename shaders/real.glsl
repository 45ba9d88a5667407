// shaders/real.glsl - the double-precision arithmetic of common.glsl and the
// shaders, in one of two forms chosen when a shader is compiled:
//
//   default               `real` is double, `real3` dvec3: the device's own
//                         doubles (shaderFloat64), every result `precise`
//                         (no fused multiply-add)
//   MLOD_F64_EMULATED     `real` is uvec2, `real3` a struct of three: the
//                         doubles of f64.glsl, from 32-bit integer
//                         operations (no shaderFloat64 or shaderInt64)
//
// Both round every operation to nearest, ties to even, as the C twins in
// manylods.h do, so either form computes the CPU's bits.  The shaders
// write every double operation as one of the r_* functions below, and
// every constant as RK(high word, low word, literal): the literal in the
// native form, its bits in the emulated one (the two are the same double;
// the parity tests would find a pair that is not).

// ROLLED: a loop unrolled with the device's doubles but kept rolled with
// emulated ones, where every operation is a few hundred instructions that
// the driver inlines at each call and compiles (lavapipe took over a
// minute for a context's pipelines): repeated steps of the exact paths
// are written as such loops around one call, the same operations in the
// same order as the C twin's.  (The includer enables
// GL_EXT_control_flow_attributes.)
#ifdef MLOD_F64_EMULATED
#define ROLLED [[dont_unroll]]
#else
#define ROLLED [[unroll]]
#endif

#ifdef MLOD_F64_EMULATED

#include "f64.glsl"

#define real uvec2
struct real3 {
    uvec2 x;
    uvec2 y;
    uvec2 z;
};
#define RK(hi, lo, literal) uvec2(lo, hi)

real r_add(real a, real b) { return f64_add(a, b); }
real r_sub(real a, real b) { return f64_sub(a, b); }
real r_mul(real a, real b) { return f64_mul(a, b); }
real r_div(real a, real b) { return f64_div(a, b); }
real r_sqrt(real a) { return f64_sqrt(a); }
real r_floor(real a) { return f64_floor(a); }
real r_ceil(real a) { return f64_ceil(a); }
real r_neg(real a) { return f64_neg(a); }
real r_abs(real a) { return f64_abs(a); }
bool r_lt(real a, real b) { return f64_lt(a, b); }
bool r_le(real a, real b) { return f64_le(a, b); }
bool r_gt(real a, real b) { return f64_lt(b, a); }
bool r_ge(real a, real b) { return f64_le(b, a); }
bool r_eq(real a, real b) { return f64_eq(a, b); }
bool r_isnan(real a) { return f64_isnan(a); }
bool r_isinf(real a) { return f64_isinf(a); }
real r_f(float f) { return f64_from_float(f); }
real r_u(uint u) { return f64_from_uint(u); }
float r_to_f(real a) { return f64_to_float(a); }
uint r_to_u(real a) { return uint(f64_to_int(a)); } // a in [0, 2^31)
real r_inf() { return f64_inf(0u); }
// The buffer word of a double as the shaders keep it (both forms: its bits).
real r_load(uvec2 bits) { return bits; }
uvec2 r_bits(real a) { return a; }

#else

#define real double
#define real3 dvec3
#define RK(hi, lo, literal) literal

real r_add(real a, real b) { precise real r = a + b; return r; }
real r_sub(real a, real b) { precise real r = a - b; return r; }
real r_mul(real a, real b) { precise real r = a * b; return r; }
real r_div(real a, real b) { precise real r = a / b; return r; }
real r_sqrt(real a) { precise real r = sqrt(a); return r; }
real r_floor(real a) { return floor(a); }
real r_ceil(real a) { return ceil(a); }
real r_neg(real a) { return -a; }
real r_abs(real a) { return abs(a); }
bool r_lt(real a, real b) { return a < b; }
bool r_le(real a, real b) { return a <= b; }
bool r_gt(real a, real b) { return a > b; }
bool r_ge(real a, real b) { return a >= b; }
bool r_eq(real a, real b) { return a == b; }
bool r_isnan(real a) { return isnan(a); }
bool r_isinf(real a) { return isinf(a); }
real r_f(float f) { return double(f); }
real r_u(uint u) { return double(u); }
float r_to_f(real a) { return float(a); }
uint r_to_u(real a) { return uint(a); }
real r_inf() { return 1.0LF / 0.0LF; }
real r_load(uvec2 bits) { return packDouble2x32(bits); }
uvec2 r_bits(real a) { return unpackDouble2x32(a); }

#endif

// The constants the shaders share.
#define R_ZERO RK(0x00000000u, 0x00000000u, 0.0LF)
#define R_HALF RK(0x3FE00000u, 0x00000000u, 0.5LF)
#define R_ONE RK(0x3FF00000u, 0x00000000u, 1.0LF)
#define R_TWO RK(0x40000000u, 0x00000000u, 2.0LF)
#define R_PI RK(0x400921FBu, 0x54442D18u, 3.14159265358979323846LF)
#define R_HALF_PI RK(0x3FF921FBu, 0x54442D18u, 1.57079632679489661923LF)

// Three-vectors, component by component (ROLLED: one copy of each
// operation).
real r3_at(real3 a, uint k) { return k == 0u ? a.x : (k == 1u ? a.y : a.z); }
real3 r3_f(vec3 v) { return real3(r_f(v.x), r_f(v.y), r_f(v.z)); }
real3 r3_sub(real3 a, real3 b)
{
    real c[3];
    ROLLED for (uint k = 0u; k < 3u; k++) c[k] = r_sub(r3_at(a, k), r3_at(b, k));
    return real3(c[0], c[1], c[2]);
}
real3 r3_scale(real3 a, real s)
{
    real c[3];
    ROLLED for (uint k = 0u; k < 3u; k++) c[k] = r_mul(r3_at(a, k), s);
    return real3(c[0], c[1], c[2]);
}
