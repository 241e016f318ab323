#pragma sao effect bad version=1
#pragma sao resource src kind=input format=depth "in"
#pragma sao resource chain kind=image format=r32f mips=auto extent=input "a chain"
#pragma sao resource flat kind=image format=r32f "no chain"
#pragma sao resource dst kind=output format=r16f "out"
#pragma sao block P
layout(std140, binding = 0) uniform P {
  vec4 a;
};
#pragma sao pass first entry=run1 local=8x8 reads=src writes=chain per=mip "p"
void run1() { imageStore(out_chain[0], ivec2(0), texelFetch(in_src, ivec2(0), 0) * a); }
#pragma sao end
#pragma sao pass last entry=run2 local=8x8 reads=chain writes=dst "p"
void run2() { imageStore(out_dst, ivec2(0), texelFetch(in_chain, ivec2(0), 0) * a); }
#pragma sao end
