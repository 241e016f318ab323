#version 450
#pragma sao effect tiny version=1
#pragma sao setting float x default=1 range=[0,2] unit=m "doc"
#pragma sao setting int n default=3 range=[1,8] "doc"
#pragma sao constant uint TINY_K=7u "doc"
#pragma sao variant V values=[0,1,2] default=1 "doc"
#pragma sao variant W values=[0,1] "doc"
#pragma sao exclude V=2 W=1 "not both"
#pragma sao resource src kind=input format=depth "in"
#pragma sao resource mid kind=image format=rg32f extent=input scale=1/2 when=W "mid"
#pragma sao resource dst kind=output format=r16f "out"
#pragma sao block P
layout(std140, binding = 0) uniform P {
  vec4 a;
  float b[3];
  ivec2 c;
};
#pragma sao pass main entry=run local=8x8 reads=src writes=dst variants=V "p"
void run() { imageStore(out_dst, ivec2(0), texelFetch(in_src, ivec2(0), 0) * a); }
#pragma sao end
#pragma sao pass mips entry=down local=4x4 reads=src writes=mid variants=W "q"
void down() {}
#pragma sao end
