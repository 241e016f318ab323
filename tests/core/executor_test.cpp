// sao/executor.h: FrameState drives an executor exactly as the schedule says, keeps the images a
// new configuration keeps, fills the whole block, and keeps the temporal history's rule; checked
// with an executor that records every call.
#include <gtest/gtest.h>

#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "sao/executor.h"
#include "untuned_settings.h"

namespace {

sao::Camera camera(std::uint32_t width = 320, std::uint32_t height = 180) {
  sao::Camera c = sao::perspectiveCamera(std::numbers::pi / 3.0, width, height, 0.1, 100, sao::ClipDepth::ZeroToOne, false);
  c.view = std::array<double, 16>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  return c;
}

// Records each call as a line; images and pipelines are counted so that a leak shows.
struct RecordingExecutor : sao::Executor {
  std::vector<std::string> calls;
  std::vector<sao::PlannedImage> live;  // images created and not destroyed
  int pipelines = 0;
  int failCreateAt = -1;  // the index of the createImage call that fails
  int creates = 0;
  sao::FrameWork lastWork;
  sao::ParamBlock lastBlock{};

  sao::Status createImage(const sao::PlannedImage& image) override {
    if (creates++ == failCreateAt) return sao::Status::error(sao::StatusCode::DriverError, "out of memory");
    for (const sao::PlannedImage& other : live)
      EXPECT_FALSE(other.resource == image.resource && sao::sameImage(other, image)) << "created twice";
    live.push_back(image);
    calls.push_back("create " + std::string(sao::gen::kResources[std::size_t(image.resource)].name));
    return sao::Status::success();
  }
  void destroyImage(const sao::PlannedImage& image) noexcept override {
    auto it = std::find_if(live.begin(), live.end(), [&](const sao::PlannedImage& p) {
      return p.resource == image.resource && sao::sameImage(p, image);
    });
    EXPECT_NE(it, live.end()) << "destroyed an image never created";
    if (it != live.end()) live.erase(it);
    calls.push_back("destroy " + std::string(sao::gen::kResources[std::size_t(image.resource)].name));
  }
  bool failPrepare = false;
  int adopted = 0;
  sao::Status preparePlan(const sao::Plan&, const sao::Schedule&) override {
    calls.push_back("prepare");
    return failPrepare ? sao::Status::error(sao::StatusCode::DriverError, "no descriptor pool")
                       : sao::Status::success();
  }
  void planAdopted() noexcept override {
    ++adopted;
    calls.push_back("adopted");
  }
  sao::Status createPipeline(const sao::gen::PassInfo& pass, const sao::gen::PassVariantInfo&) override {
    ++pipelines;
    calls.push_back("pipeline " + std::string(pass.name));
    return sao::Status::success();
  }
  sao::Status beginFrame(const sao::FrameWork& work) override {
    lastWork = work;
    lastBlock = *work.block;
    calls.push_back("begin");
    return sao::Status::success();
  }
  void barrier(std::span<const sao::Hazard> hazards) override {
    EXPECT_FALSE(hazards.empty());
    calls.push_back("barrier " + std::to_string(hazards.size()));
  }
  void dispatch(const sao::ScheduledDispatch& d, std::span<const sao::ScheduledBinding> bindings) override {
    EXPECT_EQ(bindings.size(), d.variant->bindings.size());
    calls.push_back("dispatch " + std::string(sao::gen::pass(d.pass).name));
  }
  sao::Status endFrame() override {
    calls.push_back("end");
    return sao::Status::success();
  }
  std::size_t count(const std::string& prefix) const {
    return std::count_if(calls.begin(), calls.end(), [&](const std::string& c) { return c.rfind(prefix, 0) == 0; });
  }
};

TEST(Executor, AFrameIsTheScheduleInOrderWithTheWholeBlock) {
  const sao::Settings s = sao::test::untunedDefaults();
  sao::PlanInputs in;
  sao::FrameState frame("engine");
  RecordingExecutor ex;
  ASSERT_TRUE(frame.configure(s, camera(), in, ex).ok());
  EXPECT_EQ(ex.live.size(), frame.plan().images.size());
  EXPECT_EQ(std::size_t(ex.pipelines), frame.plan().passes.size());
  ex.calls.clear();
  sao::FrameInputs fi;
  fi.values.frameIndex = 3;
  ASSERT_TRUE(frame.run(fi, ex).ok());

  // What the schedule says, call for call.
  const sao::Schedule& schedule = frame.schedule();
  std::vector<std::string> expected{"begin"};
  if (!schedule.entryHazards().empty()) expected.push_back("barrier " + std::to_string(schedule.entryHazards().size()));
  for (const sao::ScheduledDispatch& d : schedule.dispatches) {
    if (!schedule.hazardsBefore(d).empty()) expected.push_back("barrier " + std::to_string(schedule.hazardsBefore(d).size()));
    expected.push_back("dispatch " + std::string(sao::gen::pass(d.pass).name));
  }
  if (!schedule.exitHazards().empty()) expected.push_back("barrier " + std::to_string(schedule.exitHazards().size()));
  expected.push_back("end");
  EXPECT_EQ(ex.calls, expected);

  // The block is frameConstants' for the same inputs, byte for byte (no history: temporal is off).
  sao::ParamBlock block{};
  ASSERT_TRUE(sao::frameConstants(s, camera(), in, fi.values, block).ok());
  EXPECT_EQ(std::memcmp(&block, &ex.lastBlock, sizeof block), 0);
  EXPECT_FALSE(ex.lastWork.historyValid);

  frame.release(ex);
  EXPECT_TRUE(ex.live.empty());
  EXPECT_FALSE(frame.configured());
}

TEST(Executor, ANewConfigurationRecreatesOnlyTheImagesItChanges) {
  sao::Settings s = sao::test::untunedDefaults();
  sao::FrameState frame("engine");
  RecordingExecutor ex;
  ASSERT_TRUE(frame.configure(s, camera(), {}, ex).ok());
  const int pipelines = ex.pipelines;
  // A block value: nothing is created or destroyed, no pipeline is made again.
  ex.calls.clear();
  s.radius = 2.5f;
  ASSERT_TRUE(frame.configure(s, camera(), {}, ex).ok());
  EXPECT_EQ(ex.count("create"), 0u);
  EXPECT_EQ(ex.count("destroy"), 0u);
  EXPECT_EQ(ex.pipelines, pipelines);
  // Another resolution: the reduced images change, the full-resolution chain (csz) is kept.
  ex.calls.clear();
  s.resolution_divisor = s.resolution_divisor == 1 ? 2 : 1;
  ASSERT_TRUE(frame.configure(s, camera(), {}, ex).ok());
  EXPECT_GT(ex.count("destroy"), 0u);
  EXPECT_EQ(ex.count("destroy csz"), 0u);
  EXPECT_EQ(ex.live.size(), frame.plan().images.size());
  // A resize changes every image.
  ex.calls.clear();
  const std::size_t before = ex.live.size();
  ASSERT_TRUE(frame.configure(s, camera(640, 360), {}, ex).ok());
  EXPECT_EQ(ex.count("destroy"), before);
  EXPECT_EQ(ex.live.size(), frame.plan().images.size());
  frame.release(ex);
  EXPECT_TRUE(ex.live.empty());
}

TEST(Executor, AFailedConfigurationChangesNothing) {
  const sao::Settings s = sao::test::untunedDefaults();
  sao::FrameState frame("engine");
  RecordingExecutor ex;
  ex.failCreateAt = 2;
  const sao::Status st = frame.configure(s, camera(), {}, ex);
  EXPECT_EQ(st.code, sao::StatusCode::DriverError);
  EXPECT_TRUE(ex.live.empty());
  EXPECT_FALSE(frame.configured());
  EXPECT_EQ(frame.run({}, ex).code, sao::StatusCode::InvalidInput);
  // After a configuration that ran, a failure on a resize keeps it: its images, its plan, its frames.
  ex.failCreateAt = -1;
  ASSERT_TRUE(frame.configure(s, camera(), {}, ex).ok());
  const std::size_t images = ex.live.size();
  const std::string plan = frame.plan().describe();
  ex.creates = 0;
  ex.failCreateAt = 1;
  ex.calls.clear();
  EXPECT_FALSE(frame.configure(s, camera(640, 360), {}, ex).ok());
  EXPECT_EQ(ex.live.size(), images);
  EXPECT_EQ(frame.plan().describe(), plan);
  EXPECT_TRUE(frame.configured());
  EXPECT_TRUE(frame.run({}, ex).ok());
  // Likewise when the executor cannot prepare the rest of the plan.
  ex.failCreateAt = -1;
  ex.failPrepare = true;
  const int adopted = ex.adopted;
  EXPECT_FALSE(frame.configure(s, camera(640, 360), {}, ex).ok());
  EXPECT_EQ(ex.live.size(), images);
  EXPECT_EQ(frame.plan().describe(), plan);
  EXPECT_EQ(ex.adopted, adopted);
  ex.failPrepare = false;
  // A resize that works creates the new images before the old ones go.
  ex.failCreateAt = -1;
  ex.calls.clear();
  ASSERT_TRUE(frame.configure(s, camera(640, 360), {}, ex).ok());
  const auto firstDestroy = std::find_if(ex.calls.begin(), ex.calls.end(),
                                         [](const std::string& c) { return c.rfind("destroy", 0) == 0; });
  EXPECT_EQ(std::count_if(firstDestroy, ex.calls.end(), [](const std::string& c) { return c.rfind("create", 0) == 0; }),
            0);
  EXPECT_LT(std::find(ex.calls.begin(), ex.calls.end(), "prepare"), firstDestroy);
  EXPECT_EQ(ex.calls.back(), "adopted");
  frame.release(ex);
  EXPECT_TRUE(ex.live.empty());
}

TEST(Executor, TheFrameIsCheckedBeforeTheExecutorSeesIt) {
  const sao::Settings s = sao::test::untunedDefaults();
  sao::FrameState frame("my-engine");
  RecordingExecutor ex;
  const sao::Status unconfigured = frame.run({}, ex);
  EXPECT_NE(unconfigured.message.find("my-engine"), std::string::npos) << unconfigured.message;
  ASSERT_TRUE(frame.configure(s, camera(), {}, ex).ok());
  ex.calls.clear();
  // A camera of another size changes the plan: refused, not silently replanned.
  const sao::Camera wide = camera(400, 180);
  sao::FrameInputs fi;
  fi.camera = &wide;
  const sao::Status st = frame.run(fi, ex);
  EXPECT_EQ(st.code, sao::StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("my-engine: this frame's camera"), std::string::npos) << st.message;
  // A mask that keeps channels of an effect-owned output.
  sao::FrameInputs masked;
  masked.values.outputChannels = sao::kChannelG;
  EXPECT_FALSE(frame.run(masked, ex).ok());
  // Supplied images are checked against the plan: depth of the wrong size.
  sao::SuppliedImages images{};
  images[std::size_t(sao::gen::ResourceId::depth)] = {true, {100, 100}, {}};
  sao::FrameInputs supplied;
  supplied.images = &images;
  EXPECT_FALSE(frame.run(supplied, ex).ok());
  EXPECT_TRUE(ex.calls.empty()) << "a refused frame reached the executor";
  frame.release(ex);
}

TEST(Executor, TheHistoryFollowsTheTemporalContract) {
  sao::Settings s = sao::test::untunedDefaults();
  s.temporal = true;
  sao::FrameState frame("engine");
  RecordingExecutor ex;
  ASSERT_TRUE(frame.configure(s, camera(), {}, ex).ok());
  ASSERT_TRUE(frame.run({}, ex).ok());
  EXPECT_FALSE(ex.lastWork.historyValid);
  const std::uint32_t parity = ex.lastWork.historyParity;
  ASSERT_TRUE(frame.run({}, ex).ok());
  EXPECT_TRUE(ex.lastWork.historyValid);
  EXPECT_EQ(ex.lastWork.historyParity, parity ^ 1u);
  // A camera cut.
  sao::FrameInputs cut;
  cut.resetHistory = true;
  ASSERT_TRUE(frame.run(cut, ex).ok());
  EXPECT_FALSE(ex.lastWork.historyValid);
  // A jittered camera keeps the plan and the history; another setting, or any configure(), starts
  // it again.
  sao::Camera jittered = camera();
  jittered.projection[8] += 0.001;
  ASSERT_TRUE(frame.run({}, ex).ok());
  ASSERT_TRUE(frame.render(s, jittered, {}, {}, ex).ok());
  EXPECT_TRUE(ex.lastWork.historyValid);
  s.radius = 3.0f;
  ASSERT_TRUE(frame.render(s, jittered, {}, {}, ex).ok());
  EXPECT_FALSE(ex.lastWork.historyValid);
  ASSERT_TRUE(frame.run({}, ex).ok());
  ASSERT_TRUE(frame.configure(s, camera(), {}, ex).ok());
  ASSERT_TRUE(frame.run({}, ex).ok());
  EXPECT_FALSE(ex.lastWork.historyValid);
  frame.release(ex);
  EXPECT_TRUE(ex.live.empty());
}

// render(): the per-frame call plans only when keeps() says so, and refuses a frame its new plan
// cannot take before touching an image.
TEST(Executor, RenderPlansOnlyWhenTheFrameNeedsIt) {
  sao::Settings s = sao::test::untunedDefaults();
  sao::FrameState frame("engine");
  RecordingExecutor ex;
  ASSERT_TRUE(frame.render(s, camera(), {}, {}, ex).ok());
  EXPECT_EQ(frame.plans(), 1u);
  // A jittered camera keeps the plan: no new configuration, nothing created.
  sao::Camera jittered = camera();
  jittered.projection[8] += 0.001;
  EXPECT_TRUE(frame.keeps(s, jittered, {}));
  ex.calls.clear();
  ASSERT_TRUE(frame.render(s, jittered, {}, {}, ex).ok());
  EXPECT_EQ(frame.plans(), 1u);
  EXPECT_EQ(ex.count("create"), 0u);
  // A resize with a depth image of the old size: refused before any image changes.
  sao::SuppliedImages images{};
  images[std::size_t(sao::gen::ResourceId::depth)] = {true, {320, 180}, {}};
  sao::FrameInputs fi;
  fi.images = &images;
  ex.calls.clear();
  EXPECT_FALSE(frame.render(s, camera(640, 360), {}, fi, ex).ok());
  EXPECT_TRUE(ex.calls.empty());
  EXPECT_EQ(frame.plans(), 1u);
  // An executor's own limit refuses the plan likewise.
  struct Limited : RecordingExecutor {
    sao::Status checkPlan(const sao::Plan& plan) override {
      return plan.aoExtent.width > 400 ? sao::Status::error(sao::StatusCode::InvalidExtent, "too wide")
                                       : sao::Status::success();
    }
  } limited;
  sao::FrameState other("engine");
  EXPECT_EQ(other.render(s, camera(640, 360), {}, {}, limited).code, sao::StatusCode::InvalidExtent);
  EXPECT_TRUE(limited.calls.empty());
  frame.release(ex);
}

// A device's limits against a plan, named as the API names them.
TEST(Executor, DeviceLimitsNameThePassAndTheLimit) {
  const sao::Settings s = sao::test::untunedDefaults();
  sao::Plan plan;
  ASSERT_TRUE(sao::plan(s, camera(), {}, plan).ok());
  sao::DeviceLimits limits;  // all 0: nothing checked
  EXPECT_TRUE(sao::checkDeviceLimits(plan, limits).ok());
  std::uint32_t shared = 0;
  for (const sao::PlannedPass& p : plan.passes) shared = std::max(shared, p.variant->sharedBytes);
  ASSERT_GT(shared, 0u) << "the default plan has a pass with shared memory";
  limits.sharedBytes = {shared, "maxComputeSharedMemorySize"};
  EXPECT_TRUE(sao::checkDeviceLimits(plan, limits).ok()) << "exactly the limit fits";
  limits.sharedBytes.value = shared - 1;
  const sao::Status st = sao::checkDeviceLimits(plan, limits);
  EXPECT_EQ(st.code, sao::StatusCode::DriverError);
  EXPECT_NE(st.message.find("bytes of shared memory, above this device's maxComputeSharedMemorySize " +
                            std::to_string(shared - 1)),
            std::string::npos)
      << st.message;
  EXPECT_NE(st.message.find("pass '"), std::string::npos) << st.message;
  limits.sharedBytes = {};
  limits.imageSide = {plan.inputExtent.width - 1, "GL_MAX_TEXTURE_SIZE"};
  const sao::Status side = sao::checkDeviceLimits(plan, limits);
  EXPECT_EQ(side.code, sao::StatusCode::InvalidExtent);
  EXPECT_NE(side.message.find("exceeds this device's GL_MAX_TEXTURE_SIZE"), std::string::npos) << side.message;
  limits.imageSide = {};
  limits.storageImagesPerPass = {1, "maxPerStageDescriptorStorageImages"};  // a levels= chain binds several
  EXPECT_NE(sao::checkDeviceLimits(plan, limits).message.find("storage images"), std::string::npos);
}

// repeat(): the same work again, the history not advanced twice.
TEST(Executor, RepeatRunsTheLastFrameAgain) {
  sao::Settings s = sao::test::untunedDefaults();
  s.temporal = true;
  sao::FrameState frame("engine");
  RecordingExecutor ex;
  EXPECT_FALSE(frame.repeat(ex).ok()) << "nothing ran yet";
  ASSERT_TRUE(frame.render(s, camera(), {}, {}, ex).ok());
  ASSERT_TRUE(frame.render(s, camera(), {}, {}, ex).ok());
  const std::vector<std::string> once = ex.calls;
  const std::uint32_t parity = ex.lastWork.historyParity;
  const sao::ParamBlock block = ex.lastBlock;
  const std::uint32_t next = frame.history().parity;
  ex.calls.clear();
  ASSERT_TRUE(frame.repeat(ex).ok());
  EXPECT_EQ(ex.lastWork.historyParity, parity);
  EXPECT_TRUE(ex.lastWork.historyValid);
  EXPECT_EQ(std::memcmp(&block, &ex.lastBlock, sizeof block), 0);
  EXPECT_EQ(frame.history().parity, next);
  EXPECT_EQ(ex.count("dispatch"), frame.schedule().dispatches.size());
  frame.release(ex);
  EXPECT_FALSE(frame.repeat(ex).ok());
}

}  // namespace
