// makeSchedule(): the flat dispatch list the backends translate. Dispatch sizes, resolved
// bindings (aliases, a levels= pass writing a whole MIP chain), and the fewest hazards that order the
// frame: a write becomes visible to sampled reads once, just before the first dispatch that
// reads it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "untuned_settings.h"
#include "sao/schedule.h"

namespace {

using sao::HazardKind;
using sao::gen::PassId;
using sao::gen::ResourceId;

sao::Camera camera(std::uint32_t w, std::uint32_t h, std::uint32_t guard) {
  sao::Camera c =
      sao::perspectiveCamera(std::numbers::pi / 3.0, w, h, 0.1, INFINITY, sao::ClipDepth::ZeroToOne, true);
  c.guardBand = guard;
  return c;
}

sao::Schedule scheduleOf(const sao::Settings& s, const sao::Camera& c, const sao::PlanInputs& in = {}) {
  sao::Plan p;
  EXPECT_TRUE(sao::plan(s, c, in, p).ok());
  return sao::makeSchedule(p);
}

TEST(Schedule, DefaultSettings) {
  const sao::Settings settings = sao::test::untunedDefaults();
  sao::Plan p;
  ASSERT_TRUE(sao::plan(settings, camera(100, 60, 4), {}, p).ok());
  const sao::Schedule s = sao::makeSchedule(p);
  std::printf("%s", s.describe().c_str());
  const std::uint32_t L = p.cszLevels;
  ASSERT_GT(L, 2u);
  ASSERT_EQ(s.dispatches.size(), 4u) << "linear_z (the whole chain), ao_sample, two blurs";

  // linear_z covers the input (108x68 with the guard band), 2x2 texels an invocation: 7x5 groups
  // of 8x8 (16x16 texels each); it writes every level of csz (one binding, an array of eight
  // slots, the L levels first) and reads only the depth.
  const auto& z = s.dispatches[0];
  EXPECT_EQ(z.pass, PassId::linear_z);
  EXPECT_EQ(z.level, 0u);
  EXPECT_EQ(z.groupsX, 7u);
  EXPECT_EQ(z.groupsY, 5u);
  EXPECT_EQ(z.hazardCount, 0u);
  for (const auto& b : s.bindingsOf(z))
    if (b.write) {
      EXPECT_EQ(b.resource, ResourceId::csz);
      EXPECT_EQ(b.baseLevel, 0u);
      EXPECT_EQ(b.levelCount, L);
    }

  // ao_sample reads the whole chain, all of it pending: one hazard for the run of levels.
  const auto& ao = s.dispatches[1];
  EXPECT_EQ(ao.pass, PassId::ao_sample);
  EXPECT_EQ(ao.groupsX, 13u);  // the AO extent 100x60
  EXPECT_EQ(ao.groupsY, 8u);
  bool sawChain = false;
  for (const auto& b : s.bindingsOf(ao))
    if (!b.write && b.resource == ResourceId::csz) {
      EXPECT_TRUE(b.wholeChain);
      EXPECT_EQ(b.levelCount, L);
      sawChain = true;
    }
  EXPECT_TRUE(sawChain);
  ASSERT_EQ(ao.hazardCount, 1u);
  EXPECT_EQ(s.hazardsBefore(ao)[0].kind, HazardKind::ReadAfterWrite);
  EXPECT_EQ(s.hazardsBefore(ao)[0].baseLevel, 0u);
  EXPECT_EQ(s.hazardsBefore(ao)[0].levelCount, L);

  // The blur and the output pass each wait for the image the previous dispatch wrote.
  const auto& blur = s.dispatches[2];
  const auto& up = s.dispatches[3];
  EXPECT_EQ(blur.pass, PassId::blur);
  EXPECT_EQ(up.pass, PassId::output);
  ASSERT_EQ(blur.hazardCount, 1u);
  EXPECT_EQ(s.hazardsBefore(blur)[0].resource, ResourceId::ao_raw);
  ASSERT_EQ(up.hazardCount, 1u);
  EXPECT_EQ(s.hazardsBefore(up)[0].resource, ResourceId::ao_low);

  // Entry: the caller's depth, then every written image against the previous frame. Exit: the output.
  int callerWrote = 0, written = 0;
  for (const auto& h : s.entryHazards()) {
    if (h.kind == HazardKind::CallerWrote) {
      EXPECT_EQ(h.resource, ResourceId::depth);
      ++callerWrote;
    } else {
      EXPECT_EQ(h.kind, HazardKind::WriteAfterRead) << "every written image is read by someone";
      ++written;
    }
  }
  EXPECT_EQ(callerWrote, 1);
  EXPECT_EQ(written, 4) << "csz, ao_raw, ao_low, ao";
  ASSERT_EQ(s.exitHazards().size(), 1u);
  EXPECT_EQ(s.exitHazards()[0].resource, ResourceId::ao);
  EXPECT_EQ(s.exitHazards()[0].kind, HazardKind::CallerReads);
}

TEST(Schedule, NoBlurReadsTheAliasedImage) {
  sao::Settings settings = sao::test::untunedDefaults();
  settings.blur_radius = 0;
  settings.resolution_divisor = 2;
  const sao::Schedule s = scheduleOf(settings, camera(64, 32, 0));
  const auto& last = s.dispatches.back();
  EXPECT_EQ(last.pass, PassId::upsample);
  for (const auto& b : s.bindingsOf(last))
    if (b.resource != ResourceId::csz) { EXPECT_EQ(b.resource, b.write ? ResourceId::ao : ResourceId::ao_raw); }
  ASSERT_EQ(last.hazardCount, 1u);
  EXPECT_EQ(s.hazardsBefore(last)[0].resource, ResourceId::ao_raw);
  for (const auto& d : s.dispatches) EXPECT_NE(d.pass, PassId::blur);
}

// Without blur at full resolution ao_sample_output writes the output after linear_z: its one
// hazard is csz, and the caller reads ao after it.
TEST(Schedule, NoBlurAtFullResolutionSamplesStraightIntoTheOutput) {
  sao::Settings settings = sao::test::untunedDefaults();
  settings.blur_radius = 0;
  const sao::Schedule s = scheduleOf(settings, camera(64, 32, 0));
  ASSERT_EQ(s.dispatches.size(), 2u);
  const auto& last = s.dispatches.back();
  EXPECT_EQ(last.pass, PassId::ao_sample_output);
  bool writesAo = false;
  for (const auto& b : s.bindingsOf(last)) {
    if (b.write) writesAo = writesAo || b.resource == ResourceId::ao;
    EXPECT_NE(b.resource, ResourceId::ao_raw);
  }
  EXPECT_TRUE(writesAo);
  ASSERT_EQ(last.hazardCount, 1u);
  EXPECT_EQ(s.hazardsBefore(last)[0].resource, ResourceId::csz);
  ASSERT_EQ(s.exitHazards().size(), 1u);
  EXPECT_EQ(s.exitHazards()[0].resource, ResourceId::ao);
}

// The temporal history (history=true): two copies of ao_raw's size at 16 bytes a texel;
// ao_sample reads the previous frame's copy (no hazard inside the frame: nothing in it writes that
// copy) and writes this frame's; the frame's entry makes the previous frame's writes visible (RAW
// on the previous copy) and orders this frame's write after the previous frame's read (WAR).
TEST(Schedule, TemporalHistoryIsReadFromThePreviousFrameAndWrittenForTheNext) {
  sao::Settings settings = sao::test::untunedDefaults();
  settings.temporal = true;
  settings.resolution_divisor = 2;
  sao::Plan p;
  ASSERT_TRUE(sao::plan(settings, camera(64, 32, 0), {}, p).ok());
  const sao::PlannedImage* history = p.image(ResourceId::history);
  ASSERT_NE(history, nullptr);
  EXPECT_EQ(history->copies, 2u);
  EXPECT_EQ(history->extent, (sao::Extent{32, 16}));
  EXPECT_EQ(history->bytes, 2u * 32u * 16u * 16u);
  const sao::Schedule s = sao::makeSchedule(p);
  std::printf("%s", s.describe().c_str());
  int reads = 0, writes = 0;
  for (const auto& d : s.dispatches)
    for (const auto& b : s.bindingsOf(d))
      if (b.resource == ResourceId::history) {
        EXPECT_EQ(d.pass, PassId::ao_sample);
        EXPECT_EQ(b.previousFrame, !b.write);
        (b.write ? writes : reads) += 1;
      }
  EXPECT_EQ(reads, 1);
  EXPECT_EQ(writes, 1);
  for (const auto& d : s.dispatches)
    for (const auto& h : s.hazardsBefore(d)) EXPECT_NE(h.resource, ResourceId::history) << "no hazard inside the frame";
  int rawPrevious = 0, warCurrent = 0;
  for (const auto& h : s.entryHazards())
    if (h.resource == ResourceId::history) {
      rawPrevious += h.kind == HazardKind::ReadAfterWrite && h.previousFrame;
      warCurrent += h.kind == HazardKind::WriteAfterRead && !h.previousFrame;
    }
  EXPECT_EQ(rawPrevious, 1);
  EXPECT_EQ(warCurrent, 1);
  // Without the setting there is no history at all.
  settings.temporal = false;
  ASSERT_TRUE(sao::plan(settings, camera(64, 32, 0), {}, p).ok());
  EXPECT_EQ(p.image(ResourceId::history), nullptr);
}

TEST(Schedule, WithoutTheHierarchyThereIsNoMipDispatch) {
  sao::Settings settings = sao::test::untunedDefaults();
  settings.use_z_hierarchy = false;
  const sao::Schedule s = scheduleOf(settings, camera(64, 32, 0));
  ASSERT_EQ(s.dispatches.size(), 4u);
  // ao_sample reads the single csz level, written by linear_z just before.
  ASSERT_EQ(s.dispatches[1].hazardCount, 1u);
  EXPECT_EQ(s.hazardsBefore(s.dispatches[1])[0].resource, ResourceId::csz);
  for (const auto& b : s.bindingsOf(s.dispatches[1])) EXPECT_FALSE(b.wholeChain);
}

TEST(Schedule, SecondLayerAndNormalsAreReadAndWrittenInTheSameDispatches) {
  const sao::Schedule s = scheduleOf(sao::test::untunedDefaults(), camera(64, 32, 2), {sao::DepthEncoding::Hardware, {.depth2 = true, .normals = true}});
  int callerWrote = 0;
  for (const auto& h : s.entryHazards()) callerWrote += h.kind == HazardKind::CallerWrote;
  EXPECT_EQ(callerWrote, 3) << "depth, depth2, normals";
  // linear_z writes csz, linear_z2 csz2 (eight storage images each, GL's minimum); ao_sample
  // waits for both chains.
  ASSERT_EQ(s.dispatches.size(), 5u);
  EXPECT_EQ(s.dispatches[0].pass, PassId::linear_z);
  EXPECT_EQ(s.dispatches[1].pass, PassId::linear_z2);
  EXPECT_EQ(s.dispatches[2].pass, PassId::ao_sample);
  EXPECT_EQ(s.dispatches[1].hazardCount, 0u);
  ASSERT_EQ(s.dispatches[2].hazardCount, 2u);
  EXPECT_EQ(s.hazardsBefore(s.dispatches[2])[0].resource, ResourceId::csz);
  EXPECT_EQ(s.hazardsBefore(s.dispatches[2])[1].resource, ResourceId::csz2);
}

TEST(Schedule, SuppliedImagesAreCheckedAgainstThePlan) {
  sao::Plan p;
  ASSERT_TRUE(sao::plan(sao::test::untunedDefaults(), camera(64, 32, 2), {}, p).ok());
  sao::SuppliedImages in{};
  in[static_cast<std::size_t>(ResourceId::depth)] = {true, {68, 36}};
  EXPECT_TRUE(sao::checkSupplied(p, in, false, "test").ok());
  in[static_cast<std::size_t>(ResourceId::depth)] = {true, {64, 32}};
  const sao::Status wrong = sao::checkSupplied(p, in, false, "test");
  EXPECT_EQ(wrong.code, sao::StatusCode::InvalidInput);
  EXPECT_NE(wrong.message.find("is 64x32, the camera needs 68x36"), std::string::npos) << wrong.message;
  in[static_cast<std::size_t>(ResourceId::depth)] = {false, {}};
  EXPECT_NE(sao::checkSupplied(p, in, false, "test").message.find("none is supplied"), std::string::npos);
  in[static_cast<std::size_t>(ResourceId::depth)] = {true, {68, 36}};
  in[static_cast<std::size_t>(ResourceId::normals)] = {true, {68, 36}};
  EXPECT_EQ(sao::checkSupplied(p, in, false, "test").code, sao::StatusCode::InvalidInput) << "normals not planned";
  in[static_cast<std::size_t>(ResourceId::normals)] = {};
  in[static_cast<std::size_t>(ResourceId::ao)] = {true, {64, 32}};
  EXPECT_EQ(sao::checkSupplied(p, in, false, "test").code, sao::StatusCode::InvalidInput) << "output not expected";
  EXPECT_TRUE(sao::checkSupplied(p, in, true, "test").ok());
  in[static_cast<std::size_t>(ResourceId::ao)] = {true, {60, 32}};
  EXPECT_EQ(sao::checkSupplied(p, in, true, "test").code, sao::StatusCode::InvalidInput) << "output size";
}

}  // namespace
