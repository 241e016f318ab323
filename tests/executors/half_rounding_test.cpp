// The shader's binary16 rounding (sao_round_to_half, sao_round_to_half_signed in
// effect/include/sao_blur.glsl: integer operations on the float's bits) on each API against an
// independent oracle in double (round to the nearest multiple of the binary16 spacing, ties away
// from zero): every binary32 value whose 13 bits below binary16's mantissa are a tie, one step
// either side of it, or 0 / all ones, for every exponent from 2^-25 to 2^15 (binary16's range);
// every tie in the subnormal range; and a stride through all values below 1. The CPU reference's
// frexp form (roundToHalfAsShader) is checked against the same oracle, so GPU and CPU agree bit
// for bit wherever the effect stores a binary16 value. The shader is half_rounding.comp; Vulkan
// runs its SPIR-V, which the build makes (half_rounding_comp_spv.h).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "harness.h"

#if __has_include("gl_support.h")
#include <epoxy/gl.h>

#include "gl_support.h"
#include "sao/gl/program_build.h"
#endif
#if __has_include("vk_support.h")
#include "vk_support.h"
#if __has_include("half_rounding_comp_spv.h")
#include <stdint.h>  // uint32_t for glslangValidator's --vn header

#include "half_rounding_comp_spv.h"
#define SAO_HALF_ROUNDING_SPV 1
#endif
#endif

namespace sao::exectest {
namespace {

#ifndef SAO_EFFECT_INCLUDE_DIR  // the source tree's, from this file's place in it
#define SAO_EFFECT_INCLUDE_DIR (std::filesystem::path(__FILE__).parent_path() / "../../effect/include").string()
#endif

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << "cannot read " << path;
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

#if __has_include("gl_support.h")
// half_rounding.comp with each #include line replaced by the library file it names (GL has no
// include directive).
std::string glSource() {
  std::istringstream comp(readText(std::filesystem::path(__FILE__).parent_path() / "half_rounding.comp"));
  std::string source, line;
  while (std::getline(comp, line)) {
    if (line.rfind("#extension GL_GOOGLE_include_directive", 0) == 0) continue;
    if (line.rfind("#include \"", 0) == 0)
      line = readText(std::filesystem::path(SAO_EFFECT_INCLUDE_DIR) / line.substr(10, line.size() - 11));
    source += line + "\n";
  }
  return source;
}

std::vector<std::uint32_t> roundOnGl(const std::vector<std::uint32_t>& values) {
  GLuint program = 0;
  const Status built = gl::buildProgram({{GL_COMPUTE_SHADER, glSource(), "half_rounding.comp"}}, "half rounding", program);
  EXPECT_TRUE(built.ok()) << built.message;
  if (!built) return {};
  const auto n = GLsizeiptr(values.size());
  GLuint buffers[2];
  glCreateBuffers(2, buffers);
  glNamedBufferStorage(buffers[0], n * 4, values.data(), 0);
  glNamedBufferStorage(buffers[1], n * 16, nullptr, GL_MAP_READ_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
  glUseProgram(program);
  glDispatchCompute(GLuint(values.size() + 63) / 64, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<std::uint32_t> out(values.size() * 4);
  glGetNamedBufferSubData(buffers[1], 0, n * 16, out.data());
  glUseProgram(0);
  glDeleteBuffers(2, buffers);
  glDeleteProgram(program);
  return out;
}
#endif

#if SAO_HALF_ROUNDING_SPV
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"  // Vulkan's create-info structs
// The same dispatch on Vulkan: two host-visible storage buffers in one descriptor set.
std::vector<std::uint32_t> roundOnVulkan(const std::vector<std::uint32_t>& values) {
  struct Objects {
    vk::headless::Context& ctx = vktest::context();
    VkDevice d = ctx.device();
    vk::headless::Buffer in, out;
    VkShaderModule module = VK_NULL_HANDLE;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    ~Objects() {
      vkDestroyPipeline(d, pipeline, nullptr);
      vkDestroyPipelineLayout(d, layout, nullptr);
      vkDestroyDescriptorPool(d, pool, nullptr);
      vkDestroyDescriptorSetLayout(d, setLayout, nullptr);
      vkDestroyShaderModule(d, module, nullptr);
      ctx.destroy(in);
      ctx.destroy(out);
    }
  } o;
  const VkDeviceSize bytes = values.size() * 4;
  const VkDescriptorSetLayoutBinding bindings[2] = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT},
                                                    {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT}};
  const VkDescriptorPoolSize poolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2};
  const VkShaderModuleCreateInfo mi{.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
                                    .codeSize = sizeof kHalfRoundingSpv, .pCode = kHalfRoundingSpv};
  const VkDescriptorSetLayoutCreateInfo si{.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                           .bindingCount = 2, .pBindings = bindings};
  const VkDescriptorPoolCreateInfo pi{.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 1,
                                      .poolSizeCount = 1, .pPoolSizes = &poolSize};
  const VkPipelineLayoutCreateInfo li{.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, .setLayoutCount = 1,
                                      .pSetLayouts = &o.setLayout};
  if (!o.ctx.createBuffer(bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, o.in).ok() ||
      !o.ctx.createBuffer(bytes * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, o.out).ok() ||
      vkCreateShaderModule(o.d, &mi, nullptr, &o.module) != VK_SUCCESS ||
      vkCreateDescriptorSetLayout(o.d, &si, nullptr, &o.setLayout) != VK_SUCCESS ||
      vkCreateDescriptorPool(o.d, &pi, nullptr, &o.pool) != VK_SUCCESS ||
      vkCreatePipelineLayout(o.d, &li, nullptr, &o.layout) != VK_SUCCESS) {
    ADD_FAILURE() << "making the buffers, the shader module, the layouts or the pool failed";
    return {};
  }
  const VkComputePipelineCreateInfo ci{
      .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
      .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                .module = o.module, .pName = "main"},
      .layout = o.layout};
  const VkDescriptorSetAllocateInfo ai{.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                       .descriptorPool = o.pool, .descriptorSetCount = 1, .pSetLayouts = &o.setLayout};
  VkDescriptorSet set = VK_NULL_HANDLE;
  if (vkCreateComputePipelines(o.d, VK_NULL_HANDLE, 1, &ci, nullptr, &o.pipeline) != VK_SUCCESS ||
      vkAllocateDescriptorSets(o.d, &ai, &set) != VK_SUCCESS) {
    ADD_FAILURE() << "making the pipeline or the descriptor set failed";
    return {};
  }
  std::memcpy(o.in.mapped, values.data(), bytes);
  const VkDescriptorBufferInfo infos[2] = {{o.in.buffer, 0, VK_WHOLE_SIZE}, {o.out.buffer, 0, VK_WHOLE_SIZE}};
  VkWriteDescriptorSet writes[2];
  for (std::uint32_t b = 0; b < 2; ++b)
    writes[b] = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = set, .dstBinding = b, .descriptorCount = 1,
                 .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .pBufferInfo = &infos[b]};
  vkUpdateDescriptorSets(o.d, 2, writes, 0, nullptr);
  const Status st = o.ctx.submit([&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, o.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, o.layout, 0, 1, &set, 0, nullptr);
    vkCmdDispatch(cmd, std::uint32_t(values.size() + 63) / 64, 1, 1);
    const VkMemoryBarrier toHost{.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER, .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
                                 .dstAccessMask = VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0,
                         nullptr, 0, nullptr);
  });
  EXPECT_TRUE(st.ok()) << st.message;
  const auto* rounded = static_cast<const std::uint32_t*>(o.out.mapped);
  return st ? std::vector<std::uint32_t>(rounded, rounded + values.size() * 4) : std::vector<std::uint32_t>{};
}
#endif

using HalfRounding = ApiTest;
TEST_P(HalfRounding, ShaderBitsMatchTheOracle) {
  const std::vector<std::uint32_t> values = testValues();
  std::vector<std::uint32_t> out;
#if __has_include("gl_support.h")
  if (api() == Api::Gl) out = roundOnGl(values);
#endif
  if (api() == Api::Vulkan) {
#if SAO_HALF_ROUNDING_SPV
    out = roundOnVulkan(values);
#else
    FAIL() << "half_rounding_comp_spv.h (glslangValidator on half_rounding.comp, tests/executors/CMakeLists.txt) is "
              "not built into this program";
#endif
  }
  ASSERT_EQ(out.size(), values.size() * 4);

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
    if (inUnit) {
      EXPECT_EQ(bitsOf(cpu::roundToHalfAsShader(x)), unsignedExpected) << "CPU reference, x = " << x;
    }
  }
  EXPECT_EQ(bad, 0u);
  std::printf("%s half rounding: %zu values (%zu above 1, clamped by sao_round_to_half), %zu results, %zu differ\n",
              toString(api()), values.size(), clamped, checked, bad);
}
SAO_INSTANTIATE_APIS(HalfRounding);

}  // namespace
}  // namespace sao::exectest
