// The extended effect on OpenGL against the CPU reference, both compiled unchanged against it
// (the CPU reference runs ao_halve through cpu_passes.h, its oracle beside the GLSL). Bit for bit:
// GL's ao equals the CPU's (the extra pass changes nothing before it), GL's ao_half equals the
// CPU's Result::images[ao_half], and GL's ao_half equals GL's own ao times 0.5.
#include <gtest/gtest.h>

#include <bit>
#include <cstdio>
#include <memory>
#include <string>

#include "sao/cpu/reference.h"
#include "sao/gl/effect.h"
#include "sao/gl/headless.h"
#include "sao/gl/texture_io.h"
#include "walkthrough_case.h"

namespace sao::walkthrough {
namespace {

// Empty when a and b hold the same bits, else the count and the first differing texel.
std::string bitDifference(const FloatImage& actual, const FloatImage& expected) {
  if (actual.extent != expected.extent || actual.channels != expected.channels)
    return "extent or channels differ: " + std::to_string(actual.extent.width) + "x" +
           std::to_string(actual.extent.height) + "x" + std::to_string(actual.channels) + " against " +
           std::to_string(expected.extent.width) + "x" + std::to_string(expected.extent.height) + "x" +
           std::to_string(expected.channels);
  std::size_t count = 0, first = 0;
  for (std::size_t i = 0; i < actual.data.size(); ++i)
    if (std::bit_cast<std::uint32_t>(actual.data[i]) != std::bit_cast<std::uint32_t>(expected.data[i]) && count++ == 0)
      first = i;
  if (count == 0) return {};
  const std::size_t texel = first / actual.channels;
  return std::to_string(count) + " values differ; first at (" + std::to_string(texel % actual.extent.width) + ", " +
         std::to_string(texel / actual.extent.width) + "): " + std::to_string(actual.data[first]) + " against " +
         std::to_string(expected.data[first]);
}

FloatImage halved(const FloatImage& a) {
  FloatImage out = a;
  for (float& v : out.data) v *= 0.5f;  // exact: a binary16 value in [0, 1] halved is a float
  return out;
}

class ExtendedEffectOnGl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const Status st = gl::HeadlessContext::create(context_);
    if (!st) contextError_ = st.message;
  }
  static void TearDownTestSuite() { context_.reset(); }

  static std::unique_ptr<gl::HeadlessContext> context_;
  static std::string contextError_;
};
std::unique_ptr<gl::HeadlessContext> ExtendedEffectOnGl::context_;
std::string ExtendedEffectOnGl::contextError_;

TEST_F(ExtendedEffectOnGl, NewPassMatchesTheCpuReferenceBitForBit) {
  ASSERT_TRUE(context_) << "no headless GL context: " << contextError_;
  std::printf("GL: %s\n", context_->description().c_str());

  std::unique_ptr<gl::Effect> effect;
  const Status created = gl::Effect::create(gl::HeadlessContext::getProcAddress(), effect);
  ASSERT_TRUE(created.ok()) << created.message;

  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const DepthImage depth = caseDepth();
    cpu::Inputs cpuInputs;
    cpuInputs.depth = &depth;
    cpu::Result cpu;
    const Status ran = cpu::run(c.settings, caseCamera(), cpuInputs, {cpu::Precision::Float, 2}, cpu);
    ASSERT_TRUE(ran.ok()) << ran.message;
    const FloatImage& cpuAo = cpu.ao;
    const auto& cpuHalf = cpu.images[static_cast<std::size_t>(gen::ResourceId::ao_half)];
    ASSERT_EQ(cpuHalf.size(), 1u) << "the CPU reference ran the new pass into the new image";

    std::uint32_t depthTexture = 0;
    const Status up = gl::uploadDepth(depth, gl::GlDepth::D32F, depthTexture);
    ASSERT_TRUE(up.ok()) << up.message;
    gl::Inputs inputs;
    inputs.depth = {depthTexture, gl::kDepthComponent32F};
    const Status st = effect->render(caseCamera(), c.settings, inputs);
    ASSERT_TRUE(st.ok()) << st.message;
    ASSERT_EQ(effect->plan().passes.back().pass, gen::PassId::ao_halve);
    ASSERT_NE(effect->texture(gen::ResourceId::ao_half), 0u) << "the backend allocated the new image from the plan";
    const FloatImage ao = gl::readTexture(effect->aoTexture(), 1);
    const FloatImage half = gl::readTexture(effect->texture(gen::ResourceId::ao_half), 1);
    gl::deleteTexture(depthTexture);
    for (const gl::DebugMessage& m : context_->errors()) ADD_FAILURE() << gl::HeadlessContext::format(m);
    context_->clearMessages();

    // Not vacuous: the sphere and the floor occlude part of the image.
    std::size_t occluded = 0;
    for (float v : cpuAo.data) occluded += v < 0.9f;
    EXPECT_GT(occluded, cpuAo.data.size() / 50) << "the scene should darken some pixels";

    EXPECT_EQ(bitDifference(ao, cpuAo), "") << "GL ao against the CPU reference's, both of the extended effect";
    EXPECT_EQ(bitDifference(half, cpuHalf[0]), "") << "GL ao_half against the CPU reference's (its ao_halve oracle)";
    EXPECT_EQ(bitDifference(half, halved(ao)), "") << "GL ao_half against GL's own ao * 0.5";
  }
}

}  // namespace
}  // namespace sao::walkthrough
