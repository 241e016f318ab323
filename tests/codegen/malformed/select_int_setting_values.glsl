#pragma sao effect bad version=1
#pragma sao setting int mode default=0 values=[0,1,2] "three modes"
#pragma sao variant V values=[0,1] select=mode "v"
#pragma sao resource src kind=input format=depth "in"
#pragma sao resource dst kind=output format=r16f "out"
#pragma sao block P
layout(std140, binding = 0) uniform P {
  vec4 a;
};
#pragma sao pass main entry=run local=8x8 reads=src writes=dst "p"
void run() { imageStore(out_dst, ivec2(0), texelFetch(in_src, ivec2(0), 0) * a); }
#pragma sao end
