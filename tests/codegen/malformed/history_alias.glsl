#pragma sao effect bad version=1
#pragma sao setting int taps default=4 range=[0,16] "taps"
#pragma sao resource src kind=input format=depth "in"
#pragma sao resource past kind=image format=rgba32f history=true "the previous frame's"
#pragma sao resource mid kind=image format=rgba32f "intermediate"
#pragma sao resource dst kind=output format=r16f "out"
#pragma sao block P
layout(std140, binding = 0) uniform P {
  vec4 a;
};
#pragma sao pass first entry=run1 local=8x8 reads=src,past writes=past "p"
void run1() { imageStore(out_past, ivec2(0), texelFetch(in_src, ivec2(0), 0) * a + texelFetch(in_past, ivec2(0), 0)); }
#pragma sao end
#pragma sao pass second entry=run2 local=8x8 reads=src writes=mid skip_when=taps==0 "p"
void run2() { imageStore(out_mid, ivec2(0), texelFetch(in_src, ivec2(0), 0) * a); }
#pragma sao end
#pragma sao pass third entry=run3 local=8x8 reads=mid writes=dst alias_when=taps==0:mid=past "p"
void run3() { imageStore(out_dst, ivec2(0), texelFetch(in_mid, ivec2(0), 0) * a); }
#pragma sao end
