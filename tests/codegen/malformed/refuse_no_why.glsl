#pragma sao effect bad version=1
#pragma sao setting int taps default=4 range=[1,16] "taps"
#pragma sao setting bool on default=true "switch"
#pragma sao setting float gain default=1 range=[0,2] "gain"
#pragma sao derived single when=taps==1&&on==true "one tap, switched on"
#pragma sao refuse gain when=on==false
#pragma sao resource src kind=input format=depth "in"
#pragma sao resource dst kind=output format=r16f "out"
#pragma sao block P
layout(std140, binding = 0) uniform P {
  vec4 a;
};
#pragma sao pass main entry=run local=8x8 reads=src writes=dst "a"
void run() { imageStore(out_dst, ivec2(0), texelFetch(in_src, ivec2(0), 0) * a); }
#pragma sao end
