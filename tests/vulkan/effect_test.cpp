// sao::vk::Effect: creation, version and device checks, bad inputs, every depth format and layout,
// user output, repeated recording, input changes through the descriptor ring, update(), timing.
// Runs under the validation layer with synchronization validation; any message fails the test.
#include <bit>
#include <cmath>
#include <map>

#include "image_compare.h"
#include "untuned_settings.h"
#include "analytic_scenes.h"
#include "sao/presets.h"
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

TEST_F(VkEffect, CreatesRecordsAndProducesPlausibleObscurance) {
  Frame f(64, 36, VkDepth::D32F, test::sphereOnPlaneScene());
  auto effect = makeEffect(f.config);
  ASSERT_TRUE(effect);
  EXPECT_EQ(effect->pipelineCount(), effect->plan().passes.size()) << "one pipeline per planned pass variant";
  const FloatImage ao = runOnce(*effect, f.inputs());
  ASSERT_EQ(ao.extent, (Extent{64, 36}));
  double lo = 1, hi = 0;
  for (float v : ao.data) {
    ASSERT_TRUE(std::isfinite(v));
    lo = std::min(lo, double(v));
    hi = std::max(hi, double(v));
  }
  EXPECT_GE(lo, 0.0);
  EXPECT_LE(hi, 1.0);
  EXPECT_LT(lo, 0.9) << "the sphere on the floor occludes something";
  EXPECT_GT(hi, 0.99) << "the open floor and the sky stay unoccluded";
  const auto stats = effect->memoryStats();
  EXPECT_GE(stats.liveAllocations, 1u);
  EXPECT_GE(stats.liveBytes, effect->plan().totalBytes);
  std::printf("plan: %s", effect->plan().describe().c_str());
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
  c = f.config;
  c.settings.radius = -1.0f;
  EXPECT_EQ(code(c), StatusCode::InvalidSetting);
  c = f.config;
  c.camera.projection[11] = 0.5;  // not a projection of the declared kind
  EXPECT_EQ(code(c), StatusCode::InvalidCamera);
  c = f.config;
  c.camera.width = 0;  // the core's camera analysis rejects an empty viewport first
  EXPECT_EQ(code(c), StatusCode::InvalidCamera);
  c = f.config;
  c.camera = vulkanCamera(20000, 100, 0);  // beyond maxImageDimension2D / kMaxImageSide
  const Status st = vk::Effect::create(context().deviceContext(), c, e);
  EXPECT_EQ(st.code, StatusCode::InvalidExtent) << st.message;
  EXPECT_FALSE(e);
}

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
    in.depth.extent = {32, 18};  // the viewport, not viewport + guard band
    results.push_back({"wrong extent", effect->record(cmd, in)});
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

// Every accepted depth format and input layout; formats holding the same texels agree bit for bit.
TEST_F(VkEffect, EveryDepthFormatAndLayout) {
  struct Case {
    VkDepth format;
    VkImageLayout layout;
  };
  const Case cases[] = {
      {VkDepth::D16, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
      {VkDepth::X8D24, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL},
      {VkDepth::D24S8, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL},
      {VkDepth::D24S8, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
      {VkDepth::D32F, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL},
      {VkDepth::D32FS8, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL},
      {VkDepth::D32FS8, VK_IMAGE_LAYOUT_GENERAL},
      {VkDepth::R32F, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
  };
  std::map<DepthFormat, FloatImage> first;
  for (const auto& c : cases) {
    SCOPED_TRACE(std::string(toString(c.format)) + " layout " + std::to_string(c.layout));
    Frame f(48, 27, c.format, test::stairsScene(), c.layout);
    auto effect = makeEffect(f.config);
    ASSERT_TRUE(effect);
    const FloatImage ao = runOnce(*effect, f.inputs());
    const auto [it, inserted] = first.emplace(cpuFormat(c.format), ao);
    if (!inserted) {
      EXPECT_TRUE(sameBits(ao, it->second)) << "same texels, different format or layout";
    }
    expectNoMessages(toString(c.format));
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

// Alternating inputs go through the descriptor-set ring; each frame reads its own depth.
TEST_F(VkEffect, AlternatingInputsReadTheirOwnDepth) {
  Frame f1(48, 27, VkDepth::D32F, test::sphereOnPlaneScene());
  Frame f2(48, 27, VkDepth::D32F, test::stairsScene());
  auto effect = makeEffect(f1.config);
  ASSERT_TRUE(effect);
  const FloatImage e1 = runOnce(*effect, f1.inputs());
  const FloatImage e2 = runOnce(*effect, f2.inputs());
  EXPECT_FALSE(sameBits(e1, e2));
  // Two recorded command buffers pending at once (framesInFlight = 2), then read both results.
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

// update(): settings, variants and sizes give what a fresh effect gives; pipelines are built once
// per variant and images only when the plan's images change.
TEST_F(VkEffect, UpdateMatchesAFreshEffect) {
  Frame small(40, 24, VkDepth::D32F, test::stairsScene());
  Frame large(72, 40, VkDepth::D32F, test::stairsScene());
  small.config.settings = large.config.settings = test::untunedDefaults();  // the pass counts below are full resolution's
  auto effect = makeEffect(small.config);
  ASSERT_TRUE(effect);
  const std::uint32_t pipelines = effect->pipelineCount();

  vk::Config c = small.config;
  c.settings.intensity = 2.0f;  // parameters only
  const VkImage before = effect->ownedImage(gen::ResourceId::csz).image;
  ASSERT_TRUE(effect->update(c).ok());
  EXPECT_EQ(effect->ownedImage(gen::ResourceId::csz).image, before) << "no new images for a parameter change";
  auto fresh = makeEffect(c);
  EXPECT_TRUE(sameBits(runOnce(*effect, small.inputs()), runOnce(*fresh, small.inputs())));

  c.settings.blur_radius = 0;  // nothing follows the AO: ao_sample_output writes the output
  ASSERT_TRUE(effect->update(c).ok());
  EXPECT_EQ(effect->plan().passes.size(), 2u) << "linear_z, ao_sample_output";
  fresh = makeEffect(c);
  EXPECT_TRUE(sameBits(runOnce(*effect, small.inputs()), runOnce(*fresh, small.inputs())));
  EXPECT_EQ(effect->pipelineCount(), pipelines + 1) << "one new pipeline: ao_sample_output's";

  c.settings = test::untunedDefaults();
  c.settings.use_z_hierarchy = false;  // Z_HIERARCHY=0: another ao_sample variant
  ASSERT_TRUE(effect->update(c).ok());
  EXPECT_EQ(effect->pipelineCount(), pipelines + 2);
  fresh = makeEffect(c);
  EXPECT_TRUE(sameBits(runOnce(*effect, small.inputs()), runOnce(*fresh, small.inputs())));

  c.camera = large.camera;  // a resize
  ASSERT_TRUE(effect->update(c).ok());
  EXPECT_EQ(effect->output().extent, (Extent{72, 40}));
  fresh = makeEffect(c);
  EXPECT_TRUE(sameBits(runOnce(*effect, large.inputs()), runOnce(*fresh, large.inputs())));

  vk::Config bad = c;
  bad.settings.samples = 0;
  EXPECT_EQ(effect->update(bad).code, StatusCode::InvalidSetting);
  EXPECT_EQ(effect->output().extent, (Extent{72, 40})) << "a failed update keeps the configuration";
  EXPECT_TRUE(sameBits(runOnce(*effect, large.inputs()), runOnce(*fresh, large.inputs())));
}

TEST_F(VkEffect, NormalsAndSecondLayerVariantsRun) {
  const Camera cam = vulkanCamera(48, 27, 8);
  const test::Scene scene = test::sphereOnPlaneScene();
  const DepthImage depth = test::renderDepth(scene, cam, DepthFormat::D32F);
  const DepthImage depth2 = test::renderDepth(scene, cam, DepthFormat::D32F, 1);
  const FloatImage normals = test::renderNormals(scene, cam);
  RunResult withNormals, twoLayers, plain;
  RunOptions o;
  ASSERT_TRUE(runEffect(Settings{}, cam, depth, VkDepth::D32F, plain, o).ok());
  o.normals = &normals;
  Status st = runEffect(Settings{}, cam, depth, VkDepth::D32F, withNormals, o);
  ASSERT_TRUE(st.ok()) << st.message;
  o.normals = nullptr;
  o.depth2 = &depth2;
  st = runEffect(Settings{}, cam, depth, VkDepth::D32F, twoLayers, o);
  ASSERT_TRUE(st.ok()) << st.message;
  EXPECT_EQ(withNormals.plan.variants[std::size_t(gen::VariantId::NORMALS_SUPPLIED)], 1);
  EXPECT_EQ(twoLayers.plan.variants[std::size_t(gen::VariantId::TWO_LAYER)], 1);
  // Analytic normals and rebuilt ones give nearly the same obscurance on this smooth scene.
  const Agreement a = compare(withNormals.ao, plain.ao, 0, 0.05, 1.0, "normals_vs_rebuilt");
  EXPECT_GT(a.fractionWithin, 0.9);
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

TEST_F(VkEffect, SkyStaysUnoccluded) {
  for (bool reversed : {false, true}) {
    const Camera cam = vulkanCamera(40, 24, 4, reversed ? INFINITY : 100.0, reversed);
    const DepthImage depth = test::renderDepth(test::skyScene(), cam, DepthFormat::D32F);
    RunResult r;
    const Status st = runEffect(Settings{}, cam, depth, VkDepth::D32F, r);
    ASSERT_TRUE(st.ok()) << st.message;
    for (float v : r.ao.data) ASSERT_EQ(v, 1.0f);
    for (float v : r.csz0.data) ASSERT_EQ(std::bit_cast<std::uint32_t>(v), 0u) << "sky is +0.0 in csz";
  }
}

}  // namespace
}  // namespace sao::vktest
