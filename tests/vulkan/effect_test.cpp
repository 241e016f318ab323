// sao::vk::Effect, what only Vulkan has: version and device checks, configurations and record()
// inputs only Vulkan takes, every input layout, the output layout, records sharing a command
// buffer and frames in flight, device memory, timestamps and measure(). What every API shares
// (bad settings, cameras and sizes, sky, every depth format, update() as a change of settings or
// size, the caller's output, the variants) is tests/executors/effect_test.cpp. Runs under the
// validation layer with synchronization validation; any message fails the test.
#include "analytic_scenes.h"
#include "image_compare.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

using vk::headless::Image;

// A scene uploaded once, with the matching config and inputs.
struct Frame {
  Camera camera;
  DepthImage depth;
  Image image;
  vk::Config config;
  VkImageLayout layout;

  Frame(std::uint32_t w, std::uint32_t h, VkDepth format, const test::Scene& scene,
        VkImageLayout layout_ = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, std::uint32_t guard = 8)
      : camera(vulkanCamera(w, h, guard)), layout(layout_) {
    depth = test::renderDepth(scene, camera, cpuFormat(format));
    const Status st = context().uploadDepth(depth, vkFormat(format), layout, image);
    EXPECT_TRUE(st.ok()) << st.message;
    config.camera = camera;
    config.depthFormat = vkFormat(format);
  }
  ~Frame() { context().destroy(image); }
  vk::Inputs inputs() const {
    vk::Inputs in;
    in.depth = {image.view, layout, depth.extent, config.depthFormat};
    return in;
  }
};

std::unique_ptr<vk::Effect> makeEffect(const vk::Config& config) {
  std::unique_ptr<vk::Effect> e;
  const Status st = vk::Effect::create(context().deviceContext(), config, e);
  EXPECT_TRUE(st.ok()) << st.message;
  return e;
}

// Records once, submits, reads the output back.
FloatImage runOnce(vk::Effect& effect, const vk::Inputs& in, const vk::OutputImage* userOutput = nullptr) {
  Status recorded;
  const Status st = context().submit([&](VkCommandBuffer cmd) { recorded = effect.record(cmd, in, userOutput); });
  EXPECT_TRUE(st.ok()) << st.message;
  EXPECT_TRUE(recorded.ok()) << recorded.message;
  const vk::OutputImage o = userOutput ? *userOutput : effect.output();
  const VkImageLayout layout = userOutput ? effect.config().outputLayout : o.layout;
  FloatImage ao;
  const Status rb = context().readback(o.image, o.format, o.extent, 0, layout, effect.config().outputDstStages,
                                       effect.config().outputDstAccess, ao);
  EXPECT_TRUE(rb.ok()) << rb.message;
  return ao;
}

using test::sameBits;

class VkEffect : public VkTest {};

// Device memory holds at least the plan's images.
TEST_F(VkEffect, DeviceMemoryHoldsThePlan) {
  Frame f(64, 36, VkDepth::D32F, test::sphereOnPlaneScene());
  auto effect = makeEffect(f.config);
  ASSERT_TRUE(effect);
  runOnce(*effect, f.inputs());
  const auto stats = effect->memoryStats();
  EXPECT_GE(stats.liveAllocations, 1u);
  EXPECT_GE(stats.liveBytes, effect->plan().totalBytes);
  std::printf("device memory: %llu bytes in %llu allocation(s)\n", (unsigned long long)stats.liveBytes,
              (unsigned long long)stats.liveAllocations);
}

TEST_F(VkEffect, VersionMismatchIsReported) {
  Frame f(32, 18, VkDepth::D32F, test::planeScene(2.0));
  std::unique_ptr<vk::Effect> e;
  const Status st = vk::Effect::create(context().deviceContext(), f.config, e, SAO_VERSION + 1);
  EXPECT_EQ(st.code, StatusCode::VersionMismatch) << st.message;
  EXPECT_FALSE(e);
  EXPECT_NE(st.message.find("0.1.1"), std::string::npos) << st.message;
}

TEST_F(VkEffect, BadDeviceContextIsReported) {
  Frame f(32, 18, VkDepth::D32F, test::planeScene(2.0));
  std::unique_ptr<vk::Effect> e;
  vk::DeviceContext c = context().deviceContext();
  c.getInstanceProcAddr = nullptr;
  EXPECT_EQ(vk::Effect::create(c, f.config, e).code, StatusCode::InvalidInput);
  c = context().deviceContext();
  c.device = VK_NULL_HANDLE;
  EXPECT_EQ(vk::Effect::create(c, f.config, e).code, StatusCode::InvalidInput);
  c = context().deviceContext();
  c.queueFamilyIndex = 99;
  const Status st = vk::Effect::create(c, f.config, e);
  EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
  EXPECT_FALSE(e);
}

// Bad settings, cameras and sizes: Inputs.BadSettingsAndCamera in tests/executors/effect_test.cpp.
TEST_F(VkEffect, BadConfigurationsAreReported) {
  Frame f(32, 18, VkDepth::D32F, test::planeScene(2.0));
  std::unique_ptr<vk::Effect> e;
  auto code = [&](vk::Config c) {
    const Status st = vk::Effect::create(context().deviceContext(), c, e);
    EXPECT_FALSE(st.message.empty() && !st.ok());
    return st.code;
  };
  vk::Config c = f.config;
  c.depthFormat = VK_FORMAT_R8G8B8A8_UNORM;
  EXPECT_EQ(code(c), StatusCode::UnsupportedFormat);
  c = f.config;
  c.depthFormat = VK_FORMAT_S8_UINT;
  EXPECT_EQ(code(c), StatusCode::UnsupportedFormat);
  c = f.config;
  c.normalsFormat = VK_FORMAT_D32_SFLOAT;
  EXPECT_EQ(code(c), StatusCode::UnsupportedFormat);
  c = f.config;
  c.outputLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  EXPECT_EQ(code(c), StatusCode::InvalidInput);
  c = f.config;
  c.framesInFlight = 0;
  EXPECT_EQ(code(c), StatusCode::InvalidInput);
  EXPECT_FALSE(e);
}

// Inputs of the wrong size: Inputs.DepthSizeMustBeViewportPlusGuard in tests/executors/effect_test.cpp.
TEST_F(VkEffect, BadInputsAreReportedAndNothingIsRecorded) {
  Frame f(32, 18, VkDepth::D32F, test::planeScene(2.0));
  auto effect = makeEffect(f.config);
  ASSERT_TRUE(effect);
  Image other;
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {32, 18}, other).ok());
  const vk::OutputImage userOut{other.image, other.view, VK_FORMAT_R16_SFLOAT, {32, 18}};
  std::vector<std::pair<std::string, Status>> results;
  const Status st = context().submit([&](VkCommandBuffer cmd) {
    vk::Inputs in = f.inputs();
    results.push_back({"null command buffer", effect->record(VK_NULL_HANDLE, in)});
    in.depth.view = VK_NULL_HANDLE;
    results.push_back({"null depth view", effect->record(cmd, in)});
    in = f.inputs();
    in.depth.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    results.push_back({"layout", effect->record(cmd, in)});
    in = f.inputs();
    in.depth.format = VK_FORMAT_D16_UNORM;  // the config says D32_SFLOAT
    results.push_back({"format", effect->record(cmd, in)});
    in = f.inputs();
    in.normals = in.depth;
    results.push_back({"normals not configured", effect->record(cmd, in)});
    in = f.inputs();
    in.depth2 = in.depth;
    results.push_back({"depth2 not configured", effect->record(cmd, in)});
    results.push_back({"output not configured", effect->record(cmd, f.inputs(), &userOut)});
  });
  ASSERT_TRUE(st.ok()) << st.message;
  for (const auto& [what, s] : results) {
    EXPECT_EQ(s.code, StatusCode::InvalidInput) << what << ": " << s.message;
    EXPECT_FALSE(s.message.empty()) << what;
  }

  vk::Config c = f.config;
  c.userOutput = true;
  auto withOutput = makeEffect(c);
  ASSERT_TRUE(withOutput);
  Status missing, wrongFormat, wrongSize;
  ASSERT_TRUE(context()
                  .submit([&](VkCommandBuffer cmd) {
                    missing = withOutput->record(cmd, f.inputs());
                    vk::OutputImage o = userOut;
                    o.format = VK_FORMAT_R32_SFLOAT;
                    wrongFormat = withOutput->record(cmd, f.inputs(), &o);
                    o = userOut;
                    o.extent = {16, 9};
                    wrongSize = withOutput->record(cmd, f.inputs(), &o);
                  })
                  .ok());
  EXPECT_EQ(missing.code, StatusCode::InvalidInput) << missing.message;
  EXPECT_EQ(wrongFormat.code, StatusCode::UnsupportedFormat) << wrongFormat.message;
  EXPECT_EQ(wrongSize.code, StatusCode::InvalidInput) << wrongSize.message;
  context().destroy(other);
}

// Every input layout a sampled depth may be in gives what SHADER_READ_ONLY_OPTIMAL gives, bit for
// bit (every format in that layout: Effect.EveryDepthFormat in tests/executors/effect_test.cpp).
TEST_F(VkEffect, EveryDepthLayout) {
  const auto run = [](VkDepth format, VkImageLayout layout) {
    Frame f(48, 27, format, test::stairsScene(), layout);
    auto effect = makeEffect(f.config);
    return effect ? runOnce(*effect, f.inputs()) : FloatImage{};
  };
  for (const auto& [format, layout] : {std::pair{VkDepth::X8D24, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL},
                                       std::pair{VkDepth::D24S8, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL},
                                       std::pair{VkDepth::D32F, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL},
                                       std::pair{VkDepth::D32FS8, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL},
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
  const FloatImage expected = runOnce(*owned, f.inputs());
  for (VkImageLayout layout : {VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}) {
    vk::Config c = f.config;
    c.userOutput = true;
    c.outputLayout = layout;
    auto effect = makeEffect(c);
    ASSERT_TRUE(effect);
    EXPECT_EQ(effect->output().image, VK_NULL_HANDLE);
    EXPECT_EQ(effect->plan().image(gen::ResourceId::ao), nullptr) << "the user's output is not allocated";
    Image out;
    ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {40, 24}, out).ok());
    const vk::OutputImage o{out.image, out.view, VK_FORMAT_R16_SFLOAT, {40, 24}};
    EXPECT_TRUE(sameBits(runOnce(*effect, f.inputs(), &o), expected));
    EXPECT_TRUE(sameBits(runOnce(*effect, f.inputs(), &o), expected)) << "second frame";
    context().destroy(out);
  }
}

// Several records of one effect in one command buffer and across submissions: the barriers order
// every reuse of the effect's images (synchronization validation checks the hazards).
TEST_F(VkEffect, RepeatedRecordsAreHazardFree) {
  Frame f(48, 27, VkDepth::D32F, test::rodsScene());
  f.config.framesInFlight = 3;  // three records in one command buffer use three ring slots
  auto effect = makeEffect(f.config);
  ASSERT_TRUE(effect);
  const FloatImage once = runOnce(*effect, f.inputs());
  Status a, b, c;
  ASSERT_TRUE(context()
                  .submit([&](VkCommandBuffer cmd) {
                    a = effect->record(cmd, f.inputs());
                    b = effect->record(cmd, f.inputs());
                    c = effect->record(cmd, f.inputs());
                  })
                  .ok());
  EXPECT_TRUE(a.ok() && b.ok() && c.ok());
  EXPECT_TRUE(sameBits(runOnce(*effect, f.inputs()), once));
}

// Two records of alternating inputs pending at once in one command buffer (framesInFlight = 2)
// take their own descriptor-set ring slots: each reads its own depth (alternating frames one at a
// time: Effect.AlternatingInputsReadTheirOwnDepth in tests/executors/effect_test.cpp).
TEST_F(VkEffect, TwoPendingRecordsReadTheirOwnDepth) {
  Frame f1(48, 27, VkDepth::D32F, test::sphereOnPlaneScene());
  Frame f2(48, 27, VkDepth::D32F, test::stairsScene());
  auto effect = makeEffect(f1.config);
  ASSERT_TRUE(effect);
  const FloatImage e1 = runOnce(*effect, f1.inputs());
  const FloatImage e2 = runOnce(*effect, f2.inputs());
  Image out1, out2;
  vk::Config c = f1.config;
  c.userOutput = true;
  auto ring = makeEffect(c);
  ASSERT_TRUE(ring);
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {48, 27}, out1).ok());
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {48, 27}, out2).ok());
  const vk::OutputImage o1{out1.image, out1.view, VK_FORMAT_R16_SFLOAT, {48, 27}};
  const vk::OutputImage o2{out2.image, out2.view, VK_FORMAT_R16_SFLOAT, {48, 27}};
  for (int round = 0; round < 3; ++round) {
    Status s1, s2;
    ASSERT_TRUE(context()
                    .submit([&](VkCommandBuffer cmd) {
                      s1 = ring->record(cmd, f1.inputs(), &o1);
                      s2 = ring->record(cmd, f2.inputs(), &o2);
                    })
                    .ok());
    ASSERT_TRUE(s1.ok() && s2.ok()) << s1.message << s2.message;
    FloatImage r1, r2;
    ASSERT_TRUE(context().readback(out1.image, VK_FORMAT_R16_SFLOAT, {48, 27}, 0, c.outputLayout, c.outputDstStages,
                                   c.outputDstAccess, r1).ok());
    ASSERT_TRUE(context().readback(out2.image, VK_FORMAT_R16_SFLOAT, {48, 27}, 0, c.outputLayout, c.outputDstStages,
                                   c.outputDstAccess, r2).ok());
    EXPECT_TRUE(sameBits(r1, e1)) << "round " << round;
    EXPECT_TRUE(sameBits(r2, e2)) << "round " << round;
  }
  context().destroy(out1);
  context().destroy(out2);
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
    runOnce(*effect, f.inputs());
    const Status st = effect->timings(t);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(t.method, TimingMethod::GpuTimestamps);
    ASSERT_EQ(t.passes.size(), effect->plan().passes.size());
    EXPECT_EQ(t.passes[0].pass, "linear_z");
    EXPECT_EQ(t.passes[1].pass, "ao_sample");
    for (const auto& p : t.passes) EXPECT_GE(p.milliseconds, 0.0) << p.pass;
    EXPECT_GT(t.totalMilliseconds(), 0.0);
  }
  for (auto method : {vk::MeasureMethod::Auto, vk::MeasureMethod::FenceClock}) {
    Timings m;
    const Status st = effect->measure(context().queue(), f.inputs(), nullptr, m, method);
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
  // measure() leaves the same result as record().
  const FloatImage fromMeasure = [&] {
    FloatImage ao;
    const auto o = effect->output();
    EXPECT_TRUE(context().readback(o.image, o.format, o.extent, 0, o.layout, c.outputDstStages, c.outputDstAccess, ao).ok());
    return ao;
  }();
  EXPECT_TRUE(sameBits(fromMeasure, runOnce(*effect, f.inputs())));
}

}  // namespace
}  // namespace sao::vktest
