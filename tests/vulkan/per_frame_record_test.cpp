// The per-frame record(cmd, camera, settings, inputs[, output]), what only Vulkan has (the shared
// suite, tests/executors, drives Vulkan through this call: every change of settings, camera, inputs
// or output equal to a fresh effect, steady frames allocating nothing), under validation and
// synchronization validation (a destroyed image in use, a missing barrier: a message fails the test).
// The camera per record (TAA jitter, an animated field of view, a new view rotation for world-space
// normals) is written into the record's own ring slot: an effect planned with camera A and recorded
// with B writes exactly (every texel, bit for bit) what a fresh effect recorded with B writes
// (record() and measure()); command buffers in flight each keep their own camera; a camera that
// keeps the plan records without a new plan and allocates nothing in the library; record() plans
// again exactly when sao::plan() of the camera differs, within the call, while frames in flight keep
// their camera and output; what the old plan alone used is destroyed only once the ring says those
// frames completed, and its memory given back; invalid cameras and inputs are refused as a fresh
// effect refuses them, and the effect stays usable; create() plans nothing. Temporal accumulation
// (the rest: tests/executors/temporal_test.cpp): two frames in flight give what one after the other
// gives; a record that plans again (other settings) starts the history again.
#include <cmath>
#include <cstring>
#include <numbers>
#include <string>

#include "analytic_scenes.h"
#include "library_allocations.h"
#include "moving_camera.h"
#include "normal_encodings.h"
#include "sao/presets.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

using vk::headless::Image;

constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8;
constexpr VkFormat kNormalsFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkImageLayout kRead = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

// Vulkan's [0, 1] clip range, far 100, a vertical field of view in degrees.
Camera cameraWith(double fovDegrees, double nearDistance, std::uint32_t w = kW, std::uint32_t h = kH,
                  std::uint32_t guard = kGuard) {
  Camera c = perspectiveCamera(fovDegrees * std::numbers::pi / 180.0, w, h, nearDistance, 100.0, ClipDepth::ZeroToOne, false);
  c.guardBand = guard;
  return c;
}

// A TAA jitter of (dx, dy) pixels: the projection's x and y offsets (P02, P12).
Camera jittered(Camera c, double dx, double dy) {
  c.projection[8] += 2.0 * dx / c.width;
  c.projection[9] += 2.0 * dy / c.height;
  return c;
}

Camera worldNormals(Camera c, const std::array<double, 9>& rotation) {
  c.normalsEncoding = NormalsEncoding::WorldXyz;
  c.viewRotation = rotation;
  return c;
}

// Texels whose bits differ (R16F read back as float: equal bits, equal output).
std::size_t differences(const FloatImage& a, const FloatImage& b) {
  EXPECT_EQ(a.data.size(), b.data.size());
  std::size_t n = 0;
  for (std::size_t i = 0; i < std::min(a.data.size(), b.data.size()); ++i)
    n += std::memcmp(&a.data[i], &b.data[i], sizeof(float)) != 0;
  return n;
}

class PerFrameRecord : public VkTest {
 protected:
  void SetUp() override {
    VkTest::SetUp();
    base = cameraWith(60, 0.1);
    const test::Scene scene = test::sphereOnPlaneScene();
    depth = test::renderDepth(scene, base, DepthFormat::D32F);
    ASSERT_TRUE(context().uploadDepth(depth, VK_FORMAT_D32_SFLOAT, kRead, depthImage).ok());
    // World-space normals written with rotation R0. The same texels serve every camera: each
    // comparison is between two effects on the same inputs.
    const FloatImage n = test::encodeNormals(test::renderNormals(scene, base), NormalsEncoding::WorldXyz, r0);
    ASSERT_TRUE(context().uploadColor(n, kNormalsFormat, kRead, normalsImage).ok());
  }
  void TearDown() override {
    for (Image* i : {&depthImage, &normalsImage, &otherDepthImage, &otherNormalsImage}) context().destroy(*i);
    for (Image& i : outputs) context().destroy(i);
    VkTest::TearDown();
  }

  // The inputs for `camera`: the depth, and the world-space normals when the camera reads them.
  // Cameras of another size or guard band get the images of prepareOtherGeometry().
  static bool baseGeometry(const Camera& camera) {
    return camera.width == kW && camera.height == kH && camera.guardBand == kGuard;
  }
  vk::Inputs inputs(const Camera& camera) const {
    vk::Inputs in;
    const bool own = baseGeometry(camera);
    const Image& d = own ? depthImage : otherDepthImage;
    in.depth = {d.view, kRead, d.extent, VK_FORMAT_D32_SFLOAT};
    if (camera.normalsEncoding == NormalsEncoding::WorldXyz) {
      const Image& n = own ? normalsImage : otherNormalsImage;
      in.normals = {n.view, kRead, n.extent, kNormalsFormat};
    }
    return in;
  }
  // Depth and normals for a camera of another size or guard band (the one other geometry a test
  // uses at a time), rendered from the same scene.
  void prepareOtherGeometry(const Camera& camera) {
    context().destroy(otherDepthImage);
    context().destroy(otherNormalsImage);
    const test::Scene scene = test::sphereOnPlaneScene();
    ASSERT_TRUE(context()
                    .uploadDepth(test::renderDepth(scene, camera, DepthFormat::D32F), VK_FORMAT_D32_SFLOAT, kRead,
                                 otherDepthImage)
                    .ok());
    const FloatImage n = test::encodeNormals(test::renderNormals(scene, camera), NormalsEncoding::WorldXyz, r0);
    ASSERT_TRUE(context().uploadColor(n, kNormalsFormat, kRead, otherNormalsImage).ok());
  }
  // A new R16F output image of `camera`'s viewport (every result in an image of its own), destroyed
  // at TearDown.
  vk::OutputImage newOutput(const Camera& camera) {
    Image& out = outputs.emplace_back();
    EXPECT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {camera.width, camera.height}, out).ok());
    return {out.image, out.view, VK_FORMAT_R16_SFLOAT, out.extent, VK_IMAGE_LAYOUT_UNDEFINED};
  }
  // One record of `e` with `camera` (and `s`, else `settings`; `in`, else inputs(camera)) into `o`,
  // submitted and waited for: the record's status.
  Status record(vk::Effect& e, const Camera& camera, const vk::OutputImage* o, const Settings* s = nullptr,
                const vk::Inputs* in = nullptr) const {
    const vk::Inputs own = in ? *in : inputs(camera);
    return submitRecord([&](VkCommandBuffer cmd) { return e.record(cmd, camera, s ? *s : settings, own, o); });
  }
  // The library's allocations in one record of `camera` into `o` (which must succeed).
  long countedRecord(vk::Effect& e, const Camera& camera, const vk::OutputImage& o) const {
    const vk::Inputs in = inputs(camera);
    const Status st = submitRecord([&](VkCommandBuffer cmd) {
      test::startCountingAllocations();
      const Status recorded = e.record(cmd, camera, settings, in, &o);
      test::stopCountingAllocations();
      return recorded;
    });
    EXPECT_TRUE(st.ok()) << st.message;
    return test::countedAllocations();
  }
  // One record into a new output, read back.
  FloatImage run(vk::Effect& e, const Camera& camera, const Settings* s = nullptr) {
    const vk::OutputImage o = newOutput(camera);
    const Status st = record(e, camera, &o, s);
    EXPECT_TRUE(st.ok()) << st.message;
    return readOutput(e, &o);
  }
  // The reference: a fresh effect whose first record (the one that plans) has `camera`.
  FloatImage fresh(const Camera& camera, Plan* plan = nullptr, ParamBlock* params = nullptr,
                   const Settings* s = nullptr) {
    auto e = makeEffect();
    if (!e) return {};
    FloatImage ao = run(*e, camera, s);
    if (plan) *plan = e->plan();
    if (params) *params = e->params();
    return ao;
  }
  // Records `cameras[i]` (with `in[i]`, else inputs(cameras[i]); `s`, else `settings`) into command
  // buffer i (ring slots in turn, every record pending at once), each into a new output, submits
  // them together, waits: the outputs read back.
  std::vector<FloatImage> inFlight(vk::Effect& e, const std::vector<Camera>& cameras,
                                   const std::vector<vk::Inputs>& in = {}, const Settings* s = nullptr) {
    vk::headless::Context& ctx = context();
    const VkDevice device = ctx.device();
    const auto n = std::uint32_t(cameras.size());
    std::vector<VkCommandBuffer> cmds(n);
    std::vector<vk::OutputImage> outs;
    outs.reserve(n);
    std::vector<VkSubmitInfo> si(n, {VK_STRUCTURE_TYPE_SUBMIT_INFO});
    EXPECT_TRUE(ctx.allocateCommandBuffers(cmds.data(), n).ok());
    for (std::uint32_t i = 0; i < n; ++i) {
      outs.push_back(newOutput(cameras[i]));
      VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
      bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
      EXPECT_EQ(vkBeginCommandBuffer(cmds[i], &bi), VK_SUCCESS);
      const vk::Inputs own = in.empty() ? inputs(cameras[i]) : in[i];
      const Status st = e.record(cmds[i], cameras[i], s ? *s : settings, own, &outs[i]);
      EXPECT_EQ(vkEndCommandBuffer(cmds[i]), VK_SUCCESS);
      EXPECT_TRUE(st.ok()) << "record " << i << ": " << st.message;
      si[i].commandBufferCount = 1;
      si[i].pCommandBuffers = &cmds[i];
    }
    VkFence fence = VK_NULL_HANDLE;
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    EXPECT_EQ(vkCreateFence(device, &fi, nullptr, &fence), VK_SUCCESS);
    EXPECT_EQ(vkQueueSubmit(ctx.queue(), n, si.data(), fence), VK_SUCCESS);
    EXPECT_EQ(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), VK_SUCCESS);
    vkDestroyFence(device, fence, nullptr);
    vkFreeCommandBuffers(device, ctx.commandPool(), n, cmds.data());
    std::vector<FloatImage> results;
    for (const vk::OutputImage& o : outs) results.push_back(readOutput(e, &o));
    return results;
  }

  const std::array<double, 9> r0 = test::viewRotation(0.7, -0.4, 0.25);
  const std::array<double, 9> r1 = test::viewRotation(-0.3, 0.5, -0.6);
  const Settings settings = presetSettings(Preset::Medium);
  Camera base;
  DepthImage depth;
  Image depthImage, normalsImage;
  Image otherDepthImage, otherNormalsImage;  // prepareOtherGeometry()
  std::vector<Image> outputs;                // newOutput()
};

TEST_F(PerFrameRecord, ACameraMatchesAFreshEffectOfThatCamera) {
  struct Case {
    const char* name;
    Camera a, b;
  };
  const Case cases[] = {
      {"jitter", base, jittered(base, 0.37, -0.21)},
      {"fov 50", base, cameraWith(50, 0.1)},
      {"fov 70", base, cameraWith(70, 0.1)},
      {"world normals, new rotation", worldNormals(base, r0), worldNormals(base, r1)},
      {"world normals, new rotation and jitter", worldNormals(base, r0), worldNormals(jittered(base, -0.45, 0.3), r1)},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    Plan planA, planB;
    ParamBlock freshParamsB{};
    const FloatImage expectedA = fresh(c.a, &planA);
    const FloatImage expectedB = fresh(c.b, &planB, &freshParamsB);
    ASSERT_EQ(planA.describe(), planB.describe()) << "the case must not change the plan";
    auto effect = makeEffect();
    ASSERT_TRUE(effect);
    // Planned with A (ring slot 0), then B in slot 1: no new plan.
    EXPECT_EQ(differences(run(*effect, c.a), expectedA), 0u) << "slot 0, camera A (the record that plans)";
    const ParamBlock paramsA = effect->params();
    const FloatImage actual = run(*effect, c.b);
    EXPECT_EQ(differences(actual, expectedB), 0u) << "texels unlike the fresh effect with camera B";
    EXPECT_GT(differences(actual, expectedA), 0u) << "camera B changed nothing: the test would prove nothing";
    EXPECT_EQ(effect->plans(), 1u) << "camera B keeps the plan: no new plan";
    // params() is the last record's block: camera B's, as the fresh effect with B has it.
    EXPECT_EQ(std::memcmp(&effect->params(), &freshParamsB, sizeof(ParamBlock)), 0);
    // Back to A: slot 0 again, then slot 1 (the slot that held B's block), and so does params().
    EXPECT_EQ(differences(run(*effect, c.a), expectedA), 0u) << "slot 0 again with camera A";
    EXPECT_EQ(std::memcmp(&effect->params(), &paramsA, sizeof(ParamBlock)), 0);
    EXPECT_EQ(differences(run(*effect, c.a), expectedA), 0u) << "slot 1 (B's) with camera A";
    EXPECT_EQ(effect->plans(), 1u);
    expectNoMessages(c.name);
  }
}

// measure() takes the camera like record(): its run uses it, on the plan it has.
TEST_F(PerFrameRecord, MeasureUsesTheCamera) {
  const Camera a = worldNormals(base, r0);
  const Camera b = worldNormals(jittered(cameraWith(65, 0.1), 0.3, -0.3), r1);
  const FloatImage expected = fresh(b);
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  run(*effect, a);  // planned with camera A
  Camera bad = b;
  bad.projection[0] = INFINITY;
  for (vk::MeasureMethod method : {vk::MeasureMethod::Auto, vk::MeasureMethod::FenceClock}) {
    const vk::OutputImage o = newOutput(b);
    Timings t;
    const Status st = effect->measure(context().queue(), b, settings, inputs(b), &o, t, method);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(differences(readOutput(*effect, &o), expected), 0u) << "method " << int(method);
  }
  EXPECT_EQ(effect->plans(), 1u) << "camera B keeps camera A's plan";
  const vk::OutputImage o = newOutput(b);
  Timings t;
  const Status st = effect->measure(context().queue(), bad, settings, inputs(bad), &o, t);
  EXPECT_EQ(st.code, StatusCode::InvalidCamera) << st.message;
  EXPECT_NE(st.message.find("non-finite element P00"), std::string::npos) << st.message;
}

// Two command buffers recorded with cameras B and C (ring slots 1 and 0 after the record that
// planned with A), both pending at once, submitted together: each output is its camera's fresh
// result.
TEST_F(PerFrameRecord, TwoFramesInFlightKeepTheirCameras) {
  const Camera a = worldNormals(base, r0);
  const Camera b = worldNormals(jittered(cameraWith(55, 0.1), 0.25, 0.25), r1);
  const Camera c = worldNormals(jittered(base, -0.25, 0.4), test::viewRotation(1.1, 0.2, 0.0));
  const FloatImage expectedB = fresh(b), expectedC = fresh(c);
  ASSERT_GT(differences(expectedB, expectedC), 0u);
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  run(*effect, a);  // planned with camera A
  const std::vector<FloatImage> out = inFlight(*effect, {b, c});
  EXPECT_EQ(effect->plans(), 1u) << "cameras B and C keep A's plan";
  EXPECT_EQ(differences(out[0], expectedB), 0u) << "slot 1, camera B";
  EXPECT_EQ(differences(out[1], expectedC), 0u) << "slot 0, camera C";
}

// A camera per record allocates nothing in the library once warm (the allocation counter of
// tests/common/library_allocations.h, timestamps on) and plans nothing: 64 jittered frames with an
// animated field of view and view rotation.
TEST_F(PerFrameRecord, NoAllocationPerRecordWithACameraEach) {
  ASSERT_TRUE(test::watchLibraryOf(reinterpret_cast<const void*>(&vk::processMemoryStats)));
  auto effect = makeEffect({.timestamps = true});
  ASSERT_TRUE(effect);
  const vk::OutputImage o = newOutput(base);
  Camera last;
  long total = 0;
  constexpr int kWarmUp = 4, kFrames = 64;
  for (int f = 0; f < kWarmUp + kFrames; ++f) {
    // Halton (2, 3) jitter in [-0.5, 0.5), a field of view between 58 and 62 degrees, a turning view.
    auto halton = [](int i, int b) {
      double r = 0, k = 1.0 / b;
      for (; i > 0; i /= b, k /= b) r += k * (i % b);
      return r;
    };
    last = worldNormals(jittered(cameraWith(60 + 2 * std::sin(f * 0.3), 0.1), halton(f + 1, 2) - 0.5,
                                 halton(f + 1, 3) - 0.5),
                        test::viewRotation(0.05 * f, -0.4, 0.25));
    const long n = countedRecord(*effect, last, o);
    if (f >= kWarmUp) total += n;
  }
  EXPECT_EQ(total, 0) << "library allocations in " << kFrames << " record() calls with a camera each";
  EXPECT_EQ(effect->plans(), 1u) << "every camera kept the first frame's plan";
  // params() is the last record's block: its camera's, as a fresh effect with it has it.
  ParamBlock withLast{};
  fresh(last, nullptr, &withLast);
  EXPECT_EQ(std::memcmp(&effect->params(), &withLast, sizeof(ParamBlock)), 0);
  // The counter sees the library: a camera of another size plans again, which allocates.
  const Camera other = worldNormals(cameraWith(60, 0.1, kW + 2), r0);
  prepareOtherGeometry(other);
  EXPECT_GT(countedRecord(*effect, other, newOutput(other)), 0);
  EXPECT_EQ(effect->plans(), 2u);
}

// A camera that changes the plan (size, guard band, csz levels) plans again within the call: it
// records while the previous frame (planned with A, recorded with a jittered camera into another
// command buffer) is still pending, both submitted together; each output is its camera's fresh
// result (under synchronization validation: the old plan's images live until that frame is done),
// and the next record with the jittered camera plans back, again equal to a fresh effect.
TEST_F(PerFrameRecord, CamerasThatChangeThePlanPlanAgainWhileFramesAreInFlight) {
  const Camera a = worldNormals(base, r0);
  const Camera valid = worldNormals(jittered(base, 0.2, 0.1), r1);
  const FloatImage expectedValid = fresh(valid);
  Camera orthographic = orthographicCamera(2.0, kW, kH, 0.1, 100.0, ClipDepth::ZeroToOne, false);
  orthographic.guardBand = kGuard;
  const std::pair<const char*, Camera> cases[] = {
      {"another size", worldNormals(cameraWith(60, 0.1, kW + 2, kH), r0)},
      {"another guard band", worldNormals(cameraWith(60, 0.1, kW, kH, kGuard + 1), r0)},
      {"a near plane that needs fewer csz levels", worldNormals(cameraWith(60, 1.0), r0)},
      {"orthographic (fewer csz levels here)", worldNormals(orthographic, r0)},
  };
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  run(*effect, a);
  const std::string planA = effect->plan().describe();
  for (const auto& [name, camera] : cases) {
    SCOPED_TRACE(name);
    if (!baseGeometry(camera)) prepareOtherGeometry(camera);
    Plan expectedPlan;
    const FloatImage expected = fresh(camera, &expectedPlan);
    ASSERT_NE(expectedPlan.describe(), planA) << "the case must change the plan";
    const std::uint64_t plansBefore = effect->plans();
    const std::vector<FloatImage> out = inFlight(*effect, {valid, camera});
    EXPECT_EQ(effect->plans(), plansBefore + 1) << "the camera planned again, once";
    EXPECT_EQ(effect->plan().describe(), expectedPlan.describe());
    EXPECT_EQ(differences(out[0], expectedValid), 0u) << "the frame in flight on the old plan";
    EXPECT_EQ(differences(out[1], expected), 0u) << "the frame on the new plan";
    EXPECT_EQ(differences(run(*effect, valid), expectedValid), 0u) << "the next record, planned back";
    EXPECT_EQ(effect->plans(), plansBefore + 2);
    EXPECT_EQ(effect->plan().describe(), planA);
    expectNoMessages(name);
  }
}

// Two frames in flight, a new plan every frame (full and half resolution alternate), no wait but
// the ring's: each command buffer is waited for only before it is recorded again. The validation
// layer reports any image destroyed while a pending frame uses it; the last two frames equal fresh
// effects; the images the alternation dropped are given back two frames after the last re-plan.
TEST_F(PerFrameRecord, NewPlansWhileFramesArePendingWaitForTheRing) {
  auto e = makeEffect();
  ASSERT_TRUE(e);
  auto settingsOf = [](std::uint32_t frame) {
    Settings s = presetSettings(Preset::Medium);
    s.resolution_divisor = frame % 2 ? 2 : 1;
    return s;
  };
  const VkDevice device = context().device();
  VkCommandBuffer cmds[2]{};
  ASSERT_TRUE(context().allocateCommandBuffers(cmds, 2).ok());
  VkFence fences[2]{};
  const vk::OutputImage outs[2] = {newOutput(base), newOutput(base)};
  for (VkFence& f : fences) {
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fi.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    ASSERT_EQ(vkCreateFence(device, &fi, nullptr, &f), VK_SUCCESS);
  }
  auto frame = [&](std::uint32_t f, const Settings& s) {
    const std::uint32_t i = f % 2;
    ASSERT_EQ(vkWaitForFences(device, 1, &fences[i], VK_TRUE, UINT64_MAX), VK_SUCCESS);  // the ring's wait
    ASSERT_EQ(vkResetFences(device, 1, &fences[i]), VK_SUCCESS);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    ASSERT_EQ(vkBeginCommandBuffer(cmds[i], &bi), VK_SUCCESS);
    const Status st = e->record(cmds[i], base, s, inputs(base), &outs[i]);
    ASSERT_EQ(vkEndCommandBuffer(cmds[i]), VK_SUCCESS);
    ASSERT_TRUE(st.ok()) << st.message;
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmds[i];
    ASSERT_EQ(vkQueueSubmit(context().queue(), 1, &si, fences[i]), VK_SUCCESS);
  };
  constexpr std::uint32_t kFrames = 8;
  for (std::uint32_t f = 0; f < kFrames; ++f) frame(f, settingsOf(f));
  const std::uint64_t pendingBytes = e->memoryStats().liveBytes;  // the last re-plan's retired images held
  ASSERT_EQ(vkWaitForFences(device, 2, fences, VK_TRUE, UINT64_MAX), VK_SUCCESS);
  for (std::uint32_t i = 0; i < 2; ++i) {
    const Settings s = settingsOf(kFrames - 2 + i);
    EXPECT_EQ(differences(readOutput(*e, &outs[i]), fresh(base, nullptr, nullptr, &s)), 0u)
        << "frame " << kFrames - 2 + i;
  }
  // Two more frames on the last plan: the ring passes the re-plan, its retired images go.
  for (std::uint32_t f = kFrames; f < kFrames + 2; ++f) frame(f, settingsOf(kFrames - 1));
  const std::uint64_t settledBytes = e->memoryStats().liveBytes;
  std::printf("device memory with a re-plan's images retired %llu bytes, after the ring passed it %llu bytes\n",
              static_cast<unsigned long long>(pendingBytes), static_cast<unsigned long long>(settledBytes));
  EXPECT_LT(settledBytes, pendingBytes) << "the images full resolution no longer uses were given back";
  ASSERT_EQ(vkWaitForFences(device, 2, fences, VK_TRUE, UINT64_MAX), VK_SUCCESS);
  for (VkFence f : fences) vkDestroyFence(device, f, nullptr);
  vkFreeCommandBuffers(device, context().commandPool(), 2, cmds);
}

// An invalid camera: the code and message a fresh effect's first record gives (the same check
// whether or not a plan exists), naming what is wrong; nothing recorded, no new plan, and the
// effect records the next valid camera exactly as a fresh effect does. (Two-channel normals read with
// an xyz encoding: exec.robustness's TwoChannelNormalsNeedAnOctahedralEncoding on Vulkan, and
// VkRobustness.NormalsFormatChannelsFollowTheEncoding.)
TEST_F(PerFrameRecord, RefusesInvalidCameras) {
  const Camera a = worldNormals(base, r0);
  const Camera valid = worldNormals(jittered(base, 0.2, 0.1), r1);
  const FloatImage expectedValid = fresh(valid);
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  run(*effect, a);
  const vk::OutputImage o = newOutput(base);
  Camera nonFinite = a, noRotation = a, scaled = a;
  nonFinite.projection[5] = NAN;
  noRotation.viewRotation.reset();
  for (int i = 0; i < 3; ++i) (*scaled.viewRotation)[std::size_t(i)] *= 1.5;
  const std::tuple<const char*, Camera, std::string> cases[] = {
      {"a non-finite projection", nonFinite, "non-finite element P11"},
      {"world normals without a rotation", noRotation, "needs Camera::viewRotation"},
      {"a scaled rotation", scaled, "is not a rotation"},
  };
  for (const auto& [name, camera, says] : cases) {
    SCOPED_TRACE(name);
    const Status st = record(*effect, camera, &o);
    EXPECT_EQ(st.code, StatusCode::InvalidCamera) << st.message;
    EXPECT_NE(st.message.find(says), std::string::npos) << st.message;
    auto freshEffect = makeEffect();  // a fresh effect's first record of the camera
    const Status refusedFresh = record(*freshEffect, camera, &o);
    EXPECT_EQ(freshEffect->plans(), 0u);
    EXPECT_EQ(refusedFresh.code, st.code) << refusedFresh.message;
    EXPECT_FALSE(refusedFresh.message.empty());
    EXPECT_EQ(st.message, refusedFresh.message) << "a fresh effect refuses it alike";
    EXPECT_EQ(effect->plans(), 1u) << "a refused camera plans nothing";
    EXPECT_EQ(differences(run(*effect, valid), expectedValid), 0u) << "the next valid record";
  }
}

// create() plans nothing (plan() empty, the parameter buffer its only memory); the first record()
// plans, and one whose normals view comes without InputImage::format (a view cannot tell it) is
// refused, naming it, and plans nothing.
TEST_F(PerFrameRecord, CreatePlansNothingAndAnInputWithoutItsFormatIsRefused) {
  auto e = makeEffect();
  ASSERT_TRUE(e);
  EXPECT_EQ(e->plans(), 0u);
  EXPECT_TRUE(e->plan().passes.empty());
  EXPECT_TRUE(e->plan().images.empty());
  EXPECT_EQ(e->memoryStats().liveAllocations, 1u) << "the parameter buffer only";
  const Settings defaults;
  vk::Inputs normalsWithoutFormat = inputs(base);
  normalsWithoutFormat.normals = {depthImage.view, kRead, depth.extent};
  const Status refused = record(*e, base, nullptr, &defaults, &normalsWithoutFormat);
  EXPECT_EQ(refused.code, StatusCode::InvalidInput);
  EXPECT_NE(refused.message.find("Inputs::normals.format is VK_FORMAT_UNDEFINED"), std::string::npos)
      << refused.message;
  EXPECT_EQ(e->plans(), 0u) << "the refused record planned nothing";
  EXPECT_EQ(e->memoryStats().liveAllocations, 1u);
  const Status recorded = record(*e, base, nullptr, &defaults);
  EXPECT_TRUE(recorded.ok()) << recorded.message;
  EXPECT_EQ(e->plans(), 1u);
  EXPECT_FALSE(e->plan().passes.empty());
}

// record() plans again exactly when sao::plan() of the camera differs from the effect's current
// plan, over fields of view, near planes, units, projection kinds and conventions; and a camera
// that plans alike records without any library allocation (core's cameraKeepsPlan decides
// without calling sao::plan(), which allocates).
TEST_F(PerFrameRecord, PlansAgainExactlyForTheCamerasThatPlanOtherwise) {
  ASSERT_TRUE(test::watchLibraryOf(reinterpret_cast<const void*>(&vk::processMemoryStats)));
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  run(*effect, base);
  std::vector<Camera> cameras;
  for (double fov : {10.0, 30.0, 45.0, 60.0, 75.0, 90.0, 120.0, 170.0})
    for (double nearDistance : {0.001, 0.05, 0.1, 0.3, 1.0, 5.0}) cameras.push_back(cameraWith(fov, nearDistance));
  for (double u : {1e-3, 0.1, 1.0, 30.0}) {
    cameras.push_back(base);
    cameras.back().metersToViewUnits = u;
  }
  for (double halfHeight : {0.01, 0.5, 2.0, 50.0}) {
    cameras.push_back(orthographicCamera(halfHeight, kW, kH, 0.1, 100.0, ClipDepth::ZeroToOne, false));
    cameras.back().guardBand = kGuard;
  }
  cameras.push_back(vulkanCamera(kW, kH, kGuard, INFINITY, true, true));  // reversed
  cameras.push_back(openglCamera(kW, kH, kGuard));
  // Back to the base camera, then two that change the size or guard band (their own depth).
  cameras.push_back(base);
  cameras.push_back(vulkanCamera(kW, kH, kGuard + 4));
  cameras.push_back(vulkanCamera(kW - 1, kH, kGuard));
  int kept = 0, replanned = 0;
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    SCOPED_TRACE("camera " + std::to_string(i));
    const Camera& camera = cameras[i];
    if (!baseGeometry(camera)) prepareOtherGeometry(camera);
    Plan p;
    const Status planned = sao::plan(settings, camera, {DepthEncoding::Hardware, {}, true, gen::Format::R16F}, p);
    ASSERT_TRUE(planned.ok()) << planned.message;
    const std::string current = effect->plan().describe();
    const bool same = p.describe() == current;
    const std::uint64_t plansBefore = effect->plans();
    const long allocations = countedRecord(*effect, camera, newOutput(camera));
    if (HasFailure()) return;
    EXPECT_EQ(effect->plans() - plansBefore, same ? 0u : 1u)
        << "plan of the camera:\n" << p.describe() << "effect's plan:\n" << current;
    EXPECT_EQ(effect->plan().describe(), p.describe());
    if (same) {
      EXPECT_EQ(allocations, 0) << "a camera that keeps the plan allocates nothing";
    }
    (same ? kept : replanned)++;
  }
  EXPECT_GT(kept, 5);
  EXPECT_GT(replanned, 5);
  std::printf("%d cameras planned alike and kept the plan, %d planned otherwise and planned again\n", kept, replanned);
}

// Temporal accumulation: frames of a camera strafing over the sphere, each with its own depth and
// frame index.
class Temporal : public PerFrameRecord {
 protected:
  void SetUp() override {
    PerFrameRecord::SetUp();
    temporal.temporal = true;
    for (std::uint32_t f = 0; f < kFrames; ++f) {
      const test::Vec3 eye{0.03 * f, 0.0, 0.0};
      cameras[f] = test::movedCamera(vulkanCamera(kW, kH, kGuard), eye);
      depths[f] = test::renderDepth(test::seenFrom(test::sphereOnPlaneScene(), eye), cameras[f], DepthFormat::D32F);
      ASSERT_TRUE(context().uploadDepth(depths[f], VK_FORMAT_D32_SFLOAT, kRead, images[f]).ok());
    }
  }
  void TearDown() override {
    for (Image& i : images) context().destroy(i);
    PerFrameRecord::TearDown();
  }
  vk::Inputs frameInputs(std::uint32_t frame) const {
    vk::Inputs in;
    in.depth = {images[frame].view, kRead, depths[frame].extent, VK_FORMAT_D32_SFLOAT};
    in.frameIndex = frame;
    return in;
  }
  // Frame `frame` of `e` (its camera, depth and index) with `s`, else `temporal`, into a new output.
  FloatImage runFrame(vk::Effect& e, std::uint32_t frame, const Settings* s = nullptr) {
    const vk::OutputImage o = newOutput(cameras[frame]);
    const vk::Inputs in = frameInputs(frame);
    const Status st = record(e, cameras[frame], &o, s ? s : &temporal, &in);
    EXPECT_TRUE(st.ok()) << st.message;
    return readOutput(e, &o);
  }

  static constexpr std::uint32_t kFrames = 3;
  Settings temporal = presetSettings(Preset::Medium);
  Camera cameras[kFrames];
  DepthImage depths[kFrames];
  Image images[kFrames];
};

// Frame 0 alone, then frames 1 and 2 recorded into two command buffers and submitted together,
// under synchronization validation: what one after the other, each waited for, gives.
TEST_F(Temporal, TwoFramesInFlightGiveWhatOneAfterTheOtherGives) {
  auto sequential = makeEffect(), inFlightEffect = makeEffect();  // Config's ring: two frames in flight
  ASSERT_TRUE(sequential && inFlightEffect);
  const FloatImage expected[3] = {runFrame(*sequential, 0), runFrame(*sequential, 1), runFrame(*sequential, 2)};
  runFrame(*inFlightEffect, 0);
  const std::vector<FloatImage> out =
      inFlight(*inFlightEffect, {cameras[1], cameras[2]}, {frameInputs(1), frameInputs(2)}, &temporal);
  EXPECT_EQ(differences(out[0], expected[1]), 0u) << "frame 1 in flight";
  EXPECT_EQ(differences(out[1], expected[2]), 0u) << "frame 2 in flight";
  EXPECT_GT(differences(expected[1], expected[2]), 0u);
  expectNoMessages("two frames in flight");
}

// A record with other settings (a hysteresis of 0.8: nothing else changes) plans again within the
// call, and a new plan starts the history again: frame 2 after frames 0 and 1 with the old
// settings is frame 2 of a fresh effect, while frames 0, 1, 2 all with the new settings differ.
TEST_F(Temporal, ANewPlanStartsTheHistoryAgain) {
  Settings other = temporal;
  other.temporal_hysteresis = 0.8f;
  auto accumulating = makeEffect(), fresh = makeEffect(), continuing = makeEffect();
  ASSERT_TRUE(accumulating && fresh && continuing);
  runFrame(*accumulating, 0);
  runFrame(*accumulating, 1);
  EXPECT_EQ(accumulating->plans(), 1u);
  const FloatImage afterNewPlan = runFrame(*accumulating, 2, &other);
  EXPECT_EQ(accumulating->plans(), 2u) << "other settings plan again";
  const FloatImage alone = runFrame(*fresh, 2, &other);
  runFrame(*continuing, 0, &other);
  runFrame(*continuing, 1, &other);
  const FloatImage continued = runFrame(*continuing, 2, &other);
  EXPECT_EQ(differences(afterNewPlan, alone), 0u) << "a new plan must start the history again";
  EXPECT_GT(differences(continued, alone), 0u) << "frame 2 with history looks like frame 2 without";
  expectNoMessages("a new plan");
}

}  // namespace
}  // namespace sao::vktest
