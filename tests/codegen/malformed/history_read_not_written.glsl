#pragma sao effect bad version=1
#pragma sao resource src kind=input format=depth "in"
#pragma sao resource past kind=image format=rgba32f history=true "the previous frame's"
#pragma sao resource dst kind=output format=r16f "out"
#pragma sao block P
layout(std140, binding = 0) uniform P {
  vec4 a;
};
#pragma sao pass main entry=run local=8x8 reads=src,past writes=dst "p"
void run() { imageStore(out_dst, ivec2(0), texelFetch(in_src, ivec2(0), 0) * a + texelFetch(in_past, ivec2(0), 0)); }
#pragma sao end
