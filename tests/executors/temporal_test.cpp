// Temporal accumulation (the `temporal` setting) on each API against the CPU reference carried
// frame to frame (runCpu's history): a camera strafing past a sphere on a plane, the camera per
// frame planning nothing and allocating nothing once warm; Inputs::resetHistory and a settings
// change start again; motion vectors. Vulkan's frames in flight stay in tests/vulkan.
#include <cstring>
#include <string>
#include <vector>

#include "harness.h"
#include "api_allocations.h"
#include "moving_camera.h"
#include "sao/presets.h"

namespace sao::exectest {
namespace {

Settings temporalMedium(bool visibility = false) {
  Settings s = presetSettings(Preset::Medium);
  s.temporal = true;
  if (visibility) s.estimator = 1, s.thickness_model = 1;  // the visibility estimator, thickness from width
  return s;
}

// A sphere on a plane seen by `base` strafing 3 cm a frame (or standing at the origin).
struct Path {
  std::vector<Camera> cameras;
  std::vector<DepthImage> depths;
  Frame frame(std::uint32_t f, const Settings& settings) const {
    Frame fr;
    fr.settings = settings;
    fr.camera = cameras[f];
    fr.depth = &depths[f];
    fr.frameIndex = f;
    return fr;
  }
};
Path makePath(const Camera& base, bool strafing, std::uint32_t frames) {
  Path p;
  for (std::uint32_t f = 0; f < frames; ++f) {
    const test::Vec3 eye{strafing ? 0.03 * f : 0.0, 0.0, 0.0};
    p.cameras.push_back(test::movedCamera(base, eye));
    p.depths.push_back(test::renderDepth(test::seenFrom(test::sphereOnPlaneScene(), eye), p.cameras.back(),
                                         DepthFormat::D32F));
  }
  return p;
}
Path strafe(std::uint32_t frames) { return makePath(test::vulkanCamera(160, 90, 8), true, frames); }
Path still(std::uint32_t frames) { return makePath(test::openglCamera(96, 64, 4), false, frames); }

// The CPU reference's frames in order, the history and its camera carried along as the GPU keeps them.
class CpuFrames {
 public:
  cpu::Result run(Frame f) {
    if (!history_.data.empty() && f.previousCamera == nullptr) f.previousCamera = &previous_;
    cpu::Result r;
    const Status st = runCpu(f, r, history_.data.empty() ? nullptr : &history_);
    EXPECT_TRUE(st.ok()) << st.message;
    history_ = r.images[std::size_t(gen::ResourceId::history)].at(0);
    previous_ = f.camera;
    return r;
  }
  const FloatImage& history() const { return history_; }

 private:
  FloatImage history_;
  Camera previous_;
};

std::size_t differences(const FloatImage& a, const FloatImage& b) {
  std::size_t n = a.data.size() != b.data.size();
  for (std::size_t i = 0; i < std::min(a.data.size(), b.data.size()); ++i)
    n += std::memcmp(&a.data[i], &b.data[i], sizeof(float)) != 0;
  return n;
}

// ---- Six strafing frames through one effect, each agreeing with the CPU reference.
struct StrafeCase {
  std::string name;
  Camera base;
  bool visibility = false;
  bool callerOutput = false;
  bool givePreviousCamera = false;  // Inputs::previousCamera set to the frame before's (null: the same)
};
std::string caseName(const StrafeCase& c) { return c.name; }
void PrintTo(const StrafeCase& c, std::ostream* os) { *os << c.name; }
std::vector<StrafeCase> strafeCases() {
  const Camera gl = test::openglCamera(160, 90, 8), vk = test::vulkanCamera(160, 90, 8);
  return {{"opengl_camera", gl},
          {"vulkan_camera_caller_output", vk, false, true},
          {"visibility_estimator", vk, true, true},
          {"previous_camera_given", gl, false, false, true}};
}

using TemporalStrafe = ApiCaseTest<StrafeCase>;
TEST_P(TemporalStrafe, EveryFrameMatchesTheCpuReferenceWithoutAllocating) {
  SAO_SKIP_UNLESS_SUPPORTED(api(), Feature::LibraryAllocations);
  const StrafeCase& c = param();
  ASSERT_TRUE(watchApiLibrary(api()));
  const Path path = makePath(c.base, true, 6);
  const Settings settings = temporalMedium(c.visibility);
  auto e = make();
  CpuFrames reference;
  std::uint64_t plans = 0, images = 0, pipelines = 0;
  long counted = 0;
  for (std::uint32_t f = 0; f < 6; ++f) {
    const std::string name = "temporal_" + c.name + std::to_string(f);
    Frame frame = path.frame(f, settings);
    frame.output.callerOwned = c.callerOutput;
    if (c.givePreviousCamera && f > 0) frame.previousCamera = &path.cameras[f - 1];
    ASSERT_TRUE(e->upload(frame).ok());
    test::startCountingAllocations();
    const Status st = e->run(frame);
    test::stopCountingAllocations();
    if (f > 0) counted += test::countedAllocations();  // frame 0 creates the effect
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(e->params().history_valid, f > 0 ? 1 : 0);
    expectAgreesWithCpu(*e, reference.run(frame), name);
    // The history this frame wrote: frame counts and packed normals as the CPU's, texel for texel
    // (0.1 % spared). GL's and GLES's image() serve this frame's copy; Vulkan's and the engine's
    // history copy 0, the one even frames write.
    if (api() == Api::Gl || api() == Api::Gles || f % 2 == 0) {
      const FloatImage history = e->image(gen::ResourceId::history), &cpuHistory = reference.history();
      ASSERT_EQ(history.data.size(), cpuHistory.data.size());
      std::size_t differ = 0;
      for (std::size_t i = 0; i < history.data.size(); i += 4)
        differ += history.data[i + 2] != cpuHistory.data[i + 2] || history.data[i + 3] != cpuHistory.data[i + 3];
      EXPECT_LE(differ, history.data.size() / 4 / 1000) << name << ": history frames or normals differ";
    }
    if (f == 0) plans = e->plans(), images = e->imageAllocations(), pipelines = e->pipelines();
  }
  EXPECT_EQ(counted, 0) << "library allocations in the per-frame call with a moving camera";
  EXPECT_EQ(e->imageAllocations(), images) << "a moving camera allocated image storage";
  EXPECT_EQ(e->plans(), plans) << "a moving camera planned again";
  EXPECT_EQ(e->pipelines(), pipelines);
}
SAO_INSTANTIATE_API_CASES(TemporalStrafe, strafeCases());

// ---- Reset and settings changes, on a still camera (GL's case) and on the strafe (Vulkan's).
struct PathCase {
  std::string name;
  bool strafing;
};
std::string caseName(const PathCase& c) { return c.name; }
void PrintTo(const PathCase& c, std::ostream* os) { *os << c.name; }
const std::vector<PathCase> kPaths = {{"still", false}, {"strafe", true}};
Path pathOf(const PathCase& c, std::uint32_t frames) { return c.strafing ? strafe(frames) : still(frames); }

using TemporalReset = ApiCaseTest<PathCase>;
TEST_P(TemporalReset, ResetHistoryGivesTheFrameWithoutHistory) {
  const Path path = pathOf(param(), 3);
  const Settings settings = temporalMedium();
  auto accumulating = make(), fresh = make();
  auto render = [&](Executor& e, std::uint32_t f, bool reset) {
    Frame frame = path.frame(f, settings);
    frame.resetHistory = reset;
    const Status st = e.render(frame);
    EXPECT_TRUE(st.ok()) << st.message;
    return e.output();
  };
  render(*accumulating, 0, false);
  const FloatImage withHistory = render(*accumulating, 1, false);
  EXPECT_EQ(accumulating->params().history_valid, 1);
  const FloatImage reset = render(*accumulating, 2, true);
  EXPECT_EQ(accumulating->params().history_valid, 0);
  const FloatImage alone2 = render(*fresh, 2, false);
  EXPECT_EQ(differences(reset, alone2), 0u) << "a reset frame must not read the history";
  const std::size_t pixels = alone2.data.size();
  EXPECT_GT(differences(withHistory, alone2), pixels / 20) << "frame 1 with history looks like frame 2 without";
  auto other = make();
  EXPECT_GT(differences(withHistory, render(*other, 1, false)), pixels / 20)
      << "frame 1 with history looks like frame 1 without";
  // A settings change starts again too.
  Frame changed = path.frame(2, settings);
  changed.settings.radius = 0.9f;
  ASSERT_TRUE(accumulating->render(changed).ok());
  EXPECT_EQ(accumulating->params().history_valid, 0);
  ASSERT_TRUE(accumulating->render(changed).ok());
  EXPECT_EQ(accumulating->params().history_valid, 1);
}
SAO_INSTANTIATE_API_CASES(TemporalReset, kPaths);

// ---- Motion vectors (MOTION_VECTORS): a field of (1.5, -0.75) pixels everywhere (as if the whole
// picture moved) in RGBA16F, four frames against the CPU given the same field: on the still camera
// with supplied normals (GL's case), on the strafe without (Vulkan's).
using TemporalMotion = ApiCaseTest<PathCase>;
TEST_P(TemporalMotion, MotionVectorsMatchTheCpuReference) {
  const Path path = pathOf(param(), 4);
  FloatImage motion(path.depths[0].extent, 4);
  for (std::size_t i = 0; i < motion.data.size(); i += 4) motion.data[i] = 1.5f, motion.data[i + 1] = -0.75f;
  const bool withNormals = !param().strafing;
  const FloatImage normals = test::renderNormals(test::sphereOnPlaneScene(), path.cameras[0]);
  auto e = make();
  CpuFrames reference;
  for (std::uint32_t f = 0; f < 4; ++f) {
    Frame frame = path.frame(f, temporalMedium());
    frame.motion = &motion;
    frame.motionTexels = Texels::RGBA16F;
    frame.normals = withNormals ? &normals : nullptr;
    const Status st = e->render(frame);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(e->plan().variants[std::size_t(gen::VariantId::MOTION_VECTORS)], 1);
    EXPECT_EQ(e->plan().variants[std::size_t(gen::VariantId::NORMALS_SUPPLIED)], withNormals ? 1 : 0);
    expectAgreesWithCpu(*e, reference.run(frame), "temporal_motion_" + param().name + std::to_string(f));
  }
  // A motion input without the temporal setting: refused by name, by a running effect and a new one.
  Frame off = path.frame(0, presetSettings(Preset::Medium));
  off.motion = &motion;
  off.motionTexels = Texels::RGBA16F;
  auto fresh = make();
  for (Executor* x : {e.get(), fresh.get()}) {
    const Status refused = x->render(off);
    EXPECT_EQ(refused.code, StatusCode::InvalidInput);
    EXPECT_NE(refused.message.find("motion vectors serve temporal accumulation only"), std::string::npos)
        << refused.message;
  }
}
SAO_INSTANTIATE_API_CASES(TemporalMotion, kPaths);

}  // namespace
}  // namespace sao::exectest
