#version 450
#extension GL_GOOGLE_include_directive : require
// tests/f64_check.comp - shaders/f64.glsl on a Vulkan device, for
// tests/test_f64_vulkan.c: one invocation per operand pair (a, b), six
// uvec4 of results each.  No 64-bit type anywhere: the module must not
// declare the Float64 or Int64 capabilities (the test checks).
layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) readonly buffer operand_buffer { uvec4 operands[]; };
layout(std430, set = 0, binding = 1) writeonly buffer result_buffer { uvec4 results[]; };
layout(push_constant) uniform push_block { uint count; } pc;

#include "f64.glsl"

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    uvec2 a = operands[i].xy, b = operands[i].zw;
    uint flags = (f64_lt(a, b) ? 1u : 0u) | (f64_le(a, b) ? 2u : 0u) | (f64_eq(a, b) ? 4u : 0u);
    // to int only where C's cast is defined: |a| < 2^31
    bool small = f64_lt(f64_abs(a), uvec2(0u, 0x41E00000u));
    results[6u * i] = uvec4(f64_add(a, b), f64_sub(a, b));
    results[6u * i + 1u] = uvec4(f64_mul(a, b), f64_div(a, b));
    results[6u * i + 2u] = uvec4(f64_sqrt(a), floatBitsToUint(f64_to_float(a)), flags);
    results[6u * i + 3u] = uvec4(f64_from_float(uintBitsToFloat(b.x)), f64_from_int(int(b.y)));
    results[6u * i + 4u] = uvec4(f64_from_uint(b.y), uint(small ? f64_to_int(a) : 0), 0u);
    results[6u * i + 5u] = uvec4(f64_floor(a), f64_ceil(a));
}
