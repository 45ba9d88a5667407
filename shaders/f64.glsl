// shaders/f64.glsl - IEEE 754 binary64 arithmetic from 32-bit integer
// operations only, for shaders on devices without shaderFloat64 or
// shaderInt64 (Apple GPUs through MoltenVK, Intel Arc, most mobile GPUs)
// and for consumer GPUs whose double rate is 1/32 to 1/64 of float.
//
// A double travels as its bits in a uvec2: x the low word, y the high word
// (sign, 11 exponent bits, the top 20 fraction bits), the layout of a C
// double's two 32-bit halves on a little-endian host.  Addition,
// subtraction, multiplication, division and square root round to nearest,
// ties to even, with subnormals, signed zeros and infinities as IEEE 754
// says: the results are the bits a C double on the host computes, on every
// device (integer operations are exact everywhere, where a device's float
// division and square root may be off by ulps).  NaNs: any NaN operand or
// invalid operation gives the one quiet NaN f64_nan(); payloads are not
// kept (the tests compare NaN-ness only).  Comparisons follow IEEE (a NaN
// compares false; -0 == +0).
//
// The same text compiles as C99 (tests/f64_c.h supplies uint, uvec2,
// findMSB, the float bit casts, f64u_mul32 and f64u_int), so tests/test_f64.c checks it
// against the host's doubles over millions of operands, and
// tests/test_f64_vulkan.c checks that the device computes the same bits.
// Hence the subset: no operators on vectors, no out parameters, no
// structs, no global constants, no recursion; every uvec2 constructor
// takes two uints.
//
// Internally a 64-bit unsigned integer is a uvec2 too (f64u_*), and a
// finite nonzero operand is its significand m (leading bit at 52) and its
// exponent E with |a| = m 2^(E - 1075) (E < 1 for subnormals).  Results go
// through f64_round_pack, which takes a significand with its leading bit
// at 62 and ten bits to round.

// ------------------------------------------------ 64-bit unsigned words --

#ifndef MLOD_F64_C
// The product of two 32-bit words: (low word, high word).
uvec2 f64u_mul32(uint a, uint b)
{
    uint hi, lo;
    umulExtended(a, b, hi, lo);
    return uvec2(lo, hi);
}

// The int of the same bits.
int f64u_int(uint u)
{
    return int(u);
}
#endif

uvec2 f64u_add(uvec2 a, uvec2 b)
{
    uint lo = a.x + b.x;
    return uvec2(lo, a.y + b.y + (lo < a.x ? 1u : 0u));
}

uvec2 f64u_sub(uvec2 a, uvec2 b) // a >= b
{
    return uvec2(a.x - b.x, a.y - b.y - (a.x < b.x ? 1u : 0u));
}

bool f64u_lt(uvec2 a, uvec2 b)
{
    return a.y < b.y || (a.y == b.y && a.x < b.x);
}

bool f64u_is0(uvec2 a)
{
    return (a.x | a.y) == 0u;
}

// The index of the highest set bit, -1 for 0.
int f64u_msb(uvec2 a)
{
    return a.y != 0u ? 32 + findMSB(a.y) : findMSB(a.x);
}

uvec2 f64u_shl(uvec2 a, int n) // 0 <= n < 64
{
    if (n == 0) return a;
    if (n >= 32) return uvec2(0u, a.x << uint(n - 32));
    return uvec2(a.x << uint(n), (a.y << uint(n)) | (a.x >> uint(32 - n)));
}

uvec2 f64u_shr(uvec2 a, int n) // 0 <= n < 64
{
    if (n == 0) return a;
    if (n >= 32) return uvec2(a.y >> uint(n - 32), 0u);
    return uvec2((a.x >> uint(n)) | (a.y << uint(32 - n)), a.y >> uint(n));
}

// Shift right by n >= 0, setting bit 0 when a set bit is shifted out (the
// sticky bit: the result stays on the same side of every rounding
// boundary as the exact quotient).
uvec2 f64u_shr_jam(uvec2 a, int n)
{
    if (n >= 64) return uvec2(f64u_is0(a) ? 0u : 1u, 0u);
    uvec2 r = f64u_shr(a, n);
    if (!f64u_is0(f64u_sub(a, f64u_shl(r, n)))) r.x |= 1u;
    return r;
}

uvec2 f64u_bit(uvec2 a, int i) // a with bit i (0 <= i < 64) set
{
    if (i >= 32) return uvec2(a.x, a.y | (1u << uint(i - 32)));
    return uvec2(a.x | (1u << uint(i)), a.y);
}

// The high 64 bits of the 128-bit product a b, bit 0 set when the low 64
// bits are not all zero.
uvec2 f64u_mul_hi_jam(uvec2 a, uvec2 b)
{
    uvec2 p00 = f64u_mul32(a.x, b.x), p01 = f64u_mul32(a.x, b.y);
    uvec2 p10 = f64u_mul32(a.y, b.x), p11 = f64u_mul32(a.y, b.y);
    uvec2 w1 = f64u_add(f64u_add(uvec2(p00.y, 0u), uvec2(p01.x, 0u)), uvec2(p10.x, 0u));
    uvec2 w2 = f64u_add(f64u_add(uvec2(p01.y, 0u), uvec2(p10.y, 0u)), f64u_add(uvec2(p11.x, 0u), uvec2(w1.y, 0u)));
    uvec2 hi = uvec2(w2.x, p11.y + w2.y);
    if ((p00.x | w1.x) != 0u) hi.x |= 1u;
    return hi;
}

// --------------------------------------------------------- the fields --

uvec2 f64_nan()
{
    return uvec2(0u, 0x7FF80000u);
}

uvec2 f64_inf(uint sign)
{
    return uvec2(0u, (sign << 31) | 0x7FF00000u);
}

uvec2 f64_zero(uint sign)
{
    return uvec2(0u, sign << 31);
}

uint f64_sign(uvec2 a)
{
    return a.y >> 31;
}

int f64_biased(uvec2 a) // the exponent field
{
    return f64u_int((a.y >> 20) & 0x7FFu);
}

bool f64_isnan(uvec2 a)
{
    uint h = a.y & 0x7FFFFFFFu;
    return h > 0x7FF00000u || (h == 0x7FF00000u && a.x != 0u);
}

bool f64_isinf(uvec2 a)
{
    return (a.y & 0x7FFFFFFFu) == 0x7FF00000u && a.x == 0u;
}

bool f64_iszero(uvec2 a)
{
    return ((a.y & 0x7FFFFFFFu) | a.x) == 0u;
}

uvec2 f64_neg(uvec2 a)
{
    return uvec2(a.x, a.y ^ 0x80000000u);
}

uvec2 f64_abs(uvec2 a)
{
    return uvec2(a.x, a.y & 0x7FFFFFFFu);
}

// The significand of a finite nonzero a, its leading bit at 52.
uvec2 f64_sig(uvec2 a)
{
    uvec2 m = uvec2(a.x, a.y & 0xFFFFFu);
    if (f64_biased(a) != 0) return uvec2(m.x, m.y | 0x100000u);
    return f64u_shl(m, 52 - f64u_msb(m));
}

// Its exponent: |a| = f64_sig(a) 2^(f64_exp(a) - 1075).
int f64_exp(uvec2 a)
{
    int e = f64_biased(a);
    return e != 0 ? e : 1 - (52 - f64u_msb(uvec2(a.x, a.y & 0xFFFFFu)));
}

// The double nearest (ties to even) to (-1)^sign sig 2^(e - 1085), where
// sig < 2^63 has its leading bit at 62, or e <= 1; a sticky bit 0 stands
// for any nonzero bits below.  Subnormal results are rounded once, at
// their own precision; past the largest double: infinity.
uvec2 f64_round_pack(uint sign, int e, uvec2 sig)
{
    if (e < 1) {
        sig = f64u_shr_jam(sig, 1 - e);
        e = 1;
    }
    uint rest = sig.x & 0x3FFu;
    uvec2 m = f64u_shr(sig, 10);
    if (rest > 0x200u || (rest == 0x200u && (m.x & 1u) != 0u)) m = f64u_add(m, uvec2(1u, 0u));
    if (m.y >= 0x200000u) { // rounded up to 2^53
        m = f64u_shr(m, 1);
        e += 1;
    }
    if (e >= 2047) return f64_inf(sign);
    if (m.y < 0x100000u) return uvec2(m.x, (sign << 31) | m.y); // subnormal or zero (e is 1)
    return uvec2(m.x, (sign << 31) | (uint(e) << 20) | (m.y & 0xFFFFFu));
}

// ---------------------------------------------------------- arithmetic --

uvec2 f64_add(uvec2 a, uvec2 b)
{
    if (f64_isnan(a) || f64_isnan(b)) return f64_nan();
    uint sa = f64_sign(a), sb = f64_sign(b);
    if (f64_isinf(a) || f64_isinf(b)) {
        if (f64_isinf(a) && f64_isinf(b) && sa != sb) return f64_nan();
        return f64_isinf(a) ? a : b;
    }
    if (f64_iszero(a)) return f64_iszero(b) ? f64_zero(sa & sb) : b;
    if (f64_iszero(b)) return a;
    int ea = f64_exp(a), eb = f64_exp(b);
    uvec2 ma = f64u_shl(f64_sig(a), 9), mb = f64u_shl(f64_sig(b), 9); // leading bits at 61
    if (ea < eb || (ea == eb && f64u_lt(ma, mb))) { // a the larger in magnitude
        uvec2 t = ma;
        ma = mb;
        mb = t;
        int te = ea;
        ea = eb;
        eb = te;
        uint ts = sa;
        sa = sb;
        sb = ts;
    }
    mb = f64u_shr_jam(mb, ea - eb);
    uvec2 sig;
    if (sa == sb) {
        sig = f64u_add(ma, mb); // below 2^63
    } else {
        sig = f64u_sub(ma, mb);
        if (f64u_is0(sig)) return f64_zero(0u); // x - x = +0
    }
    // the leading bit to 62: up by at most 1 after an addition; after a
    // subtraction with a sticky bit (ea - eb >= 10) by at most 1, so the
    // sticky bit stays below the rounding bits
    int shift = 62 - f64u_msb(sig);
    return f64_round_pack(sa, ea + 1 - shift, f64u_shl(sig, shift));
}

uvec2 f64_sub(uvec2 a, uvec2 b)
{
    return f64_add(a, f64_neg(b));
}

uvec2 f64_mul(uvec2 a, uvec2 b)
{
    uint sign = f64_sign(a) ^ f64_sign(b);
    if (f64_isnan(a) || f64_isnan(b)) return f64_nan();
    if (f64_isinf(a) || f64_isinf(b)) return f64_iszero(a) || f64_iszero(b) ? f64_nan() : f64_inf(sign);
    if (f64_iszero(a) || f64_iszero(b)) return f64_zero(sign);
    // leading bits at 62 and 63: the product's at 125 or 126, its high
    // word's at 61 or 62
    uvec2 sig = f64u_mul_hi_jam(f64u_shl(f64_sig(a), 10), f64u_shl(f64_sig(b), 11));
    int e = f64_exp(a) + f64_exp(b) - 1022;
    if (sig.y < 0x40000000u) {
        sig = f64u_shl(sig, 1);
        e -= 1;
    }
    return f64_round_pack(sign, e, sig);
}

uvec2 f64_div(uvec2 a, uvec2 b)
{
    uint sign = f64_sign(a) ^ f64_sign(b);
    if (f64_isnan(a) || f64_isnan(b)) return f64_nan();
    if (f64_isinf(a)) return f64_isinf(b) ? f64_nan() : f64_inf(sign);
    if (f64_isinf(b)) return f64_zero(sign);
    if (f64_iszero(b)) return f64_iszero(a) ? f64_nan() : f64_inf(sign);
    if (f64_iszero(a)) return f64_zero(sign);
    uvec2 ma = f64_sig(a), mb = f64_sig(b);
    int e = f64_exp(a) - f64_exp(b) + 1023;
    if (f64u_lt(ma, mb)) {
        ma = f64u_shl(ma, 1);
        e -= 1;
    }
    // the quotient ma 2^62 / mb in [2^62, 2^63), one bit a step; the
    // remainder stays below 2 mb < 2^55
    uvec2 q = uvec2(0u, 0u), rem = ma;
    for (int i = 62; i >= 0; i--) {
        if (!f64u_lt(rem, mb)) {
            rem = f64u_sub(rem, mb);
            q = f64u_bit(q, i);
        }
        rem = f64u_shl(rem, 1);
    }
    if (!f64u_is0(rem)) q.x |= 1u;
    return f64_round_pack(sign, e, q);
}

uvec2 f64_sqrt(uvec2 a)
{
    if (f64_isnan(a)) return f64_nan();
    if (f64_iszero(a)) return a; // sqrt(-0) = -0
    if (f64_sign(a) != 0u) return f64_nan();
    if (f64_isinf(a)) return a;
    uvec2 m = f64_sig(a);
    int e = f64_exp(a) - 1075; // a = m 2^e
    if ((e & 1) != 0) {
        m = f64u_shl(m, 1);
        e -= 1;
    }
    // the root of n = m 2^72 (below 2^126) digit by digit, two bits of n a
    // step: root in [2^62, 2^63); the remainder (at most 2 root, before the
    // step's subtraction below 2^66) in three words r2:r1:r0
    uvec2 root = uvec2(0u, 0u);
    uint r0 = 0u, r1 = 0u, r2 = 0u;
    for (int k = 62; k >= 0; k--) {
        uint pair = 0u;
        if (2 * k >= 72) pair = f64u_shr(m, 2 * k - 72).x & 3u;
        // rem = rem 4 + pair
        r2 = (r2 << 2) | (r1 >> 30);
        r1 = (r1 << 2) | (r0 >> 30);
        r0 = (r0 << 2) | pair;
        // t = root 4 + 1
        uint t0 = (root.x << 2) | 1u, t1 = (root.y << 2) | (root.x >> 30), t2 = root.y >> 30;
        bool ge = r2 > t2 || (r2 == t2 && (r1 > t1 || (r1 == t1 && r0 >= t0)));
        root = f64u_shl(root, 1);
        if (ge) {
            uint b0 = r0 < t0 ? 1u : 0u;
            r0 -= t0;
            uint b1 = (r1 < t1 || (r1 == t1 && b0 != 0u)) ? 1u : 0u;
            r1 = r1 - t1 - b0;
            r2 = r2 - t2 - b1;
            root.x |= 1u;
        }
    }
    if ((r0 | r1 | r2) != 0u) root.x |= 1u; // a root is never halfway: the sticky bit suffices
    return f64_round_pack(0u, e / 2 + 1049, root);
}

// The largest integer at most a (C's floor): its fraction bits cleared,
// then one less for a negative a that had any.
uvec2 f64_floor(uvec2 a)
{
    if (f64_isnan(a)) return f64_nan();
    if (f64_isinf(a) || f64_iszero(a)) return a;
    int e = f64_biased(a) - 1023;
    if (e >= 52) return a; // an integer already
    uint sign = f64_sign(a);
    if (e < 0) return sign != 0u ? uvec2(0u, 0xBFF00000u) : f64_zero(0u); // -1 or +0
    uvec2 mask = f64u_sub(f64u_shl(uvec2(1u, 0u), 52 - e), uvec2(1u, 0u)); // the fraction bits
    if (((a.x & mask.x) | (a.y & mask.y)) == 0u) return a;
    uvec2 t = uvec2(a.x & ~mask.x, a.y & ~mask.y); // toward zero
    return sign != 0u ? f64_sub(t, uvec2(0u, 0x3FF00000u)) : t;
}

// The least integer at least a (C's ceil).
uvec2 f64_ceil(uvec2 a)
{
    return f64_neg(f64_floor(f64_neg(a)));
}

// ---------------------------------------------------------- comparisons --

bool f64_lt(uvec2 a, uvec2 b)
{
    if (f64_isnan(a) || f64_isnan(b) || (f64_iszero(a) && f64_iszero(b))) return false;
    uint sa = f64_sign(a), sb = f64_sign(b);
    if (sa != sb) return sa != 0u;
    return sa == 0u ? f64u_lt(f64_abs(a), f64_abs(b)) : f64u_lt(f64_abs(b), f64_abs(a));
}

bool f64_eq(uvec2 a, uvec2 b)
{
    if (f64_isnan(a) || f64_isnan(b)) return false;
    return (a.x == b.x && a.y == b.y) || (f64_iszero(a) && f64_iszero(b));
}

bool f64_le(uvec2 a, uvec2 b)
{
    return f64_lt(a, b) || f64_eq(a, b);
}

// ---------------------------------------------------------- conversions --

uvec2 f64_from_float(float f) // exact
{
    uint u = floatBitsToUint(f), sign = u >> 31, e = (u >> 23) & 0xFFu, frac = u & 0x7FFFFFu;
    if (e == 0xFFu) return frac != 0u ? f64_nan() : f64_inf(sign);
    if (e == 0u) {
        if (frac == 0u) return f64_zero(sign);
        int top = findMSB(frac); // |f| = frac 2^-149
        uvec2 m = f64u_shl(uvec2(frac, 0u), 52 - top);
        return uvec2(m.x, (sign << 31) | (uint(874 + top) << 20) | (m.y & 0xFFFFFu));
    }
    return uvec2(frac << 29, (sign << 31) | ((e + 896u) << 20) | (frac >> 3));
}

uvec2 f64_from_uint(uint u) // exact
{
    if (u == 0u) return f64_zero(0u);
    int top = findMSB(u);
    uvec2 m = f64u_shl(uvec2(u, 0u), 52 - top);
    return uvec2(m.x, (uint(1023 + top) << 20) | (m.y & 0xFFFFFu));
}

uvec2 f64_from_int(int i) // exact
{
    uint u = uint(i);
    if (i < 0) return f64_neg(f64_from_uint(0u - u));
    return f64_from_uint(u);
}

// The float nearest to a (ties to even), as a C cast rounds: subnormal
// floats rounded at their own precision, infinity past the largest float.
float f64_to_float(uvec2 a)
{
    uint sign = f64_sign(a);
    if (f64_isnan(a)) return uintBitsToFloat(0x7FC00000u);
    if (f64_isinf(a)) return uintBitsToFloat((sign << 31) | 0x7F800000u);
    if (f64_iszero(a)) return uintBitsToFloat(sign << 31);
    uvec2 m = f64_sig(a);
    int ef = f64_exp(a) - 896; // the float's biased exponent, were it normal
    int shift = 29;            // 53 bits to 24
    if (ef < 1) {
        shift += 1 - ef;
        ef = 1;
    }
    if (shift > 54) return uintBitsToFloat(sign << 31); // below half the least subnormal
    uvec2 q = f64u_shr(m, shift);
    uvec2 rest = f64u_sub(m, f64u_shl(q, shift)), halfway = f64u_shl(uvec2(1u, 0u), shift - 1);
    uint bits = q.x;
    if (f64u_lt(halfway, rest) || (rest.x == halfway.x && rest.y == halfway.y && (bits & 1u) != 0u)) bits += 1u;
    if (bits >= 0x1000000u) { // rounded up to 2^24
        bits >>= 1;
        ef += 1;
    }
    if (ef >= 255) return uintBitsToFloat((sign << 31) | 0x7F800000u);
    if (bits < 0x800000u) return uintBitsToFloat((sign << 31) | bits); // subnormal (ef is 1)
    return uintBitsToFloat((sign << 31) | (uint(ef) << 23) | (bits & 0x7FFFFFu));
}

// Toward zero, as a C cast does; a must lie within (-2^31 - 1, 2^31).
int f64_to_int(uvec2 a)
{
    if (f64_isnan(a) || f64_iszero(a)) return 0;
    int e = f64_exp(a) - 1075; // |a| = m 2^e
    if (e <= -53) return 0;
    uvec2 m = f64_sig(a);
    uint mag = e >= 0 ? f64u_shl(m, e).x : f64u_shr(m, -e).x;
    return f64u_int(f64_sign(a) != 0u ? 0u - mag : mag);
}
