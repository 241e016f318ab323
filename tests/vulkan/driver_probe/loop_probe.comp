#version 450
// The shader of sao-vk-loop-probe (loop_probe.cpp): sao's ao_sample spiral-tap loop (effect/sao.glsl)
// reduced to what lavapipe 22.3 needs to show the growth, sao's helpers inlined under other names.
// The loop's trip count comes from the uniform buffer its body also reads; -DCONSTANT_TRIP_COUNT
// makes it the same number known at compile time (which the driver handles without growth).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D src;  // camera-space z, one level
layout(binding = 1, r32f) uniform writeonly image2D dst;
layout(std140, binding = 2) uniform Params {
  vec4 proj;  // x_C = z*(x*proj.x + proj.z), y_C = z*(y*proj.y + proj.w)
  int count;  // taps
  float radius2;
  int turns;
} pc;

bool isSky(float z) {
  uint b = floatBitsToUint(z);
  return !(b > 0x80000000u && b < 0xFF800000u);
}
vec3 position(vec2 pixel, float z) { return vec3(z * (pixel * pc.proj.xy + pc.proj.zw), z); }
float term(vec3 c, vec3 n, vec2 q, float zq) {
  if (isSky(zq)) return 0.0;
  vec3 v = position(q, zq) - c;
  float vv = dot(v, v);
  if (vv > pc.radius2) return 0.0;
  return max(0.0, dot(v, n)) / (vv + 0.01);
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = textureSize(src, 0);
  float zc = texelFetch(src, p, 0).r;
  vec3 c = position(vec2(p) + 0.5, zc);
  vec3 n = vec3(0.0, 0.0, 1.0);
  uint phase = ((3u * uint(p.x)) ^ uint(p.y + p.x * p.y)) * 1270342730u << 1u;
#ifdef CONSTANT_TRIP_COUNT
  const int s = 11;
#else
  int s = clamp(pc.count, 1, 64);
#endif
  float sum = 0.0;
  for (int i = 0; i < s; ++i) {
    float h = 8.0 * (float(i) + 0.5) / float(s);
    uint k = (uint(2 * i + 1) * uint(pc.turns)) % uint(2 * s);
    uint turn = (((k << 23u) / uint(s)) << 8u) + phase;
    float theta = float(int(turn) >> 8) * (6.28318530717958647692 / 16777216.0);
    ivec2 tap = p + ivec2(h * vec2(cos(theta), sin(theta)));
    ivec2 t = clamp(tap, ivec2(0), size - 1);
    sum += term(c, n, vec2(tap) + 0.5, texelFetch(src, t, 0).r);
  }
  imageStore(dst, p, vec4(sum));
}
