// sao::vk::Effect on bad input (docs/ROBUSTNESS.md), what only Vulkan has: other header versions, a
// VkInstance or VkPhysicalDevice of VK_NULL_HANDLE, a feature not enabled, multisampled depth, a
// depth format of VK_FORMAT_UNDEFINED, framesInFlight above the ring, empty destination stages,
// update() with a bad Vulkan configuration (the effect keeps its previous one), normals formats
// with too few channels at create() and update(), an input view also passed as the output view, a
// null output view, measure() on a null queue, and that a refused create() leaves no device memory.
// Every case must return the documented code with a message, raise no validation message (the
// fixture fails on any), allocate no device memory, and leave the device and the effect usable.
// Settings, cameras and sizes on both APIs: tests/executors/robustness_test.cpp.
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "image_compare.h"
#include "analytic_scenes.h"
#include "normal_encodings.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

using vk::headless::Image;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

using test::sameBits;

class VkRobustness : public VkTest {
 protected:
  void SetUp() override {
    VkTest::SetUp();
    camera = vulkanCamera(48, 27, 4);
    depth = test::renderDepth(test::sphereOnPlaneScene(), camera, DepthFormat::D32F);
    ASSERT_TRUE(context().uploadDepth(depth, VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, image).ok());
    config.camera = camera;
    config.depthFormat = VK_FORMAT_D32_SFLOAT;
  }
  void TearDown() override {
    context().destroy(normalsImage);
    context().destroy(image);
    VkTest::TearDown();
  }
  vk::Inputs inputs() const {
    vk::Inputs in;
    in.depth = {image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, VK_FORMAT_D32_SFLOAT};
    if (normalsImage.view != VK_NULL_HANDLE)
      in.normals = {normalsImage.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, normalsFormat};
    return in;
  }
  // create() fails with `code`, names `needle`, leaves `out` empty and no device memory behind.
  void expectCreateFails(const vk::DeviceContext& ctx, const vk::Config& c, StatusCode code, const std::string& needle) {
    const vk::MemoryStats before = vk::processMemoryStats();
    std::unique_ptr<vk::Effect> e;
    const Status st = vk::Effect::create(ctx, c, e);
    EXPECT_EQ(st.code, code) << toString(st.code) << ": " << st.message;
    EXPECT_NE(st.message.find(needle), std::string::npos) << "expected \"" << needle << "\" in: " << st.message;
    EXPECT_FALSE(e);
    EXPECT_EQ(vk::processMemoryStats().liveAllocations, before.liveAllocations) << st.message;
  }
  FloatImage run(vk::Effect& e, const vk::OutputImage* userOutput = nullptr) {
    Status recorded;
    EXPECT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = e.record(cmd, inputs(), userOutput); }).ok());
    EXPECT_TRUE(recorded.ok()) << recorded.message;
    const vk::OutputImage o = userOutput ? *userOutput : e.output();
    FloatImage ao;
    EXPECT_TRUE(context()
                    .readback(o.image, o.format, o.extent, 0, e.config().outputLayout, e.config().outputDstStages,
                              e.config().outputDstAccess, ao)
                    .ok());
    return ao;
  }

  Camera camera;
  DepthImage depth;
  Image image;
  Image normalsImage;  // passed by inputs() when set
  VkFormat normalsFormat = VK_FORMAT_UNDEFINED;
  vk::Config config;
};

TEST_F(VkRobustness, OtherHeaderVersionsAreRejected) {
  for (int version : {SAO_VERSION - 1, SAO_VERSION + (1 << 8), SAO_VERSION + (1 << 16), 0, -1}) {
    SCOPED_TRACE(version);
    std::unique_ptr<vk::Effect> e;
    const Status st = vk::Effect::create(context().deviceContext(), config, e, version);
    EXPECT_EQ(st.code, StatusCode::VersionMismatch) << st.message;
    EXPECT_FALSE(e);
  }
}

TEST_F(VkRobustness, NullInstanceOrPhysicalDevice) {
  vk::DeviceContext c = context().deviceContext();
  c.instance = VK_NULL_HANDLE;
  expectCreateFails(c, config, StatusCode::InvalidInput, "VK_NULL_HANDLE");
  c = context().deviceContext();
  c.physicalDevice = VK_NULL_HANDLE;
  expectCreateFails(c, config, StatusCode::InvalidInput, "VK_NULL_HANDLE");
}

// Supported is not enabled: a device created without shaderStorageImageExtendedFormats (on a
// physical device that has it) is refused, naming the feature; so is a context that does not say
// which features its device enabled.
TEST_F(VkRobustness, DeviceWithoutRequiredFeatureIsRefused) {
  vk::DeviceContext c = context().deviceContext();
  c.enabledFeatures = nullptr;
  expectCreateFails(c, config, StatusCode::InvalidInput, "DeviceContext::enabledFeatures is null");

  vk::headless::Options o;
  o.storageImageExtendedFormats = false;
  std::unique_ptr<vk::headless::Context> bare;
  ASSERT_TRUE(vk::headless::Context::create(o, bare).ok());
  const std::string needle = "created without the feature shaderStorageImageExtendedFormats";
  expectCreateFails(bare->deviceContext(), config, StatusCode::DriverError, needle);
  // The same physical device with the feature enabled is accepted.
  std::unique_ptr<vk::Effect> e;
  const Status st = vk::Effect::create(context().deviceContext(), config, e);
  EXPECT_TRUE(st.ok()) << st.message;
}

// Multisampled depth is read directly (msaa_depth_test.cpp); sample counts that are not one
// VkSampleCountFlagBits, or that the device cannot sample for the depth format, are refused.
TEST_F(VkRobustness, BadDepthSampleCountsAreRefused) {
  for (int n : {0, 3, 5, 128}) {
    vk::Config c = config;
    c.depthSamples = static_cast<VkSampleCountFlagBits>(n);
    expectCreateFails(context().deviceContext(), c, StatusCode::InvalidInput, "it must be one VkSampleCountFlagBits");
  }
  VkPhysicalDeviceProperties props{};
  vkGetPhysicalDeviceProperties(context().deviceContext().physicalDevice, &props);
  for (VkSampleCountFlagBits samples : {VK_SAMPLE_COUNT_2_BIT, VK_SAMPLE_COUNT_4_BIT, VK_SAMPLE_COUNT_8_BIT,
                                        VK_SAMPLE_COUNT_16_BIT, VK_SAMPLE_COUNT_32_BIT, VK_SAMPLE_COUNT_64_BIT}) {
    if (props.limits.sampledImageDepthSampleCounts & samples) continue;  // supported: the MSAA tests run it
    vk::Config c = config;
    c.depthSamples = samples;
    expectCreateFails(context().deviceContext(), c, StatusCode::UnsupportedFormat, "sampledImageDepthSampleCounts");
  }
}

TEST_F(VkRobustness, BadConfigurationValues) {
  vk::Config c = config;
  c.depthFormat = VK_FORMAT_UNDEFINED;
  expectCreateFails(context().deviceContext(), c, StatusCode::UnsupportedFormat, "Config::depthFormat");
  // Motion vectors only in the formats effect/sao.glsl lists (formats=), named in the refusal.
  c = config;
  c.settings.temporal = true;
  c.motionFormat = VK_FORMAT_R16_SFLOAT;
  expectCreateFails(context().deviceContext(), c, StatusCode::UnsupportedFormat,
                    "Config::motionFormat is VK_FORMAT_R16_SFLOAT; motion must be VK_FORMAT_R16G16_SFLOAT, "
                    "VK_FORMAT_R32G32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT or VK_FORMAT_R32G32B32A32_SFLOAT");
  c = config;
  c.framesInFlight = 17;
  expectCreateFails(context().deviceContext(), c, StatusCode::InvalidInput, "framesInFlight is 17");
  c = config;
  c.outputDstStages = 0;
  expectCreateFails(context().deviceContext(), c, StatusCode::InvalidInput, "outputDstStages is empty");
  c = config;
  c.outputLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  expectCreateFails(context().deviceContext(), c, StatusCode::InvalidInput, "outputLayout");
}

// A create() refused for a setting, a camera or a size leaves no device memory behind (the codes
// and messages, and the same through update() and GL: tests/executors/robustness_test.cpp, which
// cannot see the process's device memory).
TEST_F(VkRobustness, RefusedCreateLeavesNoMemory) {
  std::vector<vk::Config> bad;
  for (std::size_t i = 0; i < gen::kSettings.size(); ++i) {
    const SettingInfo& info = gen::kSettings[i];
    std::vector<double> values;
    if (info.type == gen::SettingType::Float) values = {kNaN, kInf, -kInf};
    if (info.type != gen::SettingType::Bool) values.insert(values.end(), {info.minValue - 1, info.maxValue + 1});
    for (double v : values) gen::setSettingValue(bad.emplace_back(config).settings, static_cast<SettingId>(i), v);
  }
  for (int element : {0, 5, 10, 11, 14}) bad.emplace_back(config).camera.projection[std::size_t(element)] = kNaN;
  bad.emplace_back(config).camera.metersToViewUnits = kInf;
  const std::uint32_t beyond = context().properties().limits.maxImageDimension2D + 1;
  for (const std::array<std::uint32_t, 3>& size : std::initializer_list<std::array<std::uint32_t, 3>>{
           {beyond, 27, 0}, {48, beyond, 0}, {beyond - 5, 27, 4}, {0xFFFFFFFFu, 0xFFFFFFFFu, 0xFFFFFFFFu},
           {48, 27, 0x80000000u}, {0, 27, 4}}) {
    vk::Config& c = bad.emplace_back(config);
    c.camera.width = size[0];
    c.camera.height = size[1];
    c.camera.guardBand = size[2];
  }
  for (const vk::Config& c : bad) {
    const vk::MemoryStats before = vk::processMemoryStats();
    std::unique_ptr<vk::Effect> e;
    const Status st = vk::Effect::create(context().deviceContext(), c, e);
    EXPECT_FALSE(st.ok());
    EXPECT_FALSE(e);
    EXPECT_EQ(vk::processMemoryStats().liveAllocations, before.liveAllocations) << st.message;
  }
  EXPECT_GE(bad.size(), 50u);
}

// update() with a bad Vulkan configuration returns the error and keeps the previous configuration:
// the images, the memory and the result stay what they were (bad settings and cameras, on both
// APIs: Robustness.RefusedFramesKeepThePreviousConfiguration in tests/executors/robustness_test.cpp).
TEST_F(VkRobustness, FailedUpdateKeepsThePreviousConfiguration) {
  std::unique_ptr<vk::Effect> e;
  ASSERT_TRUE(vk::Effect::create(context().deviceContext(), config, e).ok());
  const FloatImage before = run(*e);
  const vk::MemoryStats memory = e->memoryStats();
  std::vector<vk::Config> bad(3, config);
  bad[0].depthSamples = static_cast<VkSampleCountFlagBits>(3);
  bad[1].framesInFlight = 0;
  bad[2].depthFormat = VK_FORMAT_R8G8B8A8_UNORM;
  for (const vk::Config& c : bad) {
    const Status st = e->update(c);
    EXPECT_FALSE(st.ok());
    EXPECT_FALSE(st.message.empty());
    EXPECT_EQ(e->config().camera.width, config.camera.width);
    EXPECT_EQ(e->config().depthSamples, VK_SAMPLE_COUNT_1_BIT);
    EXPECT_EQ(e->memoryStats().liveBytes, memory.liveBytes);
  }
  EXPECT_TRUE(sameBits(run(*e), before)) << "the effect renders as before the failed updates";
}

// Config::normalsFormat channels against Camera::normalsEncoding, at create() and update(): a
// two-channel format holds only the octahedral .xy, so an xyz encoding (which would read z = 0) is
// refused naming the format and the encoding; one channel is refused for every encoding. A failed
// update() keeps the octahedral configuration, which renders from R16G16_SFLOAT as before.
TEST_F(VkRobustness, NormalsFormatChannelsFollowTheEncoding) {
  const std::array<double, 9> rotation = test::viewRotation(0.7, -0.4, 0.25);
  vk::Config c = config;
  c.camera.viewRotation = rotation;
  c.normalsFormat = VK_FORMAT_R16G16_SFLOAT;
  for (auto [encoding, name] :
       {std::pair{NormalsEncoding::CameraXyz, "CameraXyz"}, std::pair{NormalsEncoding::WorldXyz, "WorldXyz"}}) {
    c.camera.normalsEncoding = encoding;
    expectCreateFails(context().deviceContext(), c, StatusCode::UnsupportedFormat,
                      std::string("Config::normalsFormat is VK_FORMAT_R16G16_SFLOAT (two channels) but "
                                  "Camera::normalsEncoding is ") +
                          name + ", which reads .xyz: use an octahedral encoding or a three- or four-channel format");
  }
  c.normalsFormat = VK_FORMAT_R16_SFLOAT;
  c.camera.normalsEncoding = NormalsEncoding::CameraOctahedral;
  expectCreateFails(context().deviceContext(), c, StatusCode::UnsupportedFormat,
                    "Config::normalsFormat is VK_FORMAT_R16_SFLOAT (one channel) but Camera::normalsEncoding is "
                    "CameraOctahedral, which reads .xy: use a two-, three- or four-channel format");
  c.camera.normalsEncoding = NormalsEncoding::CameraXyz;
  expectCreateFails(context().deviceContext(), c, StatusCode::UnsupportedFormat,
                    "(one channel) but Camera::normalsEncoding is CameraXyz, which reads .xyz");

  // Octahedral normals of the scene in R16G16_SFLOAT: accepted, and kept through a refused update.
  c.normalsFormat = normalsFormat = VK_FORMAT_R16G16_SFLOAT;
  c.camera.normalsEncoding = NormalsEncoding::WorldOctahedral;
  const FloatImage four = test::encodeNormals(test::renderNormals(test::sphereOnPlaneScene(), camera),
                                              NormalsEncoding::WorldOctahedral, rotation);
  FloatImage two(four.extent, 2);
  for (std::size_t i = 0; i < two.data.size() / 2; ++i) {
    two.data[2 * i] = four.data[4 * i];
    two.data[2 * i + 1] = four.data[4 * i + 1];
  }
  ASSERT_TRUE(context().uploadColor(two, normalsFormat, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, normalsImage).ok());
  std::unique_ptr<vk::Effect> e;
  const Status created = vk::Effect::create(context().deviceContext(), c, e);
  ASSERT_TRUE(created.ok()) << created.message;
  const FloatImage before = run(*e);
  const vk::MemoryStats memory = e->memoryStats();
  vk::Config bad = c;
  bad.camera.normalsEncoding = NormalsEncoding::WorldXyz;
  const Status st = e->update(bad);
  EXPECT_EQ(st.code, StatusCode::UnsupportedFormat) << st.message;
  EXPECT_NE(st.message.find("VK_FORMAT_R16G16_SFLOAT (two channels) but Camera::normalsEncoding is WorldXyz"),
            std::string::npos)
      << st.message;
  EXPECT_EQ(e->config().camera.normalsEncoding, NormalsEncoding::WorldOctahedral);
  EXPECT_EQ(e->memoryStats().liveBytes, memory.liveBytes);
  EXPECT_TRUE(sameBits(run(*e), before)) << "the effect renders as before the failed update";
}

// A feedback loop (an input's view passed as the output view) and null output handles are refused
// and nothing is recorded; a good record in the same command buffer then works.
TEST_F(VkRobustness, OutputAlsoAnInputAndNullOutputHandles) {
  vk::Config c = config;
  c.userOutput = true;
  std::unique_ptr<vk::Effect> e;
  ASSERT_TRUE(vk::Effect::create(context().deviceContext(), c, e).ok());
  Image out;
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {48, 27}, out).ok());
  const vk::OutputImage good{out.image, out.view, VK_FORMAT_R16_SFLOAT, {48, 27}};
  std::vector<std::pair<std::string, Status>> results;
  Status fine;
  ASSERT_TRUE(context()
                  .submit([&](VkCommandBuffer cmd) {
                    vk::OutputImage o = good;
                    o.view = image.view;  // the depth view
                    results.push_back({"depth view as output", e->record(cmd, inputs(), &o)});
                    o = good;
                    o.view = VK_NULL_HANDLE;
                    results.push_back({"null output view", e->record(cmd, inputs(), &o)});
                    o = good;
                    o.image = VK_NULL_HANDLE;
                    results.push_back({"null output image", e->record(cmd, inputs(), &o)});
                    fine = e->record(cmd, inputs(), &good);
                  })
                  .ok());
  for (const auto& [what, st] : results) {
    EXPECT_EQ(st.code, StatusCode::InvalidInput) << what << ": " << st.message;
    EXPECT_FALSE(st.message.empty()) << what;
  }
  EXPECT_NE(results[0].second.message.find("also Inputs::depth.view"), std::string::npos) << results[0].second.message;
  EXPECT_TRUE(fine.ok()) << fine.message;
  Timings t;
  const Status measured = e->measure(VK_NULL_HANDLE, inputs(), &good, t);
  EXPECT_EQ(measured.code, StatusCode::InvalidInput) << measured.message;
  EXPECT_TRUE(context().submit([&](VkCommandBuffer) {}).ok()) << "the device is still usable";
  context().destroy(out);
}

}  // namespace
}  // namespace sao::vktest
