// sao/frame.h: the frame's members of the parameter block, and the one rule for when a new camera
// keeps the plan (checked against plan() itself), with the temporal history's own rule beside it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "untuned_settings.h"
#include "sao/frame.h"
#include "sao/output.h"
#include "sao/temporal.h"

namespace {

sao::Camera perspective(double nearDistance = 0.1) {
  return sao::perspectiveCamera(std::numbers::pi / 3.0, 320, 180, nearDistance, 100, sao::ClipDepth::ZeroToOne, false);
}

sao::Camera withView(sao::Camera c) {
  c.view = std::array<double, 16>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  return c;
}

bool samePlan(const sao::Settings& s, const sao::Camera& a, const sao::Camera& b) {
  sao::Plan pa, pb;
  if (!sao::plan(s, a, {}, pa).ok() || !sao::plan(s, b, {}, pb).ok()) return false;
  return pa.describe() == pb.describe();
}

TEST(Frame, CompleteFrameFillsEveryPerFrameMember) {
  const sao::Settings s = sao::test::untunedDefaults();
  sao::PlanInputs in;
  in.outputFormat = sao::gen::Format::RGBA8;
  in.depthSamples = 4;
  const sao::FrameValues frame{{7, 11}, 5, sao::kChannelG | sao::kChannelA, sao::OutputBlend::Multiply};
  sao::ParamBlock constants{};
  ASSERT_TRUE(sao::computeConstants(s, perspective(), in.depthEncoding, constants).ok());
  sao::ParamBlock block{};
  ASSERT_TRUE(sao::frameConstants(s, perspective(), in, frame, block).ok());
  EXPECT_EQ(block.input_offset.x, 7);
  EXPECT_EQ(block.input_offset.y, 11);
  EXPECT_EQ(block.output_mask, sao::outputMaskParam(frame.outputChannels));
  EXPECT_EQ(block.output_blend, int(sao::OutputBlend::Multiply));
  EXPECT_EQ(block.depth_samples, 4);
  sao::ParamBlock frame5 = constants;
  sao::setFrameIndex(frame5, 5);
  EXPECT_EQ(block.frame_phase, frame5.frame_phase);
  EXPECT_EQ(block.frame_alpha_offset, frame5.frame_alpha_offset);
  // Nothing else moves: completing computeConstants' block by hand gives the same bytes.
  sao::completeFrame(constants, in, frame);
  EXPECT_EQ(std::memcmp(&constants, &block, sizeof block), 0);
}

// The output's mask and blend are the frame's: one check for every backend, named by `who`.
TEST(Frame, OutputUseIsCheckedPerFrame) {
  sao::Settings s = sao::test::untunedDefaults();
  sao::PlanInputs rgba;
  rgba.outputFormat = sao::gen::Format::RGBA16F;
  rgba.userOutput = true;
  sao::Plan plan;
  ASSERT_TRUE(sao::plan(s, perspective(), rgba, plan).ok());
  auto check = [&](const sao::PlanInputs& in, std::uint32_t mask, sao::OutputBlend blend) {
    return sao::checkFrameOutput(plan, in, {{}, 0, mask, blend}, "who");
  };
  EXPECT_TRUE(check(rgba, sao::kChannelA, sao::OutputBlend::Replace).ok());
  EXPECT_TRUE(check(rgba, sao::kAllChannels, sao::OutputBlend::Multiply).ok());
  const sao::Status empty = check(rgba, 0, sao::OutputBlend::Replace);
  EXPECT_EQ(empty.code, sao::StatusCode::InvalidInput);
  EXPECT_EQ(empty.message.rfind("who: the output channel mask 0 does not fit", 0), 0u) << empty.message;
  sao::PlanInputs owned = rgba;
  owned.userOutput = false;
  EXPECT_NE(check(owned, sao::kChannelA, sao::OutputBlend::Replace).message.find("which only your own image has"),
            std::string::npos);
  EXPECT_NE(check(owned, sao::kAllChannels, sao::OutputBlend::Multiply).message.find("needs your own output"),
            std::string::npos);
  // The bent normal output fills every channel: nothing kept, nothing multiplied.
  s.estimator = 1;
  s.bent_normals = true;
  s.blur_radius = 0;  // the direct path (direct_output)
  s.resolution_divisor = 1;
  s.temporal = false;
  sao::Plan bent;
  ASSERT_TRUE(sao::plan(s, perspective(), rgba, bent).ok());
  EXPECT_TRUE(sao::checkFrameOutput(bent, rgba, {}, "who").ok());
  const sao::Status kept = sao::checkFrameOutput(bent, rgba, {{}, 0, sao::kChannelA, sao::OutputBlend::Replace}, "who");
  EXPECT_NE(kept.message.find("bent_normals writes the bent normal"), std::string::npos) << kept.message;
  EXPECT_FALSE(sao::checkFrameOutput(bent, rgba, {{}, 0, sao::kAllChannels, sao::OutputBlend::Multiply}, "who").ok());
}

// Jitter, a mirrored eye, and any camera whose extents and csz levels match keep the plan (plan()
// agrees), whatever its projection kind; a new size, guard band or level count does not, each named.
TEST(Frame, CameraKeepsPlanExactlyWhenPlanAgrees) {
  const sao::Settings s = sao::test::untunedDefaults();
  const sao::Camera base = perspective();
  sao::Camera jittered = base;
  jittered.projection[8] += 0.01;
  EXPECT_TRUE(sao::checkCameraKeepsPlan(s, base, jittered).ok());

  sao::Camera wider = base;
  wider.width = 322;
  const sao::Status w = sao::checkCameraKeepsPlan(s, base, wider);
  EXPECT_EQ(w.code, sao::StatusCode::InvalidInput);
  EXPECT_NE(w.message.find("is 322x180 with guard band 0 but the plan's camera is 320x180 with guard band 0"),
            std::string::npos) << w.message;
  sao::Camera guarded = base;
  guarded.guardBand = 4;
  EXPECT_NE(sao::checkCameraKeepsPlan(s, base, guarded).message.find("guard band 4"), std::string::npos);

  // Orthographic cameras of several sizes: each keeps the plan exactly when plan() says it is the
  // same, and at least one does (the projection kind is a block value, not part of the plan).
  int kept = 0, refused = 0;
  for (double halfHeight : {0.05, 0.2, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 64.0}) {
    const sao::Camera ortho = sao::orthographicCamera(halfHeight, 320, 180, 0.1, 100, sao::ClipDepth::ZeroToOne, false);
    const sao::Status st = sao::checkCameraKeepsPlan(s, base, ortho);
    EXPECT_EQ(st.ok(), samePlan(s, base, ortho)) << halfHeight << ": " << st.message;
    EXPECT_EQ(st.ok(), sao::cameraKeepsPlan(s, base, ortho));
    if (st.ok()) ++kept;
    else {
      ++refused;
      EXPECT_NE(st.message.find("csz MIP levels but the plan has"), std::string::npos) << st.message;
    }
  }
  EXPECT_GT(kept, 0);
  EXPECT_GT(refused, 0);

  sao::Camera broken = base;
  broken.projection[0] = NAN;
  EXPECT_EQ(sao::checkCameraKeepsPlan(s, base, broken).code, sao::StatusCode::InvalidCamera);
  EXPECT_FALSE(sao::cameraKeepsPlan(s, base, broken));
  EXPECT_FALSE(sao::cameraKeepsPlan(s, broken, base));
}

// The plan lets a camera change its projection kind; the history does not follow it (its
// reprojection takes both cameras as the current one's kind), so that frame starts again.
TEST(Frame, HistoryStartsAgainWhenTheProjectionKindChanges) {
  sao::Settings s = sao::test::untunedDefaults();
  s.temporal = true;
  sao::TemporalHistory h;
  const sao::Camera persp = withView(perspective());
  sao::finishTemporalFrame(h, s, persp);
  sao::Camera jittered = persp;
  jittered.projection[8] += 0.01;
  sao::ParamBlock block{};
  ASSERT_TRUE(sao::computeConstants(s, jittered, sao::DepthEncoding::Hardware, block).ok());
  ASSERT_TRUE(sao::prepareTemporalFrame(h, s, jittered, nullptr, false, block).ok());
  EXPECT_EQ(block.history_valid, 1);

  const sao::Camera ortho = withView(sao::orthographicCamera(2.0, 320, 180, 0.1, 100, sao::ClipDepth::ZeroToOne, false));
  ASSERT_TRUE(sao::computeConstants(s, ortho, sao::DepthEncoding::Hardware, block).ok());
  ASSERT_TRUE(sao::prepareTemporalFrame(h, s, ortho, nullptr, false, block).ok());
  EXPECT_EQ(block.history_valid, 0);
  // Named as the previous camera, another kind is refused, as before.
  const sao::Status st = sao::prepareTemporalFrame(h, s, ortho, &persp, false, block);
  EXPECT_EQ(st.code, sao::StatusCode::InvalidCamera);
  EXPECT_NE(st.message.find("projection kind"), std::string::npos) << st.message;
}

}  // namespace
