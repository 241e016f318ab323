// sao::vk::Effect on bad input (docs/ROBUSTNESS.md), what only Vulkan has: other header versions, a
// VkInstance or VkPhysicalDevice of VK_NULL_HANDLE, a feature not enabled, multisampled depth, a
// depth format of VK_FORMAT_UNDEFINED, framesInFlight above the ring, empty destination stages,
// records refused for a bad format, sample count, setting or camera (the effect keeps its previous
// configuration), normals formats with too few channels at the first record, an
// input view also passed as the output view, a null output view, measure() on a null queue, and
// that a refused create() or first record() leaves no device memory. Every case must return the
// documented code with a message, raise no validation message (the fixture fails on any),
// allocate no device memory, and leave the device and the effect usable. Settings, cameras and
// sizes on both APIs: tests/executors/robustness_test.cpp.
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
    expectStatus(vk::Effect::create(ctx, c, e), code, needle);
    EXPECT_FALSE(e);
    EXPECT_EQ(vk::processMemoryStats().liveAllocations, before.liveAllocations) << needle;
  }
  // The first record() of a new effect (the one that plans) with `in`, `cam` and `s` fails with
  // `code` and names `needle`: nothing planned, no device memory beyond create()'s, nothing
  // recorded (a good record after it in the same command buffer, of inputs() through `goodCamera`,
  // works).
  void expectFirstRecordFails(const vk::Inputs& in, const Camera& cam, const Settings& s, StatusCode code,
                              const std::string& needle, const Camera* goodCamera = nullptr) {
    std::unique_ptr<vk::Effect> e;
    ASSERT_TRUE(vk::Effect::create(context().deviceContext(), config, e).ok());
    const vk::MemoryStats created = vk::processMemoryStats();
    const Status good = submitRecord([&](VkCommandBuffer cmd) {
      expectStatus(e->record(cmd, cam, s, in), code, needle);
      EXPECT_EQ(e->plans(), 0u) << needle;
      EXPECT_TRUE(e->plan().passes.empty()) << needle;
      EXPECT_EQ(vk::processMemoryStats().liveAllocations, created.liveAllocations) << needle;
      EXPECT_EQ(vk::processMemoryStats().liveBytes, created.liveBytes) << needle;
      return e->record(cmd, goodCamera ? *goodCamera : camera, settings, inputs());
    });
    EXPECT_TRUE(good.ok()) << good.message;
  }
  FloatImage run(vk::Effect& e) { return recordAndRead(e, camera, settings, inputs()); }

  Camera camera;
  Settings settings;  // the defaults
  DepthImage depth;
  Image image;
  Image normalsImage;  // passed by inputs() when set
  VkFormat normalsFormat = VK_FORMAT_UNDEFINED;
  vk::Config config;  // the defaults
};

// What a planned effect is: refused records must leave all of it as it was.
struct Snapshot {
  explicit Snapshot(const vk::Effect& e)
      : plans(e.plans()), aoExtent(e.plan().aoExtent), passes(e.plan().passes.size()), memory(e.memoryStats()),
        output(e.output().image), generation(e.outputGeneration()), params(e.params()) {}
  void expectSame(const vk::Effect& e, const std::string& what) const {
    EXPECT_EQ(e.plans(), plans) << what;
    EXPECT_EQ(e.plan().aoExtent, aoExtent) << what;
    EXPECT_EQ(e.plan().passes.size(), passes) << what;
    EXPECT_EQ(e.memoryStats().liveBytes, memory.liveBytes) << what;
    EXPECT_EQ(e.memoryStats().liveAllocations, memory.liveAllocations) << what;
    EXPECT_EQ(e.output().image, output) << what;
    EXPECT_EQ(e.outputGeneration(), generation) << what;
    EXPECT_EQ(std::memcmp(&e.params(), &params, sizeof params), 0) << what << ": params() is the last good record's";
  }
  std::uint64_t plans;
  Extent aoExtent;
  std::size_t passes;
  vk::MemoryStats memory;
  VkImage output;
  std::uint64_t generation;
  ParamBlock params;
};

TEST_F(VkRobustness, OtherHeaderVersionsAreRejected) {
  for (int version : {SAO_VERSION - 1, SAO_VERSION + (1 << 8), SAO_VERSION + (1 << 16), 0, -1}) {
    SCOPED_TRACE(version);
    std::unique_ptr<vk::Effect> e;
    expectStatus(vk::Effect::create(context().deviceContext(), config, e, version), StatusCode::VersionMismatch);
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
  EXPECT_TRUE(makeEffect(config)) << "the same physical device with the feature enabled is accepted";
}

// Multisampled depth is read directly (msaa_depth_test.cpp); sample counts (InputImage::samples)
// that are not one VkSampleCountFlagBits, or that the device cannot sample for the depth format,
// are refused by the record that would plan them.
TEST_F(VkRobustness, BadDepthSampleCountsAreRefused) {
  vk::Inputs in = inputs();
  for (int n : {0, 3, 5, 128}) {
    SCOPED_TRACE(n);
    in.depth.samples = static_cast<VkSampleCountFlagBits>(n);
    expectFirstRecordFails(in, camera, settings, StatusCode::InvalidInput,
                           "Inputs::depth.samples is " + std::to_string(n) + "; it must be one VkSampleCountFlagBits");
  }
  VkPhysicalDeviceProperties props{};
  vkGetPhysicalDeviceProperties(context().deviceContext().physicalDevice, &props);
  for (VkSampleCountFlagBits samples : {VK_SAMPLE_COUNT_2_BIT, VK_SAMPLE_COUNT_4_BIT, VK_SAMPLE_COUNT_8_BIT,
                                        VK_SAMPLE_COUNT_16_BIT, VK_SAMPLE_COUNT_32_BIT, VK_SAMPLE_COUNT_64_BIT}) {
    if (props.limits.sampledImageDepthSampleCounts & samples) continue;  // supported: the MSAA tests run it
    SCOPED_TRACE(int(samples));
    in.depth.samples = samples;
    expectFirstRecordFails(in, camera, settings, StatusCode::UnsupportedFormat, "sampledImageDepthSampleCounts");
  }
}

TEST_F(VkRobustness, BadConfigurationValues) {
  vk::Inputs in = inputs();
  in.depth.format = VK_FORMAT_UNDEFINED;  // a view cannot tell it
  expectFirstRecordFails(in, camera, settings, StatusCode::InvalidInput,
                         "Inputs::depth.format is VK_FORMAT_UNDEFINED: name the view's format");
  // Motion vectors only in the formats effect/sao.glsl lists (formats=), named in the refusal.
  Settings temporal = settings;
  temporal.temporal = true;
  in = inputs();
  in.motion = {image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, VK_FORMAT_R16_SFLOAT};
  expectFirstRecordFails(in, camera, temporal, StatusCode::UnsupportedFormat,
                         "Inputs::motion.format is VK_FORMAT_R16_SFLOAT; motion must be VK_FORMAT_R16G16_SFLOAT, "
                         "VK_FORMAT_R32G32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT or VK_FORMAT_R32G32B32A32_SFLOAT");
  vk::Config inFlight = config, stages = config, layout = config;
  inFlight.framesInFlight = 17, stages.outputDstStages = 0, layout.outputLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  for (const auto& [c, needle] : {std::pair{inFlight, "framesInFlight is 17"}, std::pair{stages, "outputDstStages is empty"},
                                  std::pair{layout, "outputLayout"}})
    expectCreateFails(context().deviceContext(), c, StatusCode::InvalidInput, needle);
}

// A first record() (the one that plans) refused for a setting, a camera or a size leaves no device
// memory beyond what create() made, and plans nothing (the codes and messages, and the same on a
// planned effect and on GL: tests/executors/robustness_test.cpp, which cannot see the process's
// device memory). The refused records share one effect and one command buffer: each is a first.
TEST_F(VkRobustness, RefusedFirstRecordLeavesNoMemory) {
  std::vector<std::pair<Settings, Camera>> bad;
  for (std::size_t i = 0; i < gen::kSettings.size(); ++i) {
    const SettingInfo& info = gen::kSettings[i];
    std::vector<double> values;
    if (info.type == gen::SettingType::Float) values = {kNaN, kInf, -kInf};
    if (info.type != gen::SettingType::Bool) values.insert(values.end(), {info.minValue - 1, info.maxValue + 1});
    for (double v : values) gen::setSettingValue(bad.emplace_back(settings, camera).first, static_cast<SettingId>(i), v);
  }
  for (int element : {0, 5, 10, 11, 14}) bad.emplace_back(settings, camera).second.projection[std::size_t(element)] = kNaN;
  bad.emplace_back(settings, camera).second.metersToViewUnits = kInf;
  const std::uint32_t beyond = context().properties().limits.maxImageDimension2D + 1;
  for (const std::array<std::uint32_t, 3>& size : std::initializer_list<std::array<std::uint32_t, 3>>{
           {beyond, 27, 0}, {48, beyond, 0}, {beyond - 5, 27, 4}, {0xFFFFFFFFu, 0xFFFFFFFFu, 0xFFFFFFFFu},
           {48, 27, 0x80000000u}, {0, 27, 4}}) {
    Camera& c = bad.emplace_back(settings, camera).second;
    c.width = size[0], c.height = size[1], c.guardBand = size[2];
  }
  auto e = makeEffect(config);
  ASSERT_TRUE(e);
  const vk::MemoryStats created = vk::processMemoryStats();
  const Status good = submitRecord([&](VkCommandBuffer cmd) {
    for (const auto& [s, c] : bad) {
      const Status st = e->record(cmd, c, s, inputs());
      EXPECT_FALSE(st.ok());
      EXPECT_FALSE(st.message.empty());
      EXPECT_EQ(e->plans(), 0u) << st.message;
      EXPECT_EQ(vk::processMemoryStats().liveAllocations, created.liveAllocations) << st.message;
      EXPECT_EQ(vk::processMemoryStats().liveBytes, created.liveBytes) << st.message;
    }
    return e->record(cmd, camera, settings, inputs());
  });
  EXPECT_TRUE(good.ok()) << "the effect plans after the refused records: " << good.message;
  EXPECT_GE(bad.size(), 50u);
}

// A record() that would plan again, refused for a bad setting, camera, size, sample count or
// depth format, returns the error and keeps the previous configuration: the plan, the images, the
// memory, the parameter block and the result stay what they were (bad settings and cameras, on
// both APIs: Robustness.RefusedFramesKeepThePreviousConfiguration in
// tests/executors/robustness_test.cpp).
TEST_F(VkRobustness, FailedRecordKeepsThePreviousConfiguration) {
  auto e = makeEffect(config);
  ASSERT_TRUE(e);
  const FloatImage before = run(*e);
  const Snapshot planned(*e);
  struct Bad { std::string what; Settings settings; Camera camera; vk::Inputs inputs; };
  std::vector<Bad> bad(5, Bad{"", settings, camera, inputs()});
  bad[0].what = "NaN radius", bad[0].settings.radius = float(kNaN);
  bad[1].what = "inf in the projection", bad[1].camera.projection[5] = kInf;
  bad[2].what = "width 2^32-1", bad[2].camera.width = 0xFFFFFFFFu;
  bad[3].what = "depth samples 3", bad[3].inputs.depth.samples = static_cast<VkSampleCountFlagBits>(3);
  bad[4].what = "depth R8G8B8A8_UNORM", bad[4].inputs.depth.format = VK_FORMAT_R8G8B8A8_UNORM;
  for (const Bad& b : bad) {
    const Status st = submitRecord([&](VkCommandBuffer cmd) { return e->record(cmd, b.camera, b.settings, b.inputs); });
    EXPECT_FALSE(st.ok()) << b.what;
    EXPECT_FALSE(st.message.empty()) << b.what;
    planned.expectSame(*e, b.what);
  }
  EXPECT_TRUE(sameBits(run(*e), before)) << "the effect renders as before the failed records";
  EXPECT_EQ(e->plans(), planned.plans) << "and keeps its plan";
}

// InputImage::format of the normals against Camera::normalsEncoding at the first record(): a
// two-channel format holds only the octahedral .xy, so an xyz encoding (which would read z = 0) is
// refused naming the format and the encoding; one channel is refused for every encoding (a refused
// record on a planned effect keeps it: Robustness.TwoChannelNormalsNeedAnOctahedralEncoding in
// tests/executors/robustness_test.cpp).
TEST_F(VkRobustness, NormalsFormatChannelsFollowTheEncoding) {
  const std::array<double, 9> rotation = test::viewRotation(0.7, -0.4, 0.25);
  Camera cam = camera;
  cam.viewRotation = rotation;
  // Octahedral normals of the scene in R16G16_SFLOAT: the image the records below are given.
  normalsFormat = VK_FORMAT_R16G16_SFLOAT;
  const FloatImage four = test::encodeNormals(test::renderNormals(test::sphereOnPlaneScene(), camera),
                                              NormalsEncoding::WorldOctahedral, rotation);
  FloatImage two(four.extent, 2);
  for (std::size_t i = 0; i < two.data.size() / 2; ++i) {
    two.data[2 * i] = four.data[4 * i];
    two.data[2 * i + 1] = four.data[4 * i + 1];
  }
  ASSERT_TRUE(context().uploadColor(two, normalsFormat, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, normalsImage).ok());

  Camera octahedral = cam;  // what the R16G16_SFLOAT normals hold: the good record after each refusal
  octahedral.normalsEncoding = NormalsEncoding::WorldOctahedral;
  for (auto [encoding, name] :
       {std::pair{NormalsEncoding::CameraXyz, "CameraXyz"}, std::pair{NormalsEncoding::WorldXyz, "WorldXyz"}}) {
    cam.normalsEncoding = encoding;
    expectFirstRecordFails(inputs(), cam, settings, StatusCode::UnsupportedFormat,
                           std::string("Inputs::normals.format is VK_FORMAT_R16G16_SFLOAT (two channels) but "
                                       "Camera::normalsEncoding is ") +
                               name + ", which reads .xyz: use an octahedral encoding or a three- or four-channel format",
                           &octahedral);
  }
  // The declared format is what is checked (a view cannot tell its own): R16_SFLOAT on the same view.
  vk::Inputs oneChannel = inputs();
  oneChannel.normals.format = VK_FORMAT_R16_SFLOAT;
  cam.normalsEncoding = NormalsEncoding::CameraOctahedral;
  expectFirstRecordFails(oneChannel, cam, settings, StatusCode::UnsupportedFormat,
                         "Inputs::normals.format is VK_FORMAT_R16_SFLOAT (one channel) but Camera::normalsEncoding is "
                         "CameraOctahedral, which reads .xy: use a two-, three- or four-channel format",
                         &octahedral);
  cam.normalsEncoding = NormalsEncoding::CameraXyz;
  expectFirstRecordFails(oneChannel, cam, settings, StatusCode::UnsupportedFormat,
                         "(one channel) but Camera::normalsEncoding is CameraXyz, which reads .xyz", &octahedral);
}

// A feedback loop (an input's view passed as the output view) and null output handles are refused
// and nothing is recorded; a good record in the same command buffer then works.
TEST_F(VkRobustness, OutputAlsoAnInputAndNullOutputHandles) {
  auto e = makeEffect(config);
  ASSERT_TRUE(e);
  const StorageOutput out(VK_FORMAT_R16_SFLOAT, {48, 27});
  const vk::OutputImage& good = out.output;
  vk::OutputImage depthView = good, nullView = good, nullImage = good;
  depthView.view = image.view;
  nullView.view = VK_NULL_HANDLE;
  nullImage.image = VK_NULL_HANDLE;
  const std::pair<vk::OutputImage, const char*> bad[] = {
      {depthView, "also Inputs::depth.view"}, {nullView, ""}, {nullImage, ""}};
  const Status fine = submitRecord([&](VkCommandBuffer cmd) {
    for (const auto& [o, needle] : bad)
      expectStatus(e->record(cmd, camera, settings, inputs(), &o), StatusCode::InvalidInput, needle);
    return e->record(cmd, camera, settings, inputs(), &good);
  });
  EXPECT_TRUE(fine.ok()) << fine.message;
  Timings t;
  const Status measured = e->measure(VK_NULL_HANDLE, camera, settings, inputs(), &good, t);
  EXPECT_EQ(measured.code, StatusCode::InvalidInput) << measured.message;
  EXPECT_TRUE(context().submit([&](VkCommandBuffer) {}).ok()) << "the device is still usable";
}

}  // namespace
}  // namespace sao::vktest
