#pragma sao effect x version=1
#pragma sao block P
layout(std140, binding = 0) uniform P {
  vec4 a[99999999999];
  mat4 b[200000000];
};
