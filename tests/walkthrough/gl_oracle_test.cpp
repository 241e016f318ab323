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

// Section 6: a new input (ao_scale, declared in extra_pass.glsl) given by the engine by name, with
// the backend and the CPU reference compiled unchanged: GL's ao_half equals the CPU's bit for bit
// and GL's own ao * 0.5 * scale (powers of two: every product exact).
TEST_F(ExtendedEffectOnGl, NewInputMatchesTheCpuReferenceBitForBit) {
  ASSERT_TRUE(context_) << "no headless GL context: " << contextError_;
  std::unique_ptr<gl::Effect> effect;
  const Status created = gl::Effect::create(gl::HeadlessContext::getProcAddress(), effect);
  ASSERT_TRUE(created.ok()) << created.message;
  const Case c = cases()[0];
  const DepthImage depth = caseDepth();
  FloatImage scale;
  scale.extent = depth.extent;
  scale.channels = 1;
  for (std::uint32_t y = 0; y < depth.extent.height; ++y)
    for (std::uint32_t x = 0; x < depth.extent.width; ++x) scale.data.push_back(0.25f * float(1u << ((x / 3 + y) % 4)));

  cpu::Inputs cpuInputs;
  cpuInputs.depth = &depth;
  cpuInputs.moreInputs[static_cast<std::size_t>(gen::ResourceId::ao_scale)] = &scale;
  cpu::Result cpu;
  const Status ran = cpu::run(c.settings, caseCamera(), cpuInputs, {cpu::Precision::Float, 2}, cpu);
  ASSERT_TRUE(ran.ok()) << ran.message;
  EXPECT_EQ(cpu.plan.variants[static_cast<std::size_t>(gen::VariantId::AO_SCALED)], 1);

  // The factors as an R32F texture (uploadDepth's linear-z path holds every float exactly).
  DepthImage scaleTexels{scale.extent, DepthFormat::LinearZ, {}, 1};
  for (float v : scale.data) scaleTexels.texels.push_back(std::bit_cast<std::uint32_t>(v));
  std::uint32_t depthTexture = 0, scaleTexture = 0;
  ASSERT_TRUE(gl::uploadDepth(depth, gl::GlDepth::D32F, depthTexture).ok());
  ASSERT_TRUE(gl::uploadDepth(scaleTexels, gl::GlDepth::R32F, scaleTexture).ok());
  gl::Inputs inputs;
  inputs.depth = {depthTexture, gl::kDepthComponent32F};
  inputs.ao_scale = scaleTexture;  // the generated member: nothing in sao::gl names it
  const Status st = effect->render(caseCamera(), c.settings, inputs);
  ASSERT_TRUE(st.ok()) << st.message;
  EXPECT_EQ(effect->plan().variants[static_cast<std::size_t>(gen::VariantId::AO_SCALED)], 1);
  const FloatImage ao = gl::readTexture(effect->aoTexture(), 1);
  const FloatImage half = gl::readTexture(effect->texture(gen::ResourceId::ao_half), 1);

  // A wrong format is refused with the declaration's list, as any input's.
  const std::uint32_t rgba16f = gl::makeTexture(gl::kRGBA16F, depth.extent);
  inputs.ao_scale = rgba16f;
  const Status refused = effect->render(caseCamera(), c.settings, inputs);
  EXPECT_EQ(refused.code, StatusCode::UnsupportedFormat);
  EXPECT_NE(refused.message.find("is GL_RGBA16F; ao_scale must be GL_R32F"), std::string::npos) << refused.message;
  for (std::uint32_t t : {depthTexture, scaleTexture, rgba16f}) gl::deleteTexture(t);
  for (const gl::DebugMessage& m : context_->errors()) ADD_FAILURE() << gl::HeadlessContext::format(m);
  context_->clearMessages();

  FloatImage expected = halved(ao);
  const Plan& plan = effect->plan();
  const std::uint32_t guard = caseCamera().guardBand;
  for (std::uint32_t y = 0; y < plan.aoExtent.height; ++y)
    for (std::uint32_t x = 0; x < plan.aoExtent.width; ++x)
      expected.data[std::size_t(y) * plan.aoExtent.width + x] *=
          scale.data[std::size_t(y + guard) * scale.extent.width + x + guard];
  const auto& cpuHalf = cpu.images[static_cast<std::size_t>(gen::ResourceId::ao_half)];
  ASSERT_EQ(cpuHalf.size(), 1u);
  EXPECT_EQ(bitDifference(half, cpuHalf[0]), "") << "GL ao_half against the CPU reference's, with the new input";
  EXPECT_EQ(bitDifference(half, expected), "") << "GL ao_half against GL's own ao * 0.5 * ao_scale";
  EXPECT_NE(bitDifference(half, halved(ao)), "") << "the input changed the result";
}

}  // namespace
}  // namespace sao::walkthrough
