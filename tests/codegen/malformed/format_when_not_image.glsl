#pragma sao effect bad version=1
#pragma sao variant H values=[0,1] "half"
#pragma sao resource src kind=input format=depth "in"
#pragma sao resource dst kind=output format=r32f format_when=H:r16f "out: an output's formats come from formats="
#pragma sao block P
layout(std140, binding = 0) uniform P {
  vec4 a;
};
#pragma sao pass main entry=run local=8x8 reads=src writes=dst variants=H "p"
void run() { imageStore(out_dst, ivec2(0), texelFetch(in_src, ivec2(0), 0) * a); }
#pragma sao end
