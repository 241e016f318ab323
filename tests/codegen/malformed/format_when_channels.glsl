#pragma sao effect bad version=1
#pragma sao variant H values=[0,1] "half"
#pragma sao resource src kind=input format=depth "in"
#pragma sao resource mid kind=image format=rg32f format_when=H:r16f "rg32f or a one-channel format: the passes' texels differ"
#pragma sao resource dst kind=output format=r16f "out"
#pragma sao block P
layout(std140, binding = 0) uniform P {
  vec4 a;
};
#pragma sao pass first entry=run1 local=8x8 reads=src writes=mid variants=H "p"
void run1() { imageStore(out_mid, ivec2(0), texelFetch(in_src, ivec2(0), 0) * a); }
#pragma sao end
#pragma sao pass second entry=run2 local=8x8 reads=mid writes=dst "p"
void run2() { imageStore(out_dst, ivec2(0), texelFetch(in_mid, ivec2(0), 0)); }
#pragma sao end
