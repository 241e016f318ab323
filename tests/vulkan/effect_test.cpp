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

std::unique_ptr<vk::Effect> makeEffect(const vk::Config& config) {
  std::unique_ptr<vk::Effect> e;
  const Status st = vk::Effect::create(context().deviceContext(), config, e);
  EXPECT_TRUE(st.ok()) << st.message;
  return e;
}

// Records `f`'s camera and settings with `in` once, submits, reads the output back.
FloatImage runOnce(vk::Effect& effect, const Frame& f, const vk::Inputs& in,
                   const vk::OutputImage* userOutput = nullptr) {
  Status recorded;
  const Status st =
      context().submit([&](VkCommandBuffer cmd) { recorded = effect.record(cmd, f.camera, f.settings, in, userOutput); });
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
FloatImage runOnce(vk::Effect& effect, const Frame& f, const vk::OutputImage* userOutput = nullptr) {
  return runOnce(effect, f, f.inputs(), userOutput);
}

using test::sameBits;

class VkEffect : public VkTest {};

// Device memory holds at least the plan's images.
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

// Bad settings, cameras and sizes: Inputs.BadSettingsAndCamera in tests/executors/effect_test.cpp
// (here one of each: a radius of -1, a 20000-wide camera). The device-level Config is refused by
// create(); the settings, the camera and the input formats, which come with each record(), by the
// first record() (which plans): nothing planned, nothing recorded (a good record after them in the
// same command buffer renders as a fresh effect does).
TEST_F(VkEffect, BadConfigurationsAreReported) {
  Frame f(32, 18, VkDepth::D32F, test::planeScene(2.0));
  std::unique_ptr<vk::Effect> e;
  auto code = [&](vk::Config c) {
    const Status st = vk::Effect::create(context().deviceContext(), c, e);
    EXPECT_FALSE(st.message.empty() && !st.ok());
    return st.code;
  };
  vk::Config c = f.config;
  c.outputLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  EXPECT_EQ(code(c), StatusCode::InvalidInput);
  c = f.config;
  c.framesInFlight = 0;
  EXPECT_EQ(code(c), StatusCode::InvalidInput);
  EXPECT_FALSE(e);

  auto fresh = makeEffect(f.config);
  ASSERT_TRUE(fresh);
  const FloatImage expected = runOnce(*fresh, f);
  auto effect = makeEffect(f.config);
  ASSERT_TRUE(effect);
  std::vector<std::pair<std::string, Status>> results;
  Status badSetting, badSize, good;
  ASSERT_TRUE(context()
                  .submit([&](VkCommandBuffer cmd) {
                    Settings s = f.settings;
                    s.radius = -1;
                    badSetting = effect->record(cmd, f.camera, s, f.inputs());
                    Camera wide = f.camera;
                    wide.width = 20000;
                    badSize = effect->record(cmd, wide, f.settings, f.inputs());
                    vk::Inputs in = f.inputs();
                    in.depth.format = VK_FORMAT_R8G8B8A8_UNORM;
                    results.push_back({"depth R8G8B8A8_UNORM", effect->record(cmd, f.camera, f.settings, in)});
                    in.depth.format = VK_FORMAT_S8_UINT;
                    results.push_back({"depth S8_UINT", effect->record(cmd, f.camera, f.settings, in)});
                    in = f.inputs();
                    in.normals = in.depth;  // a view of the right size; its declared format is a depth one
                    results.push_back({"normals D32_SFLOAT", effect->record(cmd, f.camera, f.settings, in)});
                    good = effect->record(cmd, f.camera, f.settings, f.inputs());
                  })
                  .ok());
  EXPECT_EQ(badSetting.code, StatusCode::InvalidSetting) << badSetting.message;
  EXPECT_NE(badSetting.message.find("radius"), std::string::npos) << badSetting.message;
  EXPECT_EQ(badSize.code, StatusCode::InvalidExtent) << badSize.message;
  for (const auto& [what, st] : results) {
    EXPECT_EQ(st.code, StatusCode::UnsupportedFormat) << what << ": " << st.message;
    EXPECT_FALSE(st.message.empty()) << what;
  }
  ASSERT_TRUE(good.ok()) << good.message;
  EXPECT_EQ(effect->plans(), 1u) << "the refused records planned nothing";
  const vk::OutputImage o = effect->output();
  FloatImage ao;
  ASSERT_TRUE(context().readback(o.image, o.format, o.extent, 0, o.layout, f.config.outputDstStages,
                                 f.config.outputDstAccess, ao).ok());
  EXPECT_TRUE(sameBits(ao, expected)) << "the refused records recorded nothing";
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
  Image other;
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {32, 18}, other).ok());
  const vk::OutputImage userOut{other.image, other.view, VK_FORMAT_R16_SFLOAT, {32, 18}};
  std::vector<std::pair<std::string, Status>> invalid, unsupported;
  Status good;
  const Status st = context().submit([&](VkCommandBuffer cmd) {
    auto record = [&](const vk::Inputs& in, const vk::OutputImage* o = nullptr) {
      return effect->record(cmd, f.camera, f.settings, in, o);
    };
    vk::Inputs in = f.inputs();
    invalid.push_back({"null command buffer", effect->record(VK_NULL_HANDLE, f.camera, f.settings, in)});
    in.depth.view = VK_NULL_HANDLE;
    invalid.push_back({"null depth view", record(in)});
    in = f.inputs();
    in.depth.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    invalid.push_back({"layout", record(in)});
    in = f.inputs();
    in.depth.format = VK_FORMAT_UNDEFINED;  // required with a view: a view cannot tell its format
    invalid.push_back({"depth format undefined", record(in)});
    in = f.inputs();
    in.normals = {f.image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, f.depth.extent};
    invalid.push_back({"normals format undefined", record(in)});
    in = f.inputs();
    in.depth2 = in.depth;
    in.depth2.format = VK_FORMAT_D16_UNORM;  // every depth layer has the depth's format
    invalid.push_back({"depth2 in another format", record(in)});
    vk::OutputImage o = userOut;
    o.extent = {16, 9};
    invalid.push_back({"output size", record(f.inputs(), &o)});
    o = userOut;
    o.format = VK_FORMAT_R32_SFLOAT;
    unsupported.push_back({"output format", record(f.inputs(), &o)});
    good = record(f.inputs());
  });
  ASSERT_TRUE(st.ok()) << st.message;
  for (const auto& [what, s] : invalid) {
    EXPECT_EQ(s.code, StatusCode::InvalidInput) << what << ": " << s.message;
    EXPECT_FALSE(s.message.empty()) << what;
  }
  for (const auto& [what, s] : unsupported) {
    EXPECT_EQ(s.code, StatusCode::UnsupportedFormat) << what << ": " << s.message;
    EXPECT_FALSE(s.message.empty()) << what;
  }
  EXPECT_TRUE(good.ok()) << good.message;
  EXPECT_EQ(effect->output().image, owned.image) << "the refused records kept the configuration";
  EXPECT_EQ(effect->outputGeneration(), generation);
  EXPECT_EQ(effect->plans(), plans) << "the good record kept the plan of the first";
  FloatImage ao;
  ASSERT_TRUE(context().readback(owned.image, owned.format, owned.extent, 0, owned.layout, f.config.outputDstStages,
                                 f.config.outputDstAccess, ao).ok());
  EXPECT_TRUE(sameBits(ao, before)) << "the refused records recorded nothing";
  context().destroy(other);
}

// Every input layout a sampled depth may be in gives what SHADER_READ_ONLY_OPTIMAL gives, bit for
// bit (every format in that layout: Effect.EveryDepthFormat in tests/executors/effect_test.cpp).
TEST_F(VkEffect, EveryDepthLayout) {
  const auto run = [](VkDepth format, VkImageLayout layout) {
    Frame f(48, 27, format, test::stairsScene(), layout);
    auto effect = makeEffect(f.config);
    return effect ? runOnce(*effect, f) : FloatImage{};
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
  const FloatImage expected = runOnce(*owned, f);
  for (VkImageLayout layout : {VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}) {
    vk::Config c = f.config;
    c.outputLayout = layout;
    auto effect = makeEffect(c);
    ASSERT_TRUE(effect);
    Image out;
    ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {40, 24}, out).ok());
    const vk::OutputImage o{out.image, out.view, VK_FORMAT_R16_SFLOAT, {40, 24}};
    EXPECT_TRUE(sameBits(runOnce(*effect, f, &o), expected));
    EXPECT_EQ(effect->output().image, VK_NULL_HANDLE);
    EXPECT_EQ(effect->plan().image(gen::ResourceId::ao), nullptr) << "the user's output is not allocated";
    EXPECT_EQ(effect->outputGeneration(), 0u) << "never an owned output";
    EXPECT_TRUE(sameBits(runOnce(*effect, f, &o), expected)) << "second frame";
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
  const FloatImage once = runOnce(*effect, f);
  Status a, b, c;
  ASSERT_TRUE(context()
                  .submit([&](VkCommandBuffer cmd) {
                    a = effect->record(cmd, f.camera, f.settings, f.inputs());
                    b = effect->record(cmd, f.camera, f.settings, f.inputs());
                    c = effect->record(cmd, f.camera, f.settings, f.inputs());
                  })
                  .ok());
  EXPECT_TRUE(a.ok() && b.ok() && c.ok());
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
  Image out1, out2;
  const vk::Config c = f1.config;
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
                      s1 = ring->record(cmd, f1.camera, f1.settings, f1.inputs(), &o1);
                      s2 = ring->record(cmd, f2.camera, f2.settings, f2.inputs(), &o2);
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
  EXPECT_EQ(ring->plans(), 1u) << "both records of every round keep the first plan";
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
    runOnce(*effect, f);
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
  // measure() leaves the same result as record().
  const FloatImage fromMeasure = [&] {
    FloatImage ao;
    const auto o = effect->output();
    EXPECT_TRUE(context().readback(o.image, o.format, o.extent, 0, o.layout, c.outputDstStages, c.outputDstAccess, ao).ok());
    return ao;
  }();
  EXPECT_TRUE(sameBits(fromMeasure, runOnce(*effect, f)));
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
  const vk::OutputImage o = effect->output();
  FloatImage measured;
  ASSERT_TRUE(context().readback(o.image, o.format, o.extent, 0, o.layout, f.config.outputDstStages,
                                 f.config.outputDstAccess, measured).ok());
  auto recorded = makeEffect(f.config);
  ASSERT_TRUE(recorded);
  EXPECT_TRUE(sameBits(measured, runOnce(*recorded, f)));
}

}  // namespace
}  // namespace sao::vktest
