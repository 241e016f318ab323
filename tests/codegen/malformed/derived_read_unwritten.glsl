#pragma sao effect bad version=1
#pragma sao setting int taps default=4 range=[1,16] "taps"
#pragma sao setting bool on default=true "switch"
#pragma sao derived both when=taps==1&&on==true "both"
#pragma sao resource src kind=input format=depth "in"
#pragma sao resource mid kind=image format=r32f "intermediate"
#pragma sao resource dst kind=output format=r16f "out"
#pragma sao block P
layout(std140, binding = 0) uniform P {
  vec4 a;
};
#pragma sao pass first entry=run_a local=8x8 reads=src writes=mid skip_when=both==true "a"
void run_a() { imageStore(out_mid, ivec2(0), texelFetch(in_src, ivec2(0), 0)); }
#pragma sao end
#pragma sao pass second entry=run_b local=8x8 reads=mid writes=dst skip_when=on==false "b"
void run_b() { imageStore(out_dst, ivec2(0), texelFetch(in_mid, ivec2(0), 0) * a); }
#pragma sao end
#pragma sao pass third entry=run_c local=8x8 reads=src writes=dst skip_when=on==true "c"
void run_c() { imageStore(out_dst, ivec2(0), texelFetch(in_src, ivec2(0), 0)); }
#pragma sao end
