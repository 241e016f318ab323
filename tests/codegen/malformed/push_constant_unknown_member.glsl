#pragma sao effect bad version=1
#pragma sao resource src kind=input format=depth "in"
#pragma sao resource dst kind=output format=r16f "out"
#pragma sao block P
layout(std140, binding = 0) uniform P {
  vec4 a;
  int taps;
};
#pragma sao pass only entry=run local=8x8 reads=src writes=dst "p"
#if SAO_TARGET_VULKAN
layout(push_constant) uniform Counts { int count; } counts;
#define COUNT counts.count
#else
#define COUNT taps
#endif
void run() { imageStore(out_dst, ivec2(0), texelFetch(in_src, ivec2(0), 0) * a * float(COUNT)); }
#pragma sao end
