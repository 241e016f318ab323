// The output (sao/output.h) on Vulkan, what only Vulkan has, under validation and synchronization
// validation: the caller's image transitioned from SHADER_READ_ONLY_OPTIMAL keeping its texels,
// the effect's own output in every output format, VkFormats and OutputImage formats and layouts
// refused, and outputGeneration() following the owned output image through the records that plan
// again. Every
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
};

constexpr const char* kFormatList = "R16_SFLOAT, R8_UNORM, R8G8B8A8_UNORM or R16G16B16A16_SFLOAT";

// An UnsupportedFormat naming VkFormat `f` and the formats the effect writes.
void expectFormatRefused(const Status& st, VkFormat f) {
  expectStatus(st, StatusCode::UnsupportedFormat, "VkFormat " + std::to_string(static_cast<int>(f)));
  EXPECT_NE(st.message.find(kFormatList), std::string::npos) << st.message;
}

// Creates an effect, uploads `texels` into a new storage image of `format` in
// SHADER_READ_ONLY_OPTIMAL (record() keeps or multiplies them from that layout), records `scene`
// once with `settings` and `in` into it (its OutputImage::format selecting the final pass) and
// reads the output back into `actual`. Returns false (after failed expectations) on any error.
bool recordIntoUserOutput(const Scene& scene, const Settings& settings, const vk::Inputs& in, VkFormat format,
                          const FloatImage& texels, FloatImage& actual) {
  auto effect = makeEffect();
  if (!effect) return false;
  Image out;
  const Status up = context().uploadColor(texels, format, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, out,
                                          VK_IMAGE_USAGE_STORAGE_BIT);
  EXPECT_TRUE(up.ok()) << up.message;
  if (!up.ok()) return false;
  const vk::OutputImage o{out.image, out.view, format, texels.extent, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  actual = recordAndRead(*effect, scene.camera, settings, in, &o);
  context().destroy(out);
  return !actual.data.empty();
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
      const Settings settings = settingsFor(divisor);
      const FloatImage sentinel = test::sentinelOutput({scene.camera.width, scene.camera.height}, oc.format);
      FloatImage actual;
      ASSERT_TRUE(recordIntoUserOutput(scene, settings, scene.inputs(oc.mask, oc.blend), vkOutput(oc.format), sentinel,
                                       actual));
      cpu::Inputs ci;
      ci.depth = &scene.depth;
      ci.outputFormat = oc.format;
      ci.outputChannels = oc.mask;
      ci.outputBlend = oc.blend;
      ci.output = &sentinel;
      cpu::Result ref;
      ASSERT_TRUE(cpu::run(settings, scene.camera, ci, {cpu::Precision::Float, 2}, ref).ok());
      test::checkOutput(actual, ref.ao, sentinel, oc.format, oc.mask, compare, name);
    }
}

// The effect's own output may have any of the formats too (every channel written).
TEST_F(OutputFormat, OwnedOutputInEveryFormat) {
  const Scene scene(96, 54, 4);
  for (gen::Format f : outputFormats()) {
    SCOPED_TRACE(formatName(f));
    vk::Config c;
    c.outputFormat = vkOutput(f);
    const Settings settings = settingsFor(1);
    auto effect = makeEffect(c);
    ASSERT_TRUE(effect);
    const FloatImage actual = recordAndRead(*effect, scene.camera, settings, scene.inputs());
    ASSERT_FALSE(actual.data.empty());
    EXPECT_EQ(effect->output().format, c.outputFormat);
    cpu::Inputs ci;
    ci.depth = &scene.depth;
    ci.outputFormat = f;
    cpu::Result ref;
    ASSERT_TRUE(cpu::run(settings, scene.camera, ci, {cpu::Precision::Float, 2}, ref).ok());
    test::checkOutput(actual, ref.ao, FloatImage(actual.extent, actual.channels), f, kAllChannels, compare,
                      std::string("vk_owned_") + formatName(f));
  }
}

TEST_F(OutputFormat, OtherFormatsAndLayoutsAreRefused) {
  const Scene scene(32, 18, 0);
  const Settings settings = settingsFor(1);
  for (VkFormat f : {VK_FORMAT_R32_SFLOAT, VK_FORMAT_R16G16_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_B8G8R8A8_UNORM,
                     VK_FORMAT_R8G8B8A8_SRGB}) {
    vk::Config c;
    c.outputFormat = f;
    std::unique_ptr<vk::Effect> e;
    expectFormatRefused(vk::Effect::create(context().deviceContext(), c, e), f);
    EXPECT_FALSE(e);
  }
  // An owned output in RGBA8 (Vulkan only): a mask keeping channels is refused by record() (every
  // other bad mask and blend: tests/executors/output_format_test.cpp).
  {
    vk::Config c;
    c.outputFormat = VK_FORMAT_R8G8B8A8_UNORM;
    auto effect = makeEffect(c);
    ASSERT_TRUE(effect) << "the mask is not part of the configuration";
    expectStatus(
        submitRecord([&](VkCommandBuffer cmd) { return effect->record(cmd, scene.camera, settings, scene.inputs(kChannelA)); }),
        StatusCode::InvalidInput,
        "record() Inputs: the output channel mask 8 keeps channels of the output, which only your own image has");
  }
  // record(): your image's OutputImage::format must be one the effect writes (the same list as
  // Config::outputFormat's, each named); kept channels need a real layout.
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  const StorageOutput storage(VK_FORMAT_R8G8B8A8_UNORM, {32, 18});
  const Image& out = storage.image;
  // A multiply reads every texel: an undefined layout is refused, naming the blend (the blend is
  // the record's).
  const vk::OutputImage undef{out.image, out.view, VK_FORMAT_R8G8B8A8_UNORM, {32, 18}};
  EXPECT_TRUE(submitRecord([&](VkCommandBuffer cmd) {
    for (VkFormat f : {VK_FORMAT_R32_SFLOAT, VK_FORMAT_B8G8R8A8_UNORM}) {
      const vk::OutputImage o{out.image, out.view, f, {32, 18}, VK_IMAGE_LAYOUT_GENERAL};
      expectFormatRefused(effect->record(cmd, scene.camera, settings, scene.inputs(), &o), f);
    }
    expectStatus(effect->record(cmd, scene.camera, settings, scene.inputs(kChannelB), &undef), StatusCode::InvalidInput,
                 "Inputs::outputChannels keeps channels of the output");
    return Status::success();
  }).ok());
  expectStatus(submitRecord([&](VkCommandBuffer cmd) {
                 return effect->record(cmd, scene.camera, settings, scene.inputs(kAllChannels, OutputBlend::Multiply),
                                       &undef);
               }),
               StatusCode::InvalidInput, "Inputs::outputBlend is multiply");
  EXPECT_EQ(effect->plans(), 0u) << "no refused record planned";
}

// outputGeneration() through records: 0 before the first plan, up with the first owned output, the
// same for new settings on the same images, up for a resize, the same after a refused record, up
// when the caller's output drops the owned one, the same while there is none, up when the owned
// one comes back; 0 for ever on an effect only ever given the caller's output.
TEST_F(OutputFormat, OutputGenerationFollowsTheOwnedImage) {
  const Scene small(32, 18, 0), large(48, 27, 0);
  Settings settings = settingsFor(1);
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  EXPECT_EQ(effect->outputGeneration(), 0u) << "create() plans nothing";
  const StorageOutput out(VK_FORMAT_R16_SFLOAT, {48, 27});
  const vk::OutputImage& user = out.output;
  auto record = [&](vk::Effect& e, const Scene& scene, const vk::OutputImage* o = nullptr) {
    return submitRecord([&](VkCommandBuffer cmd) { return e.record(cmd, scene.camera, settings, scene.inputs(), o); });
  };
  ASSERT_TRUE(record(*effect, small).ok());
  const std::uint64_t g1 = effect->outputGeneration();
  EXPECT_EQ(g1, 1u) << "the first plan made the owned output";
  settings.intensity = 0.7f;  // a new plan that changes no image
  const std::uint64_t plans = effect->plans();
  ASSERT_TRUE(record(*effect, small).ok());
  EXPECT_EQ(effect->plans(), plans + 1) << "new settings plan again";
  EXPECT_EQ(effect->outputGeneration(), g1) << "new settings, same images";
  ASSERT_TRUE(record(*effect, large).ok());
  const std::uint64_t g2 = effect->outputGeneration();
  EXPECT_GT(g2, g1) << "a resize makes a new output image";
  EXPECT_EQ(effect->output().extent, (Extent{48, 27}));
  const VkImage owned = effect->output().image;
  vk::OutputImage bad = user;
  bad.format = VK_FORMAT_R32_SFLOAT;
  EXPECT_EQ(record(*effect, large, &bad).code, StatusCode::UnsupportedFormat);
  EXPECT_EQ(effect->outputGeneration(), g2) << "a refused record changes nothing";
  EXPECT_EQ(effect->output().image, owned);
  ASSERT_TRUE(record(*effect, large, &user).ok());
  const std::uint64_t g3 = effect->outputGeneration();
  EXPECT_GT(g3, g2) << "the owned output is dropped for the caller's";
  EXPECT_EQ(effect->output().image, VK_NULL_HANDLE);
  settings.intensity = 0.9f;
  ASSERT_TRUE(record(*effect, large, &user).ok());
  EXPECT_EQ(effect->outputGeneration(), g3) << "no owned output, nothing changes";
  ASSERT_TRUE(record(*effect, large).ok());
  EXPECT_GT(effect->outputGeneration(), g3) << "an owned output again is a new image";
  EXPECT_NE(effect->output().image, VK_NULL_HANDLE);
  auto userOnly = makeEffect();
  ASSERT_TRUE(userOnly);
  ASSERT_TRUE(record(*userOnly, large, &user).ok());
  EXPECT_EQ(userOnly->outputGeneration(), 0u) << "never an owned output";
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
