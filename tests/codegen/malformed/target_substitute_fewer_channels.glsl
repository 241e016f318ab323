#pragma sao effect bad version=1
#pragma sao resource src kind=input format=depth "in"
#pragma sao resource mid kind=image format=rg32f "an rg32f intermediate"
#pragma sao resource dst kind=output format=r16f formats=[r16f,r8] "out"
#pragma sao target gles storage=[rg32f:r32f,r16f:r32f] refuse=[r8] "ES 3.1 stores fewer formats"
#pragma sao block P
layout(std140, binding = 0) uniform P {
  vec4 a;
};
#pragma sao variant F values=[0,1] default=0 select=output:dst "format"
#pragma sao pass first entry=run1 local=8x8 reads=src writes=mid "p"
void run1() { imageStore(out_mid, ivec2(0), texelFetch(in_src, ivec2(0), 0) * a); }
#pragma sao end
#pragma sao pass second entry=run2 local=8x8 reads=mid writes=dst variants=F "p"
void run2() { imageStore(out_dst, ivec2(0), texelFetch(in_mid, ivec2(0), 0)); }
#pragma sao end
