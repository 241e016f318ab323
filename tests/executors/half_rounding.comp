#version 430
// The binary16 rounding of effect/include/sao_blur.glsl on a buffer of binary32 bit patterns, for
// half_rounding_test.cpp: (sao_round_to_half(x), sao_round_to_half_signed(x),
// sao_round_to_half_signed(-x), 0) per value. Vulkan: glslangValidator -I effect/include at build
// time; OpenGL: the test puts the included files in place of the #include lines.
#extension GL_GOOGLE_include_directive : require
// The constants the library names, only for it to compile (the rounding reads none of them).
#define SAO_MAX_BLUR_RADIUS 8
#define SAO_DEPTH_MODE_PERSPECTIVE 0
#define SAO_DEPTH_MODE_ORTHOGRAPHIC 1
#define SAO_DEPTH_MODE_LINEAR 2
#include "sao_depth.glsl"
#include "sao_blur.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Inputs { uint bits[]; };
layout(std430, binding = 1) writeonly buffer Outputs { uvec4 rounded[]; };

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(bits.length()))
        return;
    float x = uintBitsToFloat(bits[i]);
    rounded[i] = uvec4(floatBitsToUint(sao_round_to_half(x)), floatBitsToUint(sao_round_to_half_signed(x)),
                       floatBitsToUint(sao_round_to_half_signed(-x)), 0u);
}
