#pragma sao effect bad version=1
#pragma sao variant A values=[0,1,2,3] "doc"
#pragma sao variant B values=[0,1,2,3] "doc"
#pragma sao variant C values=[0,1,2,3] "doc"
#pragma sao variant D values=[0,1,2,3] "doc"
#pragma sao variant E values=[0,1,2,3] "doc"
#pragma sao variant F values=[0,1,2,3] "doc"
#pragma sao variant H values=[0,1,2,3] "doc"
#pragma sao variant I values=[0,1,2,3] "doc"
#pragma sao variant G values=[0,1] "the effect's product: 131072 > 65536"
#pragma sao resource src kind=input format=depth "in"
#pragma sao resource dst kind=output format=r16f "out"
#pragma sao block P
layout(std140, binding = 0) uniform P {
  vec4 a;
};
#pragma sao pass main entry=run local=8x8 reads=src writes=dst "p"
void run() { imageStore(out_dst, ivec2(0), texelFetch(in_src, ivec2(0), 0) * a); }
#pragma sao end
