#pragma sao effect bad version=1
#pragma sao resource src kind=input format=depth "in"
#pragma sao resource mid kind=image format=r32f "intermediate"
#pragma sao resource dst kind=output format=r16f "out"
#pragma sao block P
layout(std140, binding = 0) uniform P {
  vec4 a;
  int taps;
  float gain;
};
#pragma sao pass first entry=run1 local=8x8 reads=src writes=mid "p"
#if SAO_TARGET_VULKAN
layout(push_constant) uniform FirstPush { int taps; } first_push;
#define TAPS first_push.taps
#else
#define TAPS taps
#endif
void run1() { imageStore(out_mid, ivec2(0), texelFetch(in_src, ivec2(0), 0) * float(TAPS)); }
#pragma sao end
#pragma sao pass second entry=run2 local=8x8 reads=mid writes=dst "p"
#if SAO_TARGET_VULKAN
layout(push_constant) uniform SecondPush { float gain; } second_push;
#define GAIN second_push.gain
#else
#define GAIN gain
#endif
void run2() { imageStore(out_dst, ivec2(0), texelFetch(in_mid, ivec2(0), 0) * GAIN); }
#pragma sao end
