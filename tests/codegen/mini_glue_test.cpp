// The generated C++ glue of the small test effect compiles (its static_asserts hold) and its
// tables say what the annotated source declares.
#include <gtest/gtest.h>

#include "mini_effect.h"

namespace gen = sao::gen;

TEST(MiniGlue, SettingsDefaultsAndMetadata) {
  const gen::Settings s;
  EXPECT_FLOAT_EQ(s.strength, 0.5f);
  EXPECT_EQ(s.taps, 4);
  EXPECT_TRUE(s.enabled);
  ASSERT_EQ(gen::kSettings.size(), 3u);
  EXPECT_EQ(gen::kSettings[0].name, "strength");
  EXPECT_EQ(gen::kSettings[0].unit, "m");
  EXPECT_EQ(gen::kSettings[0].minValue, 0.0);
  EXPECT_EQ(gen::kSettings[0].maxValue, 2.0);
  EXPECT_EQ(gen::kSettings[1].type, gen::SettingType::Int);
  for (size_t i = 0; i < gen::kSettings.size(); ++i)
    EXPECT_EQ(gen::settingValue(s, static_cast<gen::SettingId>(i)), gen::kSettings[i].defaultValue);
}

TEST(MiniGlue, SettingAccessorsRoundTrip) {
  gen::Settings s;
  gen::setSettingValue(s, gen::SettingId::taps, 9);
  gen::setSettingValue(s, gen::SettingId::enabled, 0);
  gen::setSettingValue(s, gen::SettingId::strength, 1.25);
  EXPECT_EQ(s.taps, 9);
  EXPECT_FALSE(s.enabled);
  EXPECT_FLOAT_EQ(s.strength, 1.25f);
}

TEST(MiniGlue, ParamBlockLayoutIsStd140) {
  EXPECT_EQ(offsetof(gen::MiniParams, gain), 16u);
  EXPECT_EQ(offsetof(gen::MiniParams, pair), 24u);  // vec2 aligns to 8 after a float
  EXPECT_EQ(offsetof(gen::MiniParams, table), 112u);
  EXPECT_EQ(sizeof(gen::MiniParams), 144u);
}

TEST(MiniGlue, PassTableAndVariantLookup) {
  ASSERT_EQ(gen::passes().size(), 3u);
  const auto& first = gen::pass(gen::PassId::first);
  EXPECT_EQ(first.entry, "mini_first");
  EXPECT_EQ(first.localX, 8u);
  const auto& second = gen::pass(gen::PassId::second);
  EXPECT_EQ(second.localX, 16u);
  EXPECT_EQ(second.localY, 4u);

  // FANCY=0, EXTRA=1: the extra input is bound after src, then the written chain.
  const auto* pv = gen::findPassVariant(gen::PassId::first, {0, 1});
  ASSERT_NE(pv, nullptr);
  ASSERT_EQ(pv->bindings.size(), 3u);
  EXPECT_EQ(pv->bindings[0].binding, 1u);
  EXPECT_EQ(pv->bindings[0].resource, gen::ResourceId::src);
  EXPECT_EQ(pv->bindings[1].resource, gen::ResourceId::extra);
  EXPECT_EQ(pv->bindings[2].resource, gen::ResourceId::mid);
  EXPECT_TRUE(pv->bindings[2].write);
  // EXTRA=0 drops the extra input's binding.
  const auto* plain = gen::findPassVariant(gen::PassId::first, {0, 0});
  ASSERT_NE(plain, nullptr);
  EXPECT_EQ(plain->bindings.size(), 2u);

  EXPECT_EQ(gen::findPassVariant(gen::PassId::second, {1, 1}), nullptr) << "excluded combination";
  EXPECT_EQ(gen::exclusionReason({1, 1}), "not both");
  EXPECT_TRUE(gen::exclusionReason({1, 0}).empty());
}

TEST(MiniGlue, VariantsNameWhatSelectsThem) {
  const auto& fancy = gen::kVariants[static_cast<std::size_t>(gen::VariantId::FANCY)];
  EXPECT_EQ(fancy.select, gen::VariantSelect::Setting);
  EXPECT_EQ(fancy.selectIndex, static_cast<std::uint32_t>(gen::SettingId::enabled));
  const auto& extra = gen::kVariants[static_cast<std::size_t>(gen::VariantId::EXTRA)];
  EXPECT_EQ(extra.select, gen::VariantSelect::Input);
  EXPECT_EQ(extra.selectIndex, static_cast<std::uint32_t>(gen::ResourceId::extra));
}

TEST(MiniGlue, SkipAndAliasRulesHoldOnTheirSetting) {
  const auto& first = gen::pass(gen::PassId::first);
  const auto& smoothing = gen::pass(gen::PassId::smoothing);
  const auto& second = gen::pass(gen::PassId::second);
  gen::Settings s;
  s.taps = 1;
  EXPECT_FALSE(gen::holds(first.skipWhen, s)) << "no rule: never holds";
  EXPECT_TRUE(gen::holds(smoothing.skipWhen, s));
  EXPECT_TRUE(gen::holds(second.aliasWhen, s));
  ASSERT_EQ(second.aliases.size(), 1u);
  EXPECT_EQ(second.aliases[0].declared, gen::ResourceId::smooth);
  EXPECT_EQ(second.aliases[0].serving, gen::ResourceId::mid);
  s.taps = 2;
  EXPECT_FALSE(gen::holds(smoothing.skipWhen, s));
  EXPECT_FALSE(gen::holds(second.aliasWhen, s));
  EXPECT_TRUE(first.aliases.empty());
}

TEST(MiniGlue, PresetsListOnlyTheirValues) {
  ASSERT_EQ(gen::kPresets.size(), 2u);
  const auto& fast = gen::kPresets[0];
  EXPECT_EQ(fast.preset, gen::Preset::Fast);
  EXPECT_EQ(fast.name, "fast");
  EXPECT_EQ(fast.summary, "One tap, plain path");
  gen::Settings s;
  for (const auto& v : fast.values) gen::setSettingValue(s, v.setting, v.value);
  EXPECT_EQ(s.taps, 1);
  EXPECT_FALSE(s.enabled);
  EXPECT_FLOAT_EQ(s.strength, 0.5f) << "unlisted: the default";
  EXPECT_EQ(gen::kPresets[1].preset, gen::Preset::Best);
  EXPECT_EQ(gen::kPresets[1].values.size(), 2u);
}

TEST(MiniGlue, EmbeddedBlobsArePresent) {
  for (const auto& p : gen::passes())
    for (const auto& c : p.compiled) {
      EXPECT_EQ(gen::glslSource(c.glslBlob).substr(0, 12), "#version 430");
      const auto spv = gen::spirvModule(c.spirvBlob);
      ASSERT_GT(spv.size(), 5u);
      EXPECT_EQ(spv[0], 0x07230203u);
    }
  EXPECT_TRUE(gen::glslSource(999).empty());
}

TEST(MiniGlue, RefusalRuleHoldsOnItsSetting) {
  // `#pragma sao refuse enabled when=taps>=16`: a rule of the inert rules' shape in its own list.
  ASSERT_EQ(gen::kRefusalRules.size(), 1u);
  const auto& rule = gen::kRefusalRules[0];
  EXPECT_EQ(rule.setting, gen::SettingId::enabled);
  EXPECT_EQ(rule.whenText, "taps >= 16");
  EXPECT_EQ(rule.fixText, "taps < 16");
  EXPECT_EQ(rule.reason, "the plain path takes at most 15 taps");
  gen::Settings s;
  EXPECT_FALSE(gen::holds(rule.when, s));
  s.taps = 16;
  EXPECT_TRUE(gen::holds(rule.when, s));
}

TEST(MiniGlue, InertRulesHoldOnTheirSetting) {
  // `#pragma sao inert strength when=enabled==false` and `taps when=strength==0` (a float setting).
  ASSERT_EQ(gen::kInertRules.size(), 2u);
  const auto& strength = gen::kInertRules[0];
  const auto& taps = gen::kInertRules[1];
  EXPECT_EQ(strength.setting, gen::SettingId::strength);
  EXPECT_EQ(strength.whenText, "enabled = false");
  EXPECT_EQ(strength.fixText, "enabled = true");
  EXPECT_EQ(strength.reason, "the plain path has no strength");
  EXPECT_EQ(taps.setting, gen::SettingId::taps);
  EXPECT_EQ(taps.whenText, "strength = 0");
  EXPECT_EQ(taps.fixText, "strength > 0");  // 0 is the range's minimum: the only way out is up
  gen::Settings s;
  EXPECT_FALSE(gen::holds(strength.when, s));
  EXPECT_FALSE(gen::holds(taps.when, s));
  s.enabled = false;
  s.strength = 0.0f;
  EXPECT_TRUE(gen::holds(strength.when, s));
  EXPECT_TRUE(gen::holds(taps.when, s));
}

// Shared memory and push constants are read from each variant's SPIR-V: only `smoothing` declares
// them (64 floats and a uint; the block's gain pushed on Vulkan), and the generated mirror of its
// push block copies the parameter block's member of the same name.
TEST(MiniGlue, SharedMemoryAndPushConstantsComeFromTheSpirv) {
  for (const gen::PassInfo& pass : gen::passes())
    for (const gen::PassVariantInfo& v : pass.compiled) {
      const bool smoothing = pass.name == "smoothing";
      EXPECT_EQ(v.sharedBytes, smoothing ? 260u : 0u) << v.fileStem;
      EXPECT_EQ(v.pushConstantBytes, smoothing ? 4u : 0u) << v.fileStem;
    }
  EXPECT_EQ(gen::kPushConstantBytes, 4u);
  static_assert(sizeof(gen::PushConstants) == 4);
  gen::MiniParams block{};
  block.gain = 2.5f;
  EXPECT_EQ(gen::pushConstantsOf(block).gain, 2.5f);
}
