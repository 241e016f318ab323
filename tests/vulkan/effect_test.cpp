// sao::vk::Effect, what only Vulkan has: version and device checks, configurations and record()
// inputs only Vulkan takes, every input layout, the output layout, records sharing a command
// buffer and frames in flight, device memory, timestamps and measure(). What every API shares
// (bad settings, cameras and sizes, sky, every depth format, a change of settings or size from
// one record to the next, the caller's output, the variants) is tests/executors/effect_test.cpp.
// Runs under the validation layer with synchronization validation; any message fails the test.
#include "analytic_scenes.h"
#include "image_compare.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

using vk::headless::Image;

// A scene uploaded once, with the frame's camera and settings (what each record() gets), its
// inputs and a device-level Config.
struct Frame {
  Camera camera;
  Settings settings;  // the defaults
  DepthImage depth;
  Image image;
  VkFormat format;
  vk::Config config;
  VkImageLayout layout;

  Frame(std::uint32_t w, std::uint32_t h, VkDepth format_, const test::Scene& scene,
        VkImageLayout layout_ = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, std::uint32_t guard = 8)
      : camera(vulkanCamera(w, h, guard)), format(vkFormat(format_)), layout(layout_) {
    depth = test::renderDepth(scene, camera, cpuFormat(format_));
    const Status st = context().uploadDepth(depth, format, layout, image);
    EXPECT_TRUE(st.ok()) << st.message;
  }
  ~Frame() { context().destroy(image); }
  vk::Inputs inputs() const {
    vk::Inputs in;
    in.depth = {image.view, layout, depth.extent, format};
    return in;
  }
};

FloatImage runOnce(vk::Effect& effect, const Frame& f, const vk::OutputImage* userOutput = nullptr) {
  return recordAndRead(effect, f.camera, f.settings, f.inputs(), userOutput);
}

using test::sameBits;

class VkEffect : public VkTest {};

TEST_F(VkEffect, DeviceMemoryHoldsThePlan) {
  Frame f(64, 36, VkDepth::D32F, test::sphereOnPlaneScene());
  auto effect = makeEffect(f.config);
  ASSERT_TRUE(effect);
  runOnce(*effect, f);
  const auto stats = effect->memoryStats();
  EXPECT_GE(stats.liveAllocations, 1u);
  EXPECT_GE(stats.liveBytes, effect->plan().totalBytes);
  std::printf("device memory: %llu bytes in %llu allocation(s)\n", (unsigned long long)stats.liveBytes,
              (unsigned long long)stats.liveAllocations);
}

TEST_F(VkEffect, VersionMismatchIsReported) {
  std::unique_ptr<vk::Effect> e;
  expectStatus(vk::Effect::create(context().deviceContext(), {}, e, SAO_VERSION + 1), StatusCode::VersionMismatch, "0.1.1");
  EXPECT_FALSE(e);
}

TEST_F(VkEffect, BadDeviceContextIsReported) {
  for (int i = 0; i < 3; ++i) {
    vk::DeviceContext c = context().deviceContext();
    if (i == 0) c.getInstanceProcAddr = nullptr;
    if (i == 1) c.device = VK_NULL_HANDLE;
    if (i == 2) c.queueFamilyIndex = 99;
    std::unique_ptr<vk::Effect> e;
    EXPECT_EQ(vk::Effect::create(c, {}, e).code, StatusCode::InvalidInput) << i;
    EXPECT_FALSE(e) << i;
  }
}

// Bad settings, cameras and sizes (a radius of -1, a 20000-wide camera): Inputs.BadSettingsAndCamera
// in tests/executors/effect_test.cpp. The device-level Config is refused by create(); the input
// formats, which come with each record(), by the first record() (which plans): nothing planned,
// nothing recorded (a good record after them in the same command buffer renders as a fresh effect
// does).
TEST_F(VkEffect, BadConfigurationsAreReported) {
  Frame f(32, 18, VkDepth::D32F, test::planeScene(2.0));
  std::unique_ptr<vk::Effect> e;
  for (int i = 0; i < 2; ++i) {
    vk::Config c = f.config;
    if (i == 0) c.outputLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    if (i == 1) c.framesInFlight = 0;
    expectStatus(vk::Effect::create(context().deviceContext(), c, e), StatusCode::InvalidInput, "", std::to_string(i));
  }
  EXPECT_FALSE(e);

  auto fresh = makeEffect(f.config);
  ASSERT_TRUE(fresh);
  const FloatImage expected = runOnce(*fresh, f);
  auto effect = makeEffect(f.config);
  ASSERT_TRUE(effect);
  vk::Inputs rgba = f.inputs(), s8 = f.inputs(), normals = f.inputs();
  rgba.depth.format = VK_FORMAT_R8G8B8A8_UNORM;
  s8.depth.format = VK_FORMAT_S8_UINT;
  normals.normals = normals.depth;  // a view of the right size; its declared format is a depth one
  const std::pair<const char*, vk::Inputs> bad[] = {
      {"depth R8G8B8A8_UNORM", rgba}, {"depth S8_UINT", s8}, {"normals D32_SFLOAT", normals}};
  const Status good = submitRecord([&](VkCommandBuffer cmd) {
    for (const auto& [what, in] : bad)
      expectStatus(effect->record(cmd, f.camera, f.settings, in), StatusCode::UnsupportedFormat, "", what);
    return effect->record(cmd, f.camera, f.settings, f.inputs());
  });
  ASSERT_TRUE(good.ok()) << good.message;
  EXPECT_EQ(effect->plans(), 1u) << "the refused records planned nothing";
  EXPECT_TRUE(sameBits(readOutput(*effect), expected)) << "the refused records recorded nothing";
}

// Inputs of the wrong size: Inputs.DepthSizeMustBeViewportPlusGuard in tests/executors/effect_test.cpp.
// Refused records, after a good one planned the effect: nothing recorded and the configuration
// kept (the owned output stays; a good record after them renders as before).
TEST_F(VkEffect, BadInputsAreReportedAndNothingIsRecorded) {
  Frame f(32, 18, VkDepth::D32F, test::planeScene(2.0));
  auto effect = makeEffect(f.config);
  ASSERT_TRUE(effect);
  const FloatImage before = runOnce(*effect, f);
  const vk::OutputImage owned = effect->output();
  const std::uint64_t generation = effect->outputGeneration(), plans = effect->plans();
  const StorageOutput other(VK_FORMAT_R16_SFLOAT, {32, 18});
  const vk::OutputImage& userOut = other.output;
  vk::Inputs nullView = f.inputs(), layout = f.inputs(), undefined = f.inputs(), normals = f.inputs(),
             depth2 = f.inputs();
  nullView.depth.view = VK_NULL_HANDLE;
  layout.depth.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  undefined.depth.format = VK_FORMAT_UNDEFINED;  // required with a view: a view cannot tell its format
  normals.normals = {f.image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, f.depth.extent};
  depth2.depth2 = depth2.depth;
  depth2.depth2.format = VK_FORMAT_D16_UNORM;  // every depth layer has the depth's format
  vk::OutputImage size = userOut, format = userOut;
  size.extent = {16, 9};
  format.format = VK_FORMAT_R32_SFLOAT;
  const struct {
    const char* what;
    bool nullCommandBuffer;
    vk::Inputs in;
    const vk::OutputImage* out;
    StatusCode code;
  } bad[] = {{"null command buffer", true, f.inputs(), nullptr, StatusCode::InvalidInput},
             {"null depth view", false, nullView, nullptr, StatusCode::InvalidInput},
             {"layout", false, layout, nullptr, StatusCode::InvalidInput},
             {"depth format undefined", false, undefined, nullptr, StatusCode::InvalidInput},
             {"normals format undefined", false, normals, nullptr, StatusCode::InvalidInput},
             {"depth2 in another format", false, depth2, nullptr, StatusCode::InvalidInput},
             {"output size", false, f.inputs(), &size, StatusCode::InvalidInput},
             {"output format", false, f.inputs(), &format, StatusCode::UnsupportedFormat}};
  const Status good = submitRecord([&](VkCommandBuffer cmd) {
    for (const auto& b : bad)
      expectStatus(effect->record(b.nullCommandBuffer ? VK_NULL_HANDLE : cmd, f.camera, f.settings, b.in, b.out), b.code,
                   "", b.what);
    return effect->record(cmd, f.camera, f.settings, f.inputs());
  });
  EXPECT_TRUE(good.ok()) << good.message;
  EXPECT_EQ(effect->output().image, owned.image) << "the refused records kept the configuration";
  EXPECT_EQ(effect->outputGeneration(), generation);
  EXPECT_EQ(effect->plans(), plans) << "the good record kept the plan of the first";
  EXPECT_TRUE(sameBits(readOutput(*effect), before)) << "the refused records recorded nothing";
}

// Every input layout a sampled depth may be in gives what SHADER_READ_ONLY_OPTIMAL gives, bit for
// bit (every format in that layout: Effect.EveryDepthFormat in tests/executors/effect_test.cpp).
TEST_F(VkEffect, EveryDepthLayout) {
  const auto run = [](VkDepth format, VkImageLayout layout) {
    Frame f(48, 27, format, test::stairsScene(), layout);
    auto effect = makeEffect(f.config);
    return effect ? runOnce(*effect, f) : FloatImage{};
  };
  constexpr VkImageLayout kDS = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  for (const auto& [format, layout] : {std::pair{VkDepth::X8D24, kDS}, std::pair{VkDepth::D24S8, kDS},
                                       std::pair{VkDepth::D32F, kDS}, std::pair{VkDepth::D32FS8, kDS},
                                       std::pair{VkDepth::D32FS8, VK_IMAGE_LAYOUT_GENERAL}}) {
    SCOPED_TRACE(std::string(toString(format)) + " layout " + std::to_string(layout));
    EXPECT_TRUE(sameBits(run(format, layout), run(format, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)));
    expectNoMessages(toString(format));
  }
}

TEST_F(VkEffect, UserOutputInEitherLayoutMatchesTheOwnedOne) {
  Frame f(40, 24, VkDepth::D24S8, test::sphereOnPlaneScene(), VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
  auto owned = makeEffect(f.config);
  ASSERT_TRUE(owned);
  const FloatImage expected = runOnce(*owned, f);
  for (VkImageLayout layout : {VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}) {
    vk::Config c = f.config;
    c.outputLayout = layout;
    auto effect = makeEffect(c);
    ASSERT_TRUE(effect);
    const StorageOutput out(VK_FORMAT_R16_SFLOAT, {40, 24});
    const vk::OutputImage& o = out.output;
    EXPECT_TRUE(sameBits(runOnce(*effect, f, &o), expected));
    EXPECT_EQ(effect->output().image, VK_NULL_HANDLE);
    EXPECT_EQ(effect->plan().image(gen::ResourceId::ao), nullptr) << "the user's output is not allocated";
    EXPECT_EQ(effect->outputGeneration(), 0u) << "never an owned output";
    EXPECT_TRUE(sameBits(runOnce(*effect, f, &o), expected)) << "second frame";
  }
}

// Several records of one effect in one command buffer and across submissions: the barriers order
// every reuse of the effect's images (synchronization validation checks the hazards).
TEST_F(VkEffect, RepeatedRecordsAreHazardFree) {
  Frame f(48, 27, VkDepth::D32F, test::rodsScene());
  f.config.framesInFlight = 3;  // three records in one command buffer use three ring slots
  auto effect = makeEffect(f.config);
  ASSERT_TRUE(effect);
  const FloatImage once = runOnce(*effect, f);
  EXPECT_TRUE(submitRecord([&](VkCommandBuffer cmd) {
                Status st;
                for (int i = 0; i < 3 && st.ok(); ++i) st = effect->record(cmd, f.camera, f.settings, f.inputs());
                return st;
              }).ok());
  EXPECT_TRUE(sameBits(runOnce(*effect, f), once));
}

// Two records of alternating inputs pending at once in one command buffer (framesInFlight = 2)
// take their own descriptor-set ring slots: each reads its own depth (alternating frames one at a
// time: Effect.AlternatingInputsReadTheirOwnDepth in tests/executors/effect_test.cpp).
TEST_F(VkEffect, TwoPendingRecordsReadTheirOwnDepth) {
  Frame f1(48, 27, VkDepth::D32F, test::sphereOnPlaneScene());
  Frame f2(48, 27, VkDepth::D32F, test::stairsScene());
  auto effect = makeEffect(f1.config);
  ASSERT_TRUE(effect);
  const FloatImage e1 = runOnce(*effect, f1);
  const FloatImage e2 = runOnce(*effect, f2);
  auto ring = makeEffect(f1.config);
  ASSERT_TRUE(ring);
  const StorageOutput out1(VK_FORMAT_R16_SFLOAT, {48, 27}), out2(VK_FORMAT_R16_SFLOAT, {48, 27});
  const vk::OutputImage &o1 = out1.output, &o2 = out2.output;
  for (int round = 0; round < 3; ++round) {
    const Status st = submitRecord([&](VkCommandBuffer cmd) {
      const Status s1 = ring->record(cmd, f1.camera, f1.settings, f1.inputs(), &o1);
      return s1.ok() ? ring->record(cmd, f2.camera, f2.settings, f2.inputs(), &o2) : s1;
    });
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_TRUE(sameBits(readOutput(*ring, &o1), e1)) << "round " << round;
    EXPECT_TRUE(sameBits(readOutput(*ring, &o2), e2)) << "round " << round;
  }
  EXPECT_EQ(ring->plans(), 1u) << "both records of every round keep the first plan";
}

TEST_F(VkEffect, TimestampsAndFenceFallback) {
  Frame f(64, 36, VkDepth::D32F, test::sphereOnPlaneScene());
  vk::Config c = f.config;
  c.timestamps = true;
  auto effect = makeEffect(c);
  ASSERT_TRUE(effect);
  Timings t;
  EXPECT_FALSE(effect->timings(t).ok()) << "nothing recorded yet";
  if (effect->timestampsSupported()) {
    runOnce(*effect, f);
    ASSERT_TRUE(effect->timings(t).ok());
    EXPECT_EQ(t.method, TimingMethod::GpuTimestamps);
    ASSERT_EQ(t.passes.size(), effect->plan().passes.size());
    EXPECT_EQ(t.passes[0].pass, "linear_z");
    EXPECT_EQ(t.passes[1].pass, "ao_sample");
    for (const auto& p : t.passes) EXPECT_GE(p.milliseconds, 0.0) << p.pass;
    EXPECT_GT(t.totalMilliseconds(), 0.0);
  }
  for (auto method : {vk::MeasureMethod::Auto, vk::MeasureMethod::FenceClock}) {
    Timings m;
    const Status st = effect->measure(context().queue(), f.camera, f.settings, f.inputs(), nullptr, m, method);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(m.method, method == vk::MeasureMethod::FenceClock || !effect->timestampsSupported()
                            ? TimingMethod::FinishAndClock
                            : TimingMethod::GpuTimestamps);
    ASSERT_EQ(m.passes.size(), effect->plan().passes.size());
    EXPECT_GT(m.totalMilliseconds(), 0.0);
    std::printf("%s:", toString(m.method));
    for (const auto& p : m.passes) std::printf(" %s %.3f ms", p.pass.c_str(), p.milliseconds);
    std::printf("\n");
  }
  EXPECT_EQ(effect->plans(), 1u) << "measure() plans as record() does: the same frame, one plan";
  const FloatImage fromMeasure = readOutput(*effect);
  EXPECT_TRUE(sameBits(fromMeasure, runOnce(*effect, f))) << "measure() leaves the same result as record()";
}

// measure() before any record() plans the frame itself, as record() would (the effect's first
// plan), and leaves the output record() would write.
TEST_F(VkEffect, MeasureBeforeAnyRecordPlans) {
  Frame f(48, 27, VkDepth::D32F, test::sphereOnPlaneScene());
  auto effect = makeEffect(f.config);
  ASSERT_TRUE(effect);
  EXPECT_TRUE(effect->plan().passes.empty()) << "create() plans nothing";
  EXPECT_EQ(effect->plans(), 0u);
  Timings m;
  const Status st =
      effect->measure(context().queue(), f.camera, f.settings, f.inputs(), nullptr, m, vk::MeasureMethod::FenceClock);
  ASSERT_TRUE(st.ok()) << st.message;
  EXPECT_EQ(effect->plans(), 1u);
  ASSERT_EQ(m.passes.size(), effect->plan().passes.size());
  EXPECT_FALSE(m.passes.empty());
  const FloatImage measured = readOutput(*effect);
  auto recorded = makeEffect(f.config);
  ASSERT_TRUE(recorded);
  EXPECT_TRUE(sameBits(measured, runOnce(*recorded, f)));
}

}  // namespace
}  // namespace sao::vktest
