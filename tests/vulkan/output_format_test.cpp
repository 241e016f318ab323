// The output (sao/output.h) on Vulkan, what only Vulkan has, under validation and synchronization
// validation: the caller's image transitioned from SHADER_READ_ONLY_OPTIMAL keeping its texels,
// the effect's own output in every output format, VkFormats and OutputImage formats and layouts
// refused, and outputGeneration() following the owned output image through update(). Every
// format, mask and blend against the CPU reference, the HDR multiply, bad masks and blends and
// outputGeneration() per frame on both APIs: tests/executors/output_format_test.cpp.
#include <string>

#include "analytic_scenes.h"
#include "output_format_check.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

using vk::headless::Image;

VkFormat vkOutput(gen::Format f) {
  switch (f) {
    case gen::Format::R16F: return VK_FORMAT_R16_SFLOAT;
    case gen::Format::R8: return VK_FORMAT_R8_UNORM;
    case gen::Format::RGBA8: return VK_FORMAT_R8G8B8A8_UNORM;
    case gen::Format::RGBA16F: return VK_FORMAT_R16G16B16A16_SFLOAT;
    default: return VK_FORMAT_UNDEFINED;
  }
}

Settings settingsFor(int divisor) {
  Settings s = presetSettings(Preset::Medium);
  s.resolution_divisor = divisor;
  return s;
}

struct Scene {
  Camera camera;
  DepthImage depth;
  Image image;
  Scene(std::uint32_t w, std::uint32_t h, std::uint32_t guard)
      : camera(vulkanCamera(w, h, guard, INFINITY, /*reversedZ=*/true)) {
    depth = test::renderDepth(test::sphereOnPlaneScene(), camera, DepthFormat::D32F);
    const Status st = context().uploadDepth(depth, VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, image);
    EXPECT_TRUE(st.ok()) << st.message;
  }
  ~Scene() { context().destroy(image); }
  vk::Inputs inputs(std::uint32_t channels = kAllChannels, OutputBlend blend = OutputBlend::Replace) const {
    vk::Inputs in;
    in.depth = {image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, VK_FORMAT_D32_SFLOAT};
    in.outputChannels = channels;
    in.outputBlend = blend;
    return in;
  }
  vk::Config config(int divisor) const {
    vk::Config c;
    c.camera = camera;
    c.settings = settingsFor(divisor);
    c.depthFormat = VK_FORMAT_D32_SFLOAT;
    return c;
  }
};

std::unique_ptr<vk::Effect> makeEffect(const vk::Config& config) {
  std::unique_ptr<vk::Effect> e;
  const Status st = vk::Effect::create(context().deviceContext(), config, e);
  EXPECT_TRUE(st.ok()) << st.message;
  return e;
}

// Creates the effect for `c` (a user output), uploads `texels` into a new storage image in
// SHADER_READ_ONLY_OPTIMAL (record() keeps or multiplies them from that layout), records once with
// `in` and reads the output back into `actual`. Returns false (after failed expectations) on any
// error.
bool recordIntoUserOutput(const vk::Inputs& in, const vk::Config& c, const FloatImage& texels, FloatImage& actual) {
  auto effect = makeEffect(c);
  if (!effect) return false;
  Image out;
  const Status up = context().uploadColor(texels, c.outputFormat, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, out,
                                          VK_IMAGE_USAGE_STORAGE_BIT);
  EXPECT_TRUE(up.ok()) << up.message;
  if (!up.ok()) return false;
  const vk::OutputImage o{out.image, out.view, c.outputFormat, texels.extent, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  Status recorded;
  const Status submitted = context().submit([&](VkCommandBuffer cmd) { recorded = effect->record(cmd, in, &o); });
  EXPECT_TRUE(submitted.ok() && recorded.ok()) << submitted.message << recorded.message;
  const Status read = context().readback(out.image, c.outputFormat, texels.extent, 0, c.outputLayout, c.outputDstStages,
                                         c.outputDstAccess, actual);
  EXPECT_TRUE(read.ok()) << read.message;
  context().destroy(out);
  return submitted.ok() && recorded.ok() && read.ok();
}

class OutputFormat : public VkTest {};

// The caller's image in SHADER_READ_ONLY_OPTIMAL (the shared suite's is in GENERAL): the kept
// channels and the multiplied texels survive record()'s transition from the caller's layout.
TEST_F(OutputFormat, KeptTexelsSurviveTheTransitionFromTheCallersLayout) {
  const Scene scene(160, 90, 8);
  for (int divisor : {1, 2})
    for (const test::OutputCase& oc : test::kOutputCases) {
      if (!keepsChannels(oc.format, oc.mask, oc.blend)) continue;
      const std::string name = "vk_read_only_" + test::caseName(oc) + "_d" + std::to_string(divisor);
      SCOPED_TRACE(name);
      vk::Config c = scene.config(divisor);
      c.userOutput = true;
      c.outputFormat = vkOutput(oc.format);
      const FloatImage sentinel = test::sentinelOutput({scene.camera.width, scene.camera.height}, oc.format);
      FloatImage actual;
      ASSERT_TRUE(recordIntoUserOutput(scene.inputs(oc.mask, oc.blend), c, sentinel, actual));
      cpu::Inputs ci;
      ci.depth = &scene.depth;
      ci.outputFormat = oc.format;
      ci.outputChannels = oc.mask;
      ci.outputBlend = oc.blend;
      ci.output = &sentinel;
      cpu::Result ref;
      ASSERT_TRUE(cpu::run(c.settings, scene.camera, ci, {cpu::Precision::Float, 2}, ref).ok());
      test::checkOutput(actual, ref.ao, sentinel, oc.format, oc.mask, compare, name);
    }
}

// The effect's own output may have any of the formats too (every channel written).
TEST_F(OutputFormat, OwnedOutputInEveryFormat) {
  const Scene scene(96, 54, 4);
  for (gen::Format f : outputFormats()) {
    SCOPED_TRACE(formatName(f));
    vk::Config c = scene.config(1);
    c.outputFormat = vkOutput(f);
    auto effect = makeEffect(c);
    ASSERT_TRUE(effect);
    Status recorded;
    ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = effect->record(cmd, scene.inputs()); }).ok());
    ASSERT_TRUE(recorded.ok()) << recorded.message;
    const vk::OutputImage o = effect->output();
    EXPECT_EQ(o.format, c.outputFormat);
    FloatImage actual;
    ASSERT_TRUE(context().readback(o.image, o.format, o.extent, 0, o.layout, c.outputDstStages, c.outputDstAccess, actual).ok());
    cpu::Inputs ci;
    ci.depth = &scene.depth;
    ci.outputFormat = f;
    cpu::Result ref;
    ASSERT_TRUE(cpu::run(c.settings, scene.camera, ci, {cpu::Precision::Float, 2}, ref).ok());
    test::checkOutput(actual, ref.ao, FloatImage(actual.extent, actual.channels), f, kAllChannels, compare,
                      std::string("vk_owned_") + formatName(f));
  }
}

TEST_F(OutputFormat, OtherFormatsAndLayoutsAreRefused) {
  const Scene scene(32, 18, 0);
  for (VkFormat f : {VK_FORMAT_R32_SFLOAT, VK_FORMAT_R16G16_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_B8G8R8A8_UNORM,
                     VK_FORMAT_R8G8B8A8_SRGB}) {
    vk::Config c = scene.config(1);
    c.outputFormat = f;
    std::unique_ptr<vk::Effect> e;
    const Status st = vk::Effect::create(context().deviceContext(), c, e);
    EXPECT_EQ(st.code, StatusCode::UnsupportedFormat) << st.message;
    EXPECT_NE(st.message.find("VkFormat " + std::to_string(static_cast<int>(f))), std::string::npos) << st.message;
    EXPECT_NE(st.message.find("R16_SFLOAT, R8_UNORM, R8G8B8A8_UNORM or R16G16B16A16_SFLOAT"), std::string::npos)
        << st.message;
    EXPECT_FALSE(e);
  }
  // An owned output in RGBA8 (Vulkan only): a mask keeping channels is refused by record() (every
  // other bad mask and blend: tests/executors/output_format_test.cpp).
  {
    vk::Config c = scene.config(1);
    c.outputFormat = VK_FORMAT_R8G8B8A8_UNORM;
    auto effect = makeEffect(c);
    ASSERT_TRUE(effect) << "the mask is not part of the configuration";
    Status st;
    ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { st = effect->record(cmd, scene.inputs(kChannelA)); }).ok());
    EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
    EXPECT_NE(st.message.find("record() Inputs: the output channel mask 8 keeps channels of the output, which only your "
                              "own image has"),
              std::string::npos)
        << st.message;
  }
  // record(): the image's format must be the configured one; kept channels need a real layout.
  vk::Config c = scene.config(1);
  c.userOutput = true;
  c.outputFormat = VK_FORMAT_R8G8B8A8_UNORM;
  auto effect = makeEffect(c);
  ASSERT_TRUE(effect);
  Image out;
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R8G8B8A8_UNORM, {32, 18}, out).ok());
  Status wrongFormat, undefinedLayout;
  ASSERT_TRUE(context()
                  .submit([&](VkCommandBuffer cmd) {
                    const vk::OutputImage f16{out.image, out.view, VK_FORMAT_R16_SFLOAT, {32, 18}, VK_IMAGE_LAYOUT_GENERAL};
                    wrongFormat = effect->record(cmd, scene.inputs(kChannelB), &f16);
                    const vk::OutputImage undef{out.image, out.view, VK_FORMAT_R8G8B8A8_UNORM, {32, 18}};
                    undefinedLayout = effect->record(cmd, scene.inputs(kChannelB), &undef);
                  })
                  .ok());
  EXPECT_EQ(wrongFormat.code, StatusCode::UnsupportedFormat) << wrongFormat.message;
  EXPECT_NE(wrongFormat.message.find("r16f"), std::string::npos) << wrongFormat.message;
  EXPECT_EQ(undefinedLayout.code, StatusCode::InvalidInput) << undefinedLayout.message;
  EXPECT_NE(undefinedLayout.message.find("Inputs::outputChannels keeps channels of the output"), std::string::npos)
      << undefinedLayout.message;
  // A multiply reads every texel: an undefined layout is refused, naming the blend (no update():
  // the blend is the record's).
  Status multiplyUndefined;
  ASSERT_TRUE(context()
                  .submit([&](VkCommandBuffer cmd) {
                    const vk::OutputImage undef{out.image, out.view, VK_FORMAT_R8G8B8A8_UNORM, {32, 18}};
                    multiplyUndefined = effect->record(cmd, scene.inputs(kAllChannels, OutputBlend::Multiply), &undef);
                  })
                  .ok());
  EXPECT_EQ(multiplyUndefined.code, StatusCode::InvalidInput) << multiplyUndefined.message;
  EXPECT_NE(multiplyUndefined.message.find("Inputs::outputBlend is multiply"), std::string::npos)
      << multiplyUndefined.message;
  context().destroy(out);
}

TEST_F(OutputFormat, OutputGenerationFollowsTheOwnedImage) {
  const Scene small(32, 18, 0);
  vk::Config c = small.config(1);
  auto effect = makeEffect(c);
  ASSERT_TRUE(effect);
  const std::uint64_t g1 = effect->outputGeneration();
  EXPECT_EQ(g1, 1u) << "create() made the owned output";
  c.settings.intensity = 0.7f;  // changes no image
  ASSERT_TRUE(effect->update(c).ok());
  EXPECT_EQ(effect->outputGeneration(), g1) << "new settings, same images";
  c.camera = vulkanCamera(48, 27, 0, INFINITY, true);
  ASSERT_TRUE(effect->update(c).ok());
  const std::uint64_t g2 = effect->outputGeneration();
  EXPECT_GT(g2, g1) << "a resize makes a new output image";
  EXPECT_EQ(effect->output().extent, (Extent{48, 27}));
  c.outputFormat = VK_FORMAT_R8_UNORM;
  ASSERT_TRUE(effect->update(c).ok());
  const std::uint64_t g3 = effect->outputGeneration();
  EXPECT_GT(g3, g2) << "a new output format makes a new output image";
  EXPECT_EQ(effect->output().format, VK_FORMAT_R8_UNORM);
  vk::Config bad = c;
  bad.outputFormat = VK_FORMAT_R32_SFLOAT;
  EXPECT_FALSE(effect->update(bad).ok());
  EXPECT_EQ(effect->outputGeneration(), g3) << "a failed update() changes nothing";
  c.userOutput = true;
  ASSERT_TRUE(effect->update(c).ok());
  const std::uint64_t g4 = effect->outputGeneration();
  EXPECT_GT(g4, g3) << "the owned output is dropped for the caller's";
  EXPECT_EQ(effect->output().image, VK_NULL_HANDLE);
  c.settings.intensity = 0.9f;
  ASSERT_TRUE(effect->update(c).ok());
  EXPECT_EQ(effect->outputGeneration(), g4) << "no owned output, nothing changes";
  vk::Config own = small.config(1);
  own.userOutput = true;
  auto userOnly = makeEffect(own);
  ASSERT_TRUE(userOnly);
  EXPECT_EQ(userOnly->outputGeneration(), 0u) << "created without an owned output";
}

// The generated format table (codegen/src/formats.cpp) names the VkFormats Vulkan's own header has.
TEST(Formats, GeneratedTableNamesTheVkFormats) {
  using F = gen::Format;
  const std::pair<F, VkFormat> expected[] = {
      {F::R32F, VK_FORMAT_R32_SFLOAT},
      {F::RG32F, VK_FORMAT_R32G32_SFLOAT},
      {F::R16F, VK_FORMAT_R16_SFLOAT},
      {F::RG16F, VK_FORMAT_R16G16_SFLOAT},
      {F::RGBA16F, VK_FORMAT_R16G16B16A16_SFLOAT},
      {F::R8, VK_FORMAT_R8_UNORM},
      {F::RGBA8, VK_FORMAT_R8G8B8A8_UNORM},
      {F::RGBA32F, VK_FORMAT_R32G32B32A32_SFLOAT},
      {F::Depth, VK_FORMAT_D32_SFLOAT}};
  ASSERT_EQ(std::size(expected), gen::kFormatInfo.size());
  for (const auto& [format, vk] : expected)
    EXPECT_EQ(gen::formatInfo(format).vkFormat, std::uint32_t(vk)) << formatName(format);
}

}  // namespace
}  // namespace sao::vktest
