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
  in.outputChannels = sao::kChannelG | sao::kChannelA;
  in.outputBlend = sao::OutputBlend::Multiply;
  in.depthSamples = 4;
  sao::ParamBlock constants{};
  ASSERT_TRUE(sao::computeConstants(s, perspective(), in.depthEncoding, constants).ok());
  sao::ParamBlock block{};
  ASSERT_TRUE(sao::frameConstants(s, perspective(), in, {{7, 11}, 5}, block).ok());
  EXPECT_EQ(block.input_offset.x, 7);
  EXPECT_EQ(block.input_offset.y, 11);
  EXPECT_EQ(block.output_mask, sao::outputMaskParam(in.outputChannels));
  EXPECT_EQ(block.output_blend, int(sao::OutputBlend::Multiply));
  EXPECT_EQ(block.depth_samples, 4);
  sao::ParamBlock frame5 = constants;
  sao::setFrameIndex(frame5, 5);
  EXPECT_EQ(block.frame_phase, frame5.frame_phase);
  EXPECT_EQ(block.frame_alpha_offset, frame5.frame_alpha_offset);
  // Nothing else moves: completing computeConstants' block by hand gives the same bytes.
  sao::completeFrame(constants, in, {{7, 11}, 5});
  EXPECT_EQ(std::memcmp(&constants, &block, sizeof block), 0);
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
