// The effect's inert rules (`#pragma sao inert` in effect/sao.glsl, gen::kInertRules) and the rule
// function every program applies to them (sao::inertRule, sao::describeInert): each declared
// relation holds in the metadata, and is true of the effect itself: while a rule holds, the
// setting's smallest and largest values give the same output bit for bit on the CPU reference
// (which computes every pass as the shaders do); where it does not, they give another output.
#include <string>
#include <utility>
#include <vector>

#include "sao/settings.h"
#include "test_support.h"

namespace sao::test {
namespace {

std::string nameOf(SettingId id) { return std::string(gen::kSettings[static_cast<std::size_t>(id)].name); }

// The setting's rule under `s`, by name ("" when it has an effect).
std::string inertWhen(const Settings& s, SettingId id) {
  const gen::InertRule* rule = inertRule(s, id);
  return rule ? std::string(rule->whenText) : "";
}

TEST(InertRules, DeclaredRelations) {
  // Every rule the effect declares, in words, as the CLI's message and the viewer's tooltip give it.
  std::vector<std::string> rules;
  for (const auto& r : gen::kInertRules) rules.push_back(nameOf(r.setting) + " while " + std::string(r.whenText));
  EXPECT_EQ(rules, (std::vector<std::string>{
                       "fade_start while fade_end = 0",
                       "temporal_hysteresis while temporal = false",
                       "temporal_depth_tolerance while temporal = false",
                       "blur_stride while blur_radius = 0",
                       "blur_edge_sharpness while blur_radius = 0",
                       "blur_edge_relative while blur_radius = 0",
                       "blur_edge_slope while blur_radius = 0",
                       "mip_switch_log2 while use_z_hierarchy = false",
                       "half_intermediates while blur_radius = 0, resolution_divisor = 1 and temporal = false",
                       "bias while estimator = 1",
                       "epsilon while estimator = 1",
                       "spiral_turns while estimator = 1",
                       "thickness while estimator = 0",
                       "depth_tolerance while estimator = 0",
                       "slices while estimator = 0",
                       "thickness_model while estimator = 0",
                   }));
}

TEST(InertRules, RuleFunctionFollowsTheFinalSettings) {
  Settings s;  // the defaults: no fade, no temporal accumulation, a 3-tap blur at half resolution
  EXPECT_EQ(inertWhen(s, SettingId::fade_start), "fade_end = 0");
  EXPECT_EQ(inertWhen(s, SettingId::temporal_hysteresis), "temporal = false");
  EXPECT_EQ(inertWhen(s, SettingId::temporal_depth_tolerance), "temporal = false");
  for (SettingId id : {SettingId::blur_stride, SettingId::blur_edge_sharpness, SettingId::blur_edge_relative,
                       SettingId::blur_edge_slope, SettingId::mip_switch_log2,
                       SettingId::half_intermediates, SettingId::radius, SettingId::fade_end, SettingId::temporal,
                       SettingId::blur_radius, SettingId::quad_edge_threshold, SettingId::samples})
    EXPECT_EQ(inertRule(s, id), nullptr) << nameOf(id);

  s.fade_end = 5.0f;
  s.temporal = true;
  EXPECT_EQ(inertRule(s, SettingId::fade_start), nullptr);
  EXPECT_EQ(inertRule(s, SettingId::temporal_hysteresis), nullptr);
  EXPECT_EQ(inertRule(s, SettingId::temporal_depth_tolerance), nullptr);

  s.blur_radius = 0;
  EXPECT_EQ(inertWhen(s, SettingId::blur_stride), "blur_radius = 0");
  EXPECT_EQ(inertWhen(s, SettingId::blur_edge_sharpness), "blur_radius = 0");
  EXPECT_EQ(inertWhen(s, SettingId::blur_edge_relative), "blur_radius = 0");
  EXPECT_EQ(inertWhen(s, SettingId::blur_edge_slope), "blur_radius = 0");
  s.resolution_divisor = 1;  // with temporal: ao_sample still writes (A, key) for the history
  EXPECT_EQ(inertRule(s, SettingId::half_intermediates), nullptr);
  s.temporal = false;  // nothing follows the AO: ao_sample_output writes the output itself
  EXPECT_EQ(inertWhen(s, SettingId::half_intermediates),
            "blur_radius = 0, resolution_divisor = 1 and temporal = false");
  s.resolution_divisor = 2;
  EXPECT_EQ(inertRule(s, SettingId::half_intermediates), nullptr);

  s.use_z_hierarchy = false;
  EXPECT_EQ(inertWhen(s, SettingId::mip_switch_log2), "use_z_hierarchy = false");
}

TEST(InertRules, MessageNamesTheSettingTheConditionAndTheFix) {
  Settings s;
  EXPECT_EQ(describeInert(*inertRule(s, SettingId::fade_start)),
            "fade_start has no effect while fade_end = 0 (no distance fade: sao_fade returns A unchanged and "
            "fade_start is not uploaded): also set fade_end > 0, or drop fade_start");
  EXPECT_EQ(describeInert(*inertRule(s, SettingId::temporal_hysteresis)),
            "temporal_hysteresis has no effect while temporal = false (no temporal accumulation: there is no history "
            "for it to weigh): also set temporal = true, or drop temporal_hysteresis");
  s.blur_radius = 0;
  s.resolution_divisor = 1;
  EXPECT_EQ(describeInert(*inertRule(s, SettingId::half_intermediates)),
            "half_intermediates has no effect while blur_radius = 0, resolution_divisor = 1 and temporal = false "
            "(ao_sample_output writes the output itself: there are no (A, key) intermediate images): also set "
            "blur_radius > 0, resolution_divisor > 1 or temporal = true, or drop half_intermediates");
}

// ---- The rules are true of the effect: the CPU reference computes every pass as the shaders do.

struct Scenario {
  Camera camera = testCamera(8, 1000.0, ClipDepth::NegativeOneToOne, false, 96, 54);
  DepthImage depth = renderDepth(sphereOnPlaneScene(), camera, DepthFormat::D32F);
  FloatImage ao(const Settings& s) const {
    cpu::Inputs in;
    in.depth = &depth;
    return runOrFail(s, camera, in, cpu::Precision::Float).ao;
  }
};

// The output with setting `id` at its smallest and at its largest value.
std::pair<FloatImage, FloatImage> atBothEnds(const Scenario& sc, Settings s, SettingId id) {
  const SettingInfo& info = gen::kSettings[static_cast<std::size_t>(id)];
  gen::setSettingValue(s, id, info.minValue);
  EXPECT_TRUE(validate(s).ok()) << validate(s).message;
  FloatImage low = sc.ao(s);
  gen::setSettingValue(s, id, info.maxValue);
  if (id == SettingId::fade_start && s.fade_end > 0.0f) s.fade_start = s.fade_end * 0.5f;  // below fade_end
  EXPECT_TRUE(validate(s).ok()) << validate(s).message;
  return {std::move(low), sc.ao(s)};
}

TEST(InertRules, WhileARuleHoldsTheSettingChangesNoBit) {
  const Scenario sc;
  // For each rule, settings under which it holds: the defaults, changed as little as needed.
  for (const auto& rule : gen::kInertRules) {
    SCOPED_TRACE(nameOf(rule.setting) + " while " + std::string(rule.whenText));
    Settings s;
    if (rule.when.setting == SettingId::blur_radius) s.blur_radius = 0;
    if (rule.when.setting == SettingId::use_z_hierarchy) s.use_z_hierarchy = false;
    if (rule.when.setting == SettingId::direct_output) s.blur_radius = 0, s.resolution_divisor = 1;
    if (rule.when.setting == SettingId::estimator) s.estimator = int(rule.when.value);
    ASSERT_NE(inertRule(s, rule.setting), nullptr) << "the rule does not hold under the chosen settings";
    const auto [low, high] = atBothEnds(sc, s, rule.setting);
    ASSERT_FALSE(low.data.empty());
    EXPECT_TRUE(sameBits(low, high)) << "the output depends on a setting declared to have no effect";
  }
}

TEST(InertRules, WhereNoRuleHoldsTheSettingChangesTheOutput) {
  // The counterpart (so that the test above is not vacuous): each setting matters once its rule no
  // longer holds. The temporal settings need a history of earlier frames, which one run has not;
  // tests/cpu/temporal_test.cpp measures them.
  const Scenario sc;
  Settings fade;
  fade.fade_end = 1000.0f;  // the scene lies within 10 m: fading from 0 or from 500 m differs there
  Settings blur;            // the defaults: a 3-tap blur at half resolution
  blur.blur_edge_sharpness = 1.0f;
  Settings slanted = blur;  // an edge sharp enough to cut the scenario's slanted surfaces
  slanted.blur_edge_sharpness = 100.0f;
  Settings mips;
  mips.radius = 3.0f;  // wide enough for taps to reach past level 0 at every mip_switch_log2
  Settings direct;
  direct.blur_radius = 0;
  direct.resolution_divisor = 2;  // not direct output: the upsample reads rg16f or rg32f (A, key)
  Settings visibility;  // the visibility estimator: its thickness model and slices
  visibility.estimator = 1;
  visibility.radius = 3.0f;
  const Settings alchemy;  // the defaults: the alchemy estimator's bias, epsilon and spiral
  const std::vector<std::pair<SettingId, Settings>> cases = {
      {SettingId::fade_start, fade},         {SettingId::blur_stride, blur},
      {SettingId::blur_edge_sharpness, blur}, {SettingId::blur_edge_relative, blur},
      {SettingId::blur_edge_slope, slanted},
      {SettingId::mip_switch_log2, mips},
      {SettingId::half_intermediates, direct}, {SettingId::thickness, visibility},
      {SettingId::depth_tolerance, visibility}, {SettingId::slices, visibility},
      {SettingId::thickness_model, visibility},
      {SettingId::bias, alchemy},            {SettingId::epsilon, alchemy},
      {SettingId::spiral_turns, alchemy}};
  for (const auto& [id, s] : cases) {
    SCOPED_TRACE(nameOf(id));
    ASSERT_EQ(inertRule(s, id), nullptr);
    const auto [low, high] = atBothEnds(sc, s, id);
    EXPECT_FALSE(sameBits(low, high)) << "the setting changes nothing even where no rule holds";
  }
}

}  // namespace
}  // namespace sao::test
