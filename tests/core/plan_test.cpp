// plan() models only what the scene needs: MIP levels from the largest projected radius,
// variants from the inputs, images and bytes, dropped passes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "untuned_settings.h"
#include "sao/frame.h"
#include "sao/plan.h"
#include "sao/schedule.h"
#include "sao/settings.h"

namespace {

using sao::gen::PassId;
using sao::gen::ResourceId;

sao::Camera camera720() {
  return sao::perspectiveCamera(std::numbers::pi / 3.0, 1280, 720, 0.1, INFINITY, sao::ClipDepth::ZeroToOne, true);
}

bool hasPass(const sao::Plan& p, PassId id) {
  for (const auto& x : p.passes)
    if (x.pass == id) return true;
  return false;
}

TEST(Plan, DefaultSceneAt720p) {
  sao::Plan p;
  ASSERT_TRUE(sao::plan(sao::test::untunedDefaults(), camera720(), {}, p).ok());
  // r' max = r S' / n = 1 * 623.5 / 0.1 = 6235 px -> floor(log2) = 12; minus log q' 3 = 9,
  // capped by SAO_MAX_MIP_LEVELS - 1 = 7 -> 8 levels.
  EXPECT_EQ(p.cszLevels, 8u);
  EXPECT_EQ(p.passes.size(), 4u) << "linear_z, ao_sample, blur, output";
  EXPECT_EQ(p.passes[0].pass, PassId::linear_z);
  EXPECT_EQ(sao::makeSchedule(p).dispatches.size(), p.passes.size()) << "one dispatch a pass: linear_z writes the whole chain";
  EXPECT_FALSE(hasPass(p, PassId::linear_z2)) << "no second layer given";
  const auto* csz = p.image(ResourceId::csz);
  ASSERT_NE(csz, nullptr);
  EXPECT_EQ(csz->mipLevels, 8u);
  EXPECT_EQ(p.image(ResourceId::csz2), nullptr) << "no second layer given";
  // Bytes by hand: csz r32f, levels 1280x720 ... 10x5 = 1,228,750 texels x 4 = 4,915,000;
  // ao_raw and ao_low rg32f 1280x720 x 8 = 7,372,800 each; ao r16f x 2 = 1,843,200.
  EXPECT_EQ(csz->bytes, 4915000u);
  EXPECT_EQ(p.image(ResourceId::ao_raw)->bytes, 7372800u);
  EXPECT_EQ(p.image(ResourceId::ao_low)->bytes, 7372800u);
  EXPECT_EQ(p.image(ResourceId::ao)->bytes, 1843200u);
  EXPECT_EQ(p.totalBytes, 21503800u);
  // Without a plan: both layers' chains, width_run's (rg16f: 4 bytes a texel too) and csz_share's
  // (rg32f: 8) down to 1x1 (11 levels, 1,228,763 texels each) and every image at its largest (ao_raw
  // and ao_low undivided and rg32f; the temporal history, rgba32f in two copies): 3 x 4,915,052 +
  // 9,830,104 + 2 x 7,372,800 + 1,843,200 + 2 x 14,745,600.
  const std::uint64_t full = sao::fullAllocationBytes(camera720(), {});
  EXPECT_EQ(full, 70655260u);
  std::printf("default scene 1280x720: %s", p.describe().c_str());
  std::printf("full allocation: %llu bytes (plan %.1f%% of it)\n", static_cast<unsigned long long>(full),
              100.0 * double(p.totalBytes) / double(full));
}

TEST(Plan, SmallRadiusWithoutBlurAllocatesLittle) {
  sao::Settings s = sao::test::untunedDefaults();
  s.radius = 0.01f;  // r' max 62 px: 3 csz levels
  s.blur_radius = 0;  // no blur at full resolution: ao_sample_output writes ao, no ao_raw, no ao_low
  sao::Plan p;
  ASSERT_TRUE(sao::plan(s, camera720(), {}, p).ok());
  EXPECT_EQ(p.cszLevels, 3u);
  // csz (921,600 + 230,400 + 57,600) x 4 + ao 1,843,200 (before ao_sample_output also ao_raw's 7,372,800).
  EXPECT_EQ(p.totalBytes, 4838400u + 1843200u);
  std::printf("radius 0.01 m, blur 0, 1280x720: %llu bytes (%.1f%% of the full allocation)\n",
              static_cast<unsigned long long>(p.totalBytes),
              100.0 * double(p.totalBytes) / double(sao::fullAllocationBytes(camera720(), {})));
}

TEST(Plan, SmallRadiusNeedsFewerLevels) {
  sao::Settings s = sao::test::untunedDefaults();
  sao::Plan big, small;
  ASSERT_TRUE(sao::plan(s, camera720(), {}, big).ok());
  s.radius = 0.01f;  // r' max = 62 px -> 5 - 3 = 2 -> 3 levels
  ASSERT_TRUE(sao::plan(s, camera720(), {}, small).ok());
  EXPECT_EQ(small.cszLevels, 3u);
  EXPECT_LT(small.cszLevels, big.cszLevels);
  EXPECT_LT(small.totalBytes, big.totalBytes);
  auto cam = camera720();
  cam.projection[14] *= 100.0;  // near plane at 10 m: r' max = 62 px as well
  ASSERT_TRUE(sao::plan(sao::test::untunedDefaults(), cam, {}, small).ok());
  EXPECT_EQ(small.cszLevels, 3u);
}

TEST(Plan, VariantsFollowTheInputs) {
  sao::Plan p;
  ASSERT_TRUE(sao::plan(sao::test::untunedDefaults(), camera720(), {}, p).ok());
  EXPECT_EQ(p.variants[static_cast<std::size_t>(sao::gen::VariantId::NORMALS_SUPPLIED)], 0);
  sao::PlanInputs in;
  in.supplied.normals = true;
  ASSERT_TRUE(sao::plan(sao::test::untunedDefaults(), camera720(), in, p).ok());
  EXPECT_EQ(p.variants[static_cast<std::size_t>(sao::gen::VariantId::NORMALS_SUPPLIED)], 1)
      << "supplying normals removes the reconstruction variant";
  for (const auto& pass : p.passes) EXPECT_EQ(pass.variant, sao::gen::findPassVariant(pass.pass, p.variants));

  in.supplied.depth2 = true;
  ASSERT_TRUE(sao::plan(sao::test::untunedDefaults(), camera720(), in, p).ok());
  ASSERT_NE(p.image(ResourceId::csz2), nullptr);
  EXPECT_EQ(p.image(ResourceId::csz2)->mipLevels, p.cszLevels);

  sao::Settings flat = sao::test::untunedDefaults();
  flat.use_z_hierarchy = false;
  const sao::Status st = sao::plan(flat, camera720(), in, p);
  EXPECT_EQ(st.code, sao::StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("single-layer"), std::string::npos) << st.message;
}

TEST(Plan, NoHierarchyMeansOneLevel) {
  sao::Settings s = sao::test::untunedDefaults();
  s.use_z_hierarchy = false;
  sao::Plan p;
  ASSERT_TRUE(sao::plan(s, camera720(), {}, p).ok());
  EXPECT_EQ(p.cszLevels, 1u);
  EXPECT_EQ(p.variants[static_cast<std::size_t>(sao::gen::VariantId::Z_HIERARCHY)], 0);
}

// The derived settings read as bools of their terms, and writing one changes nothing.
TEST(Settings, DerivedSettingsFollowTheirTerms) {
  using sao::gen::SettingId;
  for (int blur : {0, 1})
    for (int d : {1, 2, 4})
      for (bool temporal : {false, true}) {
        sao::Settings s;
        s.blur_radius = blur;
        s.resolution_divisor = d;
        s.temporal = temporal;
        const bool direct = blur == 0 && d == 1 && !temporal;
        EXPECT_EQ(sao::gen::settingValue(s, SettingId::direct_output), direct ? 1.0 : 0.0);
        EXPECT_EQ(sao::gen::settingValue(s, SettingId::copy_to_output), d == 1 && !direct ? 1.0 : 0.0);
        const sao::Settings before = s;
        sao::gen::setSettingValue(s, SettingId::direct_output, direct ? 0.0 : 1.0);
        EXPECT_EQ(s, before);
      }
  EXPECT_FALSE(sao::findSetting("direct_output")) << "not a user setting";
}

// Without blur at full resolution nothing follows the AO: ao_sample_output writes the output
// itself (derived setting direct_output), so neither ao_sample, the blur, the output pass nor
// their images are planned: two dispatches.
TEST(Plan, BlurZeroAtFullResolutionWritesTheOutputFromTheSamplingPass) {
  sao::Settings s = sao::test::untunedDefaults();
  s.blur_radius = 0;
  sao::Plan p;
  ASSERT_TRUE(sao::plan(s, camera720(), {}, p).ok());
  ASSERT_EQ(p.passes.size(), 2u);
  EXPECT_EQ(p.passes[0].pass, PassId::linear_z);
  EXPECT_EQ(p.passes[1].pass, PassId::ao_sample_output);
  EXPECT_EQ(p.image(ResourceId::ao_raw), nullptr);
  EXPECT_EQ(p.image(ResourceId::ao_low), nullptr);
  EXPECT_NE(p.image(ResourceId::ao), nullptr);
  // With a blur the copy pass stays; at half resolution the upsample reads ao_raw.
  s.blur_radius = 1;
  ASSERT_TRUE(sao::plan(s, camera720(), {}, p).ok());
  EXPECT_TRUE(hasPass(p, PassId::ao_sample) && hasPass(p, PassId::blur) && hasPass(p, PassId::output));
  EXPECT_FALSE(hasPass(p, PassId::ao_sample_output));
  s.blur_radius = 0;
  s.resolution_divisor = 2;
  ASSERT_TRUE(sao::plan(s, camera720(), {}, p).ok());
  EXPECT_TRUE(hasPass(p, PassId::ao_sample) && hasPass(p, PassId::upsample));
  EXPECT_FALSE(hasPass(p, PassId::ao_sample_output) || hasPass(p, PassId::blur) || hasPass(p, PassId::output));
  EXPECT_EQ(p.image(ResourceId::ao_low), nullptr);
  EXPECT_EQ(p.resolve(p.passes.back(), ResourceId::ao_low), ResourceId::ao_raw);
}

TEST(Plan, GuardBandSizesOnlyTheDepthSideImages) {
  auto cam = camera720();
  sao::Plan plain, guarded;
  ASSERT_TRUE(sao::plan(sao::test::untunedDefaults(), cam, {}, plain).ok());
  cam.guardBand = 64;
  ASSERT_TRUE(sao::plan(sao::test::untunedDefaults(), cam, {}, guarded).ok());
  EXPECT_EQ(guarded.inputExtent, (sao::Extent{1280 + 128, 720 + 128}));
  EXPECT_EQ(guarded.image(ResourceId::csz)->extent, guarded.inputExtent);
  EXPECT_EQ(guarded.image(ResourceId::ao_raw)->extent, (sao::Extent{1280, 720}));
  EXPECT_EQ(plain.image(ResourceId::csz)->extent, (sao::Extent{1280, 720}));
  EXPECT_GT(guarded.totalBytes, plain.totalBytes);
}

TEST(Plan, UserOutputIsNotAllocated) {
  sao::PlanInputs in;
  in.userOutput = true;
  sao::Plan p;
  ASSERT_TRUE(sao::plan(sao::test::untunedDefaults(), camera720(), in, p).ok());
  EXPECT_EQ(p.image(ResourceId::ao), nullptr);
}

TEST(Plan, RejectsBadExtentsAndIsDeterministic) {
  auto cam = camera720();
  cam.guardBand = 8000;
  sao::Plan p;
  EXPECT_EQ(sao::plan(sao::test::untunedDefaults(), cam, {}, p).code, sao::StatusCode::InvalidExtent);
  sao::Plan a, b;
  ASSERT_TRUE(sao::plan(sao::test::untunedDefaults(), camera720(), {}, a).ok());
  ASSERT_TRUE(sao::plan(sao::test::untunedDefaults(), camera720(), {}, b).ok());
  EXPECT_EQ(a.describe(), b.describe());
  EXPECT_EQ(a.totalBytes, b.totalBytes);
}

// cameraKeepsPlan: jitter and a mirrored stereo eye keep the plan (and plan() agrees), a new size,
// guard band or csz level count does not (an orthographic camera here needs fewer levels), nor an
// invalid camera. tests/core/frame_test.cpp has the rule's messages and the projection kind.
TEST(Plan, CameraKeepsPlanExactlyWhenThePlanIsTheSame) {
  const sao::Settings s = sao::test::untunedDefaults();
  const sao::Camera base = sao::perspectiveCamera(std::numbers::pi / 3.0, 320, 180, 0.1, 100, sao::ClipDepth::ZeroToOne, false);
  auto shifted = [&](double x, double y) {
    sao::Camera c = base;
    c.projection[8] += x;
    c.projection[9] += y;
    return c;
  };
  auto samePlan = [&](const sao::Camera& c) {
    sao::Plan a, b;
    if (!sao::plan(s, base, {}, a).ok() || !sao::plan(s, c, {}, b).ok()) return false;
    return a.describe() == b.describe();
  };
  for (const sao::Camera& c : {shifted(0.001, -0.002), shifted(0.04, 0), shifted(-0.04, 0)}) {
    EXPECT_TRUE(sao::cameraKeepsPlan(s, base, c));
    EXPECT_TRUE(samePlan(c));
  }
  sao::Camera wider = base;
  wider.width = 321;
  sao::Camera guarded = base;
  guarded.guardBand = 4;
  sao::Camera nearer = sao::perspectiveCamera(std::numbers::pi / 3.0, 320, 180, 0.01, 100, sao::ClipDepth::ZeroToOne, false);
  sao::Camera ortho = sao::orthographicCamera(2.0, 320, 180, 0.1, 100, sao::ClipDepth::ZeroToOne, false);
  sao::Camera broken = base;
  broken.projection[0] = NAN;
  for (const sao::Camera& c : {wider, guarded, ortho, broken}) EXPECT_FALSE(sao::cameraKeepsPlan(s, base, c));
  EXPECT_FALSE(samePlan(ortho));
  // A nearer near plane projects the radius larger: more csz levels, unless the chain is capped.
  EXPECT_EQ(sao::cameraKeepsPlan(s, base, nearer), samePlan(nearer));
  sao::Settings noHierarchy = s;
  noHierarchy.use_z_hierarchy = false;
  EXPECT_TRUE(sao::cameraKeepsPlan(noHierarchy, base, nearer)) << "one level either way";
}

}  // namespace
