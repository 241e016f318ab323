// The shader's binary16 rounding (sao_round_to_half, sao_round_to_half_signed in
// effect/include/sao_blur.glsl: integer operations on the float's bits) against an independent
// oracle in double (round to the nearest multiple of the binary16 spacing, ties away from zero),
// on llvmpipe: every binary32 value whose 13 bits below binary16's mantissa are a tie, one step
// either side of it, or 0 / all ones, for every exponent from 2^-25 to 2^15 (binary16's range);
// every tie in the subnormal range; and a stride through all values below 1. The CPU reference's
// frexp form (roundToHalfAsShader) is checked against the same oracle, so GPU and CPU agree bit
// for bit wherever the effect stores a binary16 value.
#include <epoxy/gl.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "gl_support.h"
#include "sao/cpu/reference.h"
#include "sao/gl/program_build.h"

namespace sao::gltest {
namespace {

std::string readLibrary(const char* name) {
  std::ifstream in(std::string(SAO_EFFECT_INCLUDE_DIR) + "/" + name);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The oracle: |x| rounded to the nearest multiple of binary16's spacing at |x| (2^(E-10) for
// |x| in [2^E, 2^(E+1)), E >= -14; 2^-24 below), halves away from zero; exact in double.
float oracle(float x) {
  const double m = std::fabs(double(x));
  if (m == 0.0) return x;
  const int e = std::max(int(std::floor(std::log2(m))), -14);
  const double q = std::ldexp(1.0, e - 10);
  const double r = std::floor(m / q + 0.5) * q;
  return float(x < 0 ? -r : r);
}

std::vector<std::uint32_t> testValues() {
  std::vector<std::uint32_t> v;
  // Around every rounding boundary of every normal binade from 2^-25 (0x33000000) to 2^15.
  for (std::uint32_t exp = 0x66; exp <= 0x8E; ++exp)
    for (std::uint32_t hi = 0; hi < 1024; ++hi)
      for (std::uint32_t lo : {0x0u, 0x1u, 0xFFFu, 0x1000u, 0x1001u, 0x1FFFu})
        v.push_back((exp << 23) | (hi << 13) | lo);
  // Every tie of the subnormal spacing 2^-24 below 2^-14: (2k + 1) * 2^-25, and one step around it.
  for (std::uint32_t k = 0; k < 16384; ++k) {
    const float t = std::ldexp(float(2 * k + 1), -25);
    std::uint32_t b;
    std::memcpy(&b, &t, 4);
    for (std::uint32_t d : {b - 1, b, b + 1}) v.push_back(d);
  }
  // A stride through every value in [0, 1].
  for (std::uint32_t b = 0; b <= 0x3F800000u; b += 4099) v.push_back(b);
  v.push_back(0x3F800000u);
  return v;
}

class HalfRounding : public GlTest {};

TEST_F(HalfRounding, ShaderBitsMatchTheOracle) {
  // The library's two files and the effect's constants they name, as the generated passes define them.
  auto define = [](const char* name, int value) { return "#define " + std::string(name) + " " + std::to_string(value) + "\n"; };
  const std::string source = "#version 430\n" + define("SAO_MAX_BLUR_RADIUS", gen::SAO_MAX_BLUR_RADIUS) +
                             define("SAO_DEPTH_MODE_PERSPECTIVE", gen::SAO_DEPTH_MODE_PERSPECTIVE) +
                             define("SAO_DEPTH_MODE_ORTHOGRAPHIC", gen::SAO_DEPTH_MODE_ORTHOGRAPHIC) +
                             define("SAO_DEPTH_MODE_LINEAR", gen::SAO_DEPTH_MODE_LINEAR) +
                             readLibrary("sao_depth.glsl") + readLibrary("sao_blur.glsl") + R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Inputs { uint bits[]; };
layout(std430, binding = 1) writeonly buffer Outputs { uvec4 rounded[]; };
uniform uint count;
void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= count)
        return;
    float x = uintBitsToFloat(bits[i]);
    rounded[i] = uvec4(floatBitsToUint(sao_round_to_half(x)), floatBitsToUint(sao_round_to_half_signed(x)),
                       floatBitsToUint(sao_round_to_half_signed(-x)), 0u);
}
)";
  GLuint program = 0;
  const Status built = gl::buildProgram({{GL_COMPUTE_SHADER, source, "half_rounding.comp"}}, "half rounding", program);
  ASSERT_TRUE(built.ok()) << built.message;
  const std::vector<std::uint32_t> values = testValues();
  const auto n = static_cast<GLuint>(values.size());
  GLuint buffers[2];
  glCreateBuffers(2, buffers);
  glNamedBufferStorage(buffers[0], GLsizeiptr(n * 4), values.data(), 0);
  glNamedBufferStorage(buffers[1], GLsizeiptr(n * 16), nullptr, GL_MAP_READ_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
  glUseProgram(program);
  glUniform1ui(glGetUniformLocation(program, "count"), n);
  glDispatchCompute((n + 63) / 64, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<std::uint32_t> out(std::size_t(n) * 4);
  glGetNamedBufferSubData(buffers[1], 0, GLsizeiptr(n * 16), out.data());
  glUseProgram(0);
  glDeleteBuffers(2, buffers);
  glDeleteProgram(program);

  auto bitsOf = [](float f) {
    std::uint32_t b;
    std::memcpy(&b, &f, 4);
    return b;
  };
  std::size_t clamped = 0, checked = 0, bad = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    float x;
    std::memcpy(&x, &values[i], 4);
    const bool inUnit = x <= 1.0f;
    const std::uint32_t unsignedExpected = bitsOf(inUnit ? oracle(x) : 1.0f);  // clamped to [0, 1]
    clamped += !inUnit;
    const std::uint32_t got[3] = {out[4 * i], out[4 * i + 1], out[4 * i + 2]};
    const std::uint32_t want[3] = {unsignedExpected, bitsOf(oracle(x)), bitsOf(oracle(-x))};
    for (int k = 0; k < 3; ++k) {
      ++checked;
      if (got[k] != want[k] && ++bad <= 5)
        ADD_FAILURE() << "x = " << x << " (bits 0x" << std::hex << values[i] << "): function " << k << " gave 0x"
                      << got[k] << ", expected 0x" << want[k];
    }
    if (inUnit) EXPECT_EQ(bitsOf(cpu::roundToHalfAsShader(x)), unsignedExpected) << "CPU reference, x = " << x;
  }
  EXPECT_EQ(bad, 0u);
  std::printf("half rounding: %zu values (%zu above 1, clamped by sao_round_to_half), %zu results, %zu differ\n",
              values.size(), clamped, checked, bad);
}

}  // namespace
}  // namespace sao::gltest
