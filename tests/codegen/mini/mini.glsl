#version 450
#extension GL_GOOGLE_include_directive : require
// A small effect for the codegen's golden tests: three passes (one skipped for a single tap, its
// reader then aliased), two variants selected by a setting and an input, an exclusion, two presets,
// two inert rules (one on a float setting) and a refusal.
#pragma sao effect mini version=2
#pragma sao setting float strength default=0.5 range=[0,2] unit=m "How strong"
#pragma sao setting int taps default=4 range=[1,16] "Taps per pixel"
#pragma sao setting bool enabled default=true "Whether to run at all"
#pragma sao constant int MINI_MAX_TAPS=16 "Upper bound of taps"
#pragma sao variant FANCY values=[0,1] default=0 select=enabled "Fancy path"
#pragma sao variant EXTRA values=[0,1] select=input:extra "Extra input"
#pragma sao exclude FANCY=1 EXTRA=1 "not both"
#pragma sao resource src kind=input format=depth "Input depth"
#pragma sao resource extra kind=input format=rgba16f when=EXTRA "Extra input"
#pragma sao resource mid kind=image format=r32f mips=auto "Intermediate chain"
#pragma sao resource smooth kind=image format=r32f "Smoothed intermediate"
#pragma sao resource dst kind=output format=r16f "Result"
#pragma sao inert strength when=enabled==false "the plain path has no strength"
#pragma sao inert taps when=strength==0 "no strength, nothing to tap"
#pragma sao refuse enabled when=taps>=16 "the plain path takes at most 15 taps"
#pragma sao preset fast taps=1 enabled=false "One tap, plain path"
#pragma sao preset best taps=16 strength=1.5 "All taps, stronger"

#include "include/mini_lib.glsl"

#pragma sao block MiniParams
layout(std140, binding = 0) uniform MiniParams {
  vec4 scale;      // offset 0
  float gain;      // offset 16
  vec2 pair;       // offset 24
  ivec4 counts;    // offset 32
  mat4 xform;      // offset 48
  vec4 table[2];   // offset 112
};

#pragma sao pass first entry=mini_first local=8x8 reads=src,extra writes=mid variants=EXTRA "Copy"
void mini_first() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  float v = texelFetch(in_src, p, 0).r * gain;
#if EXTRA
  v += texelFetch(in_extra, p, 0).r;
#endif
  imageStore(out_mid, p, vec4(mini_twice(v)));
}
#pragma sao end

#pragma sao pass smoothing entry=mini_smooth local=8x8 reads=mid writes=smooth skip_when=taps==1 "Smooth (nothing to smooth with one tap)"
// Facts the codegen reads from the SPIR-V: a push constant (the block's gain, on Vulkan) and shared
// memory (64 floats and a uint: PassVariantInfo::sharedBytes 260).
#if SAO_TARGET_VULKAN
layout(push_constant) uniform MiniPush { float gain; } mini_push;
#define MINI_GAIN mini_push.gain
#else
#define MINI_GAIN gain
#endif
shared float mini_row[64];
shared uint mini_count;
void mini_smooth() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  const uint i = gl_LocalInvocationIndex;
  mini_row[i] = texelFetch(in_mid, p, 0).r;
  if (i == 0u) mini_count = uint(counts.x);
  barrier();
  const float v = 0.5 * (mini_row[i] + mini_row[min(i + 1u, 63u)]) * float(mini_count);
  imageStore(out_smooth, p, vec4(v * MINI_GAIN));
}
#pragma sao end

#pragma sao pass second entry=mini_second local=16x4 reads=smooth writes=dst variants=FANCY alias_when=taps==1:smooth=mid "Finish"
void mini_second() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  float v = texelFetch(in_smooth, p, 0).r;
#if FANCY
  v = sqrt(abs(v));
#endif
  imageStore(out_dst, p, vec4(v * scale.x));
}
#pragma sao end
