// resolution_divisor in plan() and makeSchedule(): at 1 the output pass copies A into the output,
// at 2 and 4 the upsample writes it instead; at 2 and 4 ao_sample and the blur run on the viewport over
// the divisor rounded up (641x359 -> 321x180, 161x90), upsample writes the full-size output, and
// the plan's bytes count the reduced images at their reduced size.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "untuned_settings.h"
#include "sao/constants.h"
#include "sao/schedule.h"

namespace {

using sao::gen::PassId;
using sao::gen::ResourceId;

sao::Camera camera641(std::uint32_t guard) {
  sao::Camera c =
      sao::perspectiveCamera(std::numbers::pi / 3.0, 641, 359, 0.1, INFINITY, sao::ClipDepth::ZeroToOne, true);
  c.guardBand = guard;
  return c;
}

std::string passNames(const sao::Plan& p) {
  std::string t;
  for (const auto& x : p.passes) t += std::string(t.empty() ? "" : " ") + std::string(sao::gen::pass(x.pass).name);
  return t;
}

sao::Extent extentOf(const sao::Plan& p, ResourceId id) {
  const sao::PlannedImage* i = p.image(id);
  return i ? i->extent : sao::Extent{};
}

struct Expected {
  int divisor;
  const char* passes;
  sao::Extent reduced;
};

TEST(Plan, ResolutionDivisorSizesTheReducedImagesAndTheirBytes) {
  const sao::Camera camera = camera641(3);  // csz 647x365 whatever the divisor
  const Expected cases[] = {
      {1, "linear_z ao_sample blur output", {641, 359}},
      {2, "linear_z ao_sample blur upsample", {321, 180}},
      {4, "linear_z ao_sample blur upsample", {161, 90}},
  };
  std::uint64_t cszBytes = 0;
  for (const Expected& c : cases) {
    sao::Settings s = sao::test::untunedDefaults();
    s.resolution_divisor = c.divisor;
    sao::Plan p;
    ASSERT_TRUE(sao::plan(s, camera, {}, p).ok()) << c.divisor;
    std::printf("divisor %d: %s", c.divisor, p.describe().c_str());
    EXPECT_EQ(passNames(p), c.passes) << c.divisor;
    EXPECT_EQ(p.aoExtent, (sao::Extent{641, 359}));
    EXPECT_EQ(extentOf(p, ResourceId::ao), (sao::Extent{641, 359})) << "the output is always the viewport";
    EXPECT_EQ(extentOf(p, ResourceId::ao_raw), c.reduced) << c.divisor;
    EXPECT_EQ(extentOf(p, ResourceId::ao_low), c.reduced) << c.divisor;
    const sao::PlannedImage* csz = p.image(ResourceId::csz);
    ASSERT_NE(csz, nullptr);
    EXPECT_EQ(csz->extent, (sao::Extent{647, 365})) << "upsample reads the full-resolution z";
    if (cszBytes == 0) cszBytes = csz->bytes;
    EXPECT_EQ(csz->bytes, cszBytes) << "the z hierarchy does not depend on the divisor";
    const std::uint64_t reducedRg32f = std::uint64_t(c.reduced.width) * c.reduced.height * 8;
    const std::uint64_t outputR16f = 641ull * 359 * 2;
    EXPECT_EQ(p.totalBytes, cszBytes + 2 * reducedRg32f + outputR16f) << "ao_raw, ao_low, ao; " << c.divisor;
  }
  // By hand at 641x359: full 2 x 1,840,952 + 460,238 = 4,142,142 bytes besides csz; half
  // 2 x 462,240 + 460,238 = 1,384,718; quarter 2 x 115,920 + 460,238 = 692,078.
  sao::Settings half = sao::test::untunedDefaults(), quarter = sao::test::untunedDefaults();
  half.resolution_divisor = 2;
  quarter.resolution_divisor = 4;
  sao::Plan full, h, q;
  ASSERT_TRUE(sao::plan(sao::test::untunedDefaults(), camera, {}, full).ok());
  ASSERT_TRUE(sao::plan(half, camera, {}, h).ok());
  ASSERT_TRUE(sao::plan(quarter, camera, {}, q).ok());
  EXPECT_EQ(full.totalBytes - cszBytes, 4142142u);
  EXPECT_EQ(h.totalBytes - cszBytes, 1384718u);
  EXPECT_EQ(q.totalBytes - cszBytes, 692078u);
}

TEST(Plan, ResolutionDivisorThreeIsRefused) {
  sao::Settings s = sao::test::untunedDefaults();
  s.resolution_divisor = 3;
  sao::Plan p;
  const sao::Status st = sao::plan(s, camera641(0), {}, p);
  EXPECT_EQ(st.code, sao::StatusCode::InvalidSetting);
  EXPECT_EQ(st.message, "setting 'resolution_divisor' = 3 is not one of its allowed values {1, 2, 4}");
}

// Without blur the blur pass and ao_low go: upsample reads ao_raw in place of the skipped blur's
// image (three dispatches); at divisor 1 ao_sample_output writes the output (two dispatches), and
// with temporal accumulation (ao_sample writes the history) the output pass reads ao_raw.
TEST(Plan, WithoutBlurTheUpsampleReadsTheRawImage) {
  for (int d : {1, 2, 4})
    for (bool temporal : {false, true}) {
      sao::Settings s = sao::test::untunedDefaults();
      s.resolution_divisor = d;
      s.blur_radius = 0;
      s.temporal = temporal;
      sao::Plan p;
      ASSERT_TRUE(sao::plan(s, camera641(0), {}, p).ok());
      const char* expected = d > 1 ? "linear_z ao_sample upsample"
                             : temporal ? "linear_z ao_sample output" : "linear_z ao_sample_output";
      EXPECT_EQ(passNames(p), expected) << d << " " << temporal;
      EXPECT_EQ(p.image(ResourceId::ao_low), nullptr) << d;
      const auto& last = p.passes.back();
      if (d > 1 || temporal) EXPECT_EQ(p.resolve(last, ResourceId::ao_low), ResourceId::ao_raw) << d;
      else EXPECT_EQ(p.image(ResourceId::ao_raw), nullptr);
    }
}

// The dispatches cover the reduced extent up to the blur (8 x 32 texels a group: texels=1x4) and
// the viewport in upsample (16 x 16 pixels a group: texels=2x2), which waits for ao_low (and csz,
// already visible since ao_sample read it).
TEST(Schedule, ReducedResolutionDispatchSizes) {
  sao::Settings s = sao::test::untunedDefaults();
  s.resolution_divisor = 4;
  sao::Plan p;
  ASSERT_TRUE(sao::plan(s, camera641(0), {}, p).ok());
  const sao::Schedule sch = sao::makeSchedule(p);
  std::printf("%s", sch.describe().c_str());
  bool sawUpsample = false;
  for (const sao::ScheduledDispatch& d : sch.dispatches) {
    if (d.pass == PassId::ao_sample || d.pass == PassId::blur) {
      EXPECT_EQ(d.groupsX, 21u) << sao::gen::pass(d.pass).name << ": ceil(161 / 8)";
      EXPECT_EQ(d.groupsY, d.pass == PassId::blur ? 3u : 12u) << sao::gen::pass(d.pass).name << ": ceil(90 / 32), ceil(90 / 8)";
    }
    if (d.pass != PassId::upsample) continue;
    sawUpsample = true;
    EXPECT_EQ(d.groupsX, 41u) << "ceil(641 / 16)";
    EXPECT_EQ(d.groupsY, 23u) << "ceil(359 / 16)";
    ASSERT_EQ(sch.hazardsBefore(d).size(), 1u);
    EXPECT_EQ(sch.hazardsBefore(d)[0].resource, ResourceId::ao_low);
    EXPECT_EQ(sch.hazardsBefore(d)[0].kind, sao::HazardKind::ReadAfterWrite);
  }
  EXPECT_TRUE(sawUpsample);
}

// The block member the shaders read: ao_divisor is the setting, for every allowed value.
TEST(Constants, AoDivisorIsTheResolutionDivisor) {
  for (int d : {1, 2, 4}) {
    sao::Settings s = sao::test::untunedDefaults();
    s.resolution_divisor = d;
    sao::ParamBlock p;
    ASSERT_TRUE(sao::computeConstants(s, camera641(2), sao::DepthEncoding::Hardware, p).ok());
    EXPECT_EQ(p.ao_divisor, d);
    EXPECT_EQ(p.ao_size.x, 641) << "ao_size stays the viewport";
    EXPECT_EQ(p.ao_size.y, 359);
  }
}

}  // namespace
