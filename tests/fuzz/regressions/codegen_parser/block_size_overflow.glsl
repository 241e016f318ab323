#pragma sao effect x version=1
#pragma sao block P
layout(std140, binding = 0) uniform P {
  mat4 b[200000000];
  vec4 c[2000000000];
};
