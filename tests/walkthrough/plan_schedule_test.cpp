// The extended effect (extra_pass.glsl) through core, compiled unchanged against its generated
// header: the generated tables, plan() and makeSchedule() hold the new image and pass with no
// edit outside effect/.
#include <gtest/gtest.h>

#include <cstdio>

#include "sao/plan.h"
#include "sao/schedule.h"
#include "walkthrough_case.h"

namespace sao::walkthrough {
namespace {

const PlannedPass* findPass(const Plan& plan, gen::PassId id) {
  for (const PlannedPass& p : plan.passes)
    if (p.pass == id) return &p;
  return nullptr;
}

TEST(ExtendedEffect, GeneratedTablesHoldTheNewImageAndPass) {
  const gen::ResourceInfo& half = gen::kResources[static_cast<std::size_t>(gen::ResourceId::ao_half)];
  EXPECT_EQ(half.name, "ao_half");
  EXPECT_EQ(half.kind, gen::ResourceKind::Image);
  EXPECT_EQ(half.format, gen::Format::R32F);
  EXPECT_FALSE(half.fullMipChain);
  EXPECT_FALSE(half.inputExtent) << "an image has the AO extent unless it says extent=input";

  ASSERT_GE(gen::passes().size(), 2u);
  const gen::PassInfo& last = gen::passes().back();
  EXPECT_EQ(last.name, "ao_halve") << "passes run in declaration order; the new one is declared last";
  EXPECT_EQ(gen::passes()[gen::passes().size() - 2].name, "upsample") << "sao.glsl's last pass";
  const gen::PassInfo& info = gen::pass(gen::PassId::ao_halve);
  EXPECT_EQ(info.localX, 8u);
  EXPECT_EQ(info.localY, 8u);
  ASSERT_EQ(info.reads.size(), 2u);
  EXPECT_EQ(info.reads[0], gen::ResourceId::ao_low);
  EXPECT_EQ(info.reads[1], gen::ResourceId::ao_scale);
  ASSERT_EQ(info.writes.size(), 1u);
  EXPECT_EQ(info.writes[0], gen::ResourceId::ao_half);
  ASSERT_EQ(info.variants.size(), 1u) << "the pass lists the new input's variant only";
  EXPECT_EQ(info.variants[0], gen::VariantId::AO_SCALED);
  EXPECT_EQ(info.compiled.size(), 2u) << "without and with ao_scale";

  // The new input (section 6): an input of the generated InputSet every API's Inputs derives from.
  const gen::ResourceInfo& scale = gen::kResources[static_cast<std::size_t>(gen::ResourceId::ao_scale)];
  EXPECT_EQ(scale.kind, gen::ResourceKind::Input);
  ASSERT_EQ(scale.formats.size(), 1u);
  EXPECT_EQ(scale.formats[0], gen::Format::R32F);
  EXPECT_EQ(gen::kInputIds.back(), gen::ResourceId::ao_scale);
  gen::InputSet<int> set;
  set[gen::ResourceId::ao_scale] = 7;
  EXPECT_EQ(set.ao_scale, 7);
  const gen::VariantInfo& v = gen::kVariants[static_cast<std::size_t>(gen::VariantId::AO_SCALED)];
  EXPECT_EQ(v.select, gen::VariantSelect::Input);
  EXPECT_EQ(static_cast<gen::ResourceId>(v.selectIndex), gen::ResourceId::ao_scale);
}

TEST(ExtendedEffect, PlanRunsTheNewPassLastAndAllocatesItsImage) {
  const Settings settings = cases()[0].settings;
  ASSERT_GT(settings.blur_radius, 0);
  Plan plan;
  const Status st = sao::plan(settings, caseCamera(), PlanInputs{}, plan);
  ASSERT_TRUE(st.ok()) << st.message;
  std::printf("%s", plan.describe().c_str());
  ASSERT_GE(plan.passes.size(), 2u);
  EXPECT_EQ(plan.passes.back().pass, gen::PassId::ao_halve);
  EXPECT_EQ(plan.passes[plan.passes.size() - 2].pass, gen::PassId::output) << "full resolution";
  EXPECT_TRUE(plan.passes.back().aliases.empty()) << "the blur runs, so ao_low serves itself";

  const PlannedImage* half = plan.image(gen::ResourceId::ao_half);
  ASSERT_NE(half, nullptr) << "the plan allocates every effect-owned image a planned pass touches";
  EXPECT_EQ(half->format, gen::Format::R32F);
  EXPECT_EQ(half->extent, (Extent{kWidth, kHeight}));
  EXPECT_EQ(half->mipLevels, 1u);
  EXPECT_EQ(half->bytes, std::uint64_t(kWidth) * kHeight * 4);
}

TEST(ExtendedEffect, PlanAppliesTheNewPassAliasWithoutBlur) {
  const Settings settings = cases()[1].settings;
  ASSERT_EQ(settings.blur_radius, 0);
  Plan plan;
  const Status st = sao::plan(settings, caseCamera(), PlanInputs{}, plan);
  ASSERT_TRUE(st.ok()) << st.message;
  EXPECT_EQ(findPass(plan, gen::PassId::blur), nullptr) << "skip_when=blur_radius==0";
  EXPECT_EQ(plan.image(gen::ResourceId::ao_low), nullptr);
  const PlannedPass* halve = findPass(plan, gen::PassId::ao_halve);
  ASSERT_NE(halve, nullptr);
  EXPECT_EQ(plan.resolve(*halve, gen::ResourceId::ao_low), gen::ResourceId::ao_raw)
      << "alias_when=blur_radius==0:ao_low=ao_raw";
  EXPECT_NE(plan.image(gen::ResourceId::ao_half), nullptr);
  // Without temporal accumulation ao_sample_output writes the output and no (A, key) image exists.
  Settings direct = settings;
  direct.temporal = false;
  ASSERT_TRUE(sao::plan(direct, caseCamera(), PlanInputs{}, plan).ok());
  EXPECT_NE(findPass(plan, gen::PassId::ao_sample_output), nullptr) << "derived direct_output";
  EXPECT_EQ(findPass(plan, gen::PassId::ao_halve), nullptr) << "skip_when=direct_output==true";
  EXPECT_EQ(plan.image(gen::ResourceId::ao_raw), nullptr);
}

TEST(ExtendedEffect, ScheduleDispatchesTheNewPassWithResolvedBindings) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    Plan plan;
    const Status st = sao::plan(c.settings, caseCamera(), PlanInputs{}, plan);
    ASSERT_TRUE(st.ok()) << st.message;
    const Schedule schedule = makeSchedule(plan);
    std::printf("%s:\n%s", c.name, schedule.describe().c_str());
    ASSERT_FALSE(schedule.dispatches.empty());
    const ScheduledDispatch& d = schedule.dispatches.back();
    EXPECT_EQ(d.pass, gen::PassId::ao_halve);
    EXPECT_EQ(d.passIndex, plan.passes.size() - 1);
    EXPECT_EQ(d.level, 0u);
    // One 8x8 group per 8x8 block of the first written image, ao_half (the AO extent).
    EXPECT_EQ(d.groupsX, (kWidth + 7) / 8);
    EXPECT_EQ(d.groupsY, (kHeight + 7) / 8);

    const auto bindings = schedule.bindingsOf(d);
    ASSERT_EQ(bindings.size(), 2u);
    const gen::ResourceId source = c.settings.blur_radius == 0 ? gen::ResourceId::ao_raw : gen::ResourceId::ao_low;
    EXPECT_EQ(bindings[0].binding, 1u) << "binding 0 is the parameter block, then reads, then writes";
    EXPECT_EQ(bindings[0].resource, source);
    EXPECT_FALSE(bindings[0].write);
    EXPECT_EQ(bindings[0].levelCount, 1u);
    EXPECT_EQ(bindings[1].binding, 2u);
    EXPECT_EQ(bindings[1].resource, gen::ResourceId::ao_half);
    EXPECT_TRUE(bindings[1].write);
    EXPECT_EQ(bindings[1].baseLevel, 0u);

    // The output pass already read `source` after its last write (that read carried the barrier), and
    // ao_half is written once: nothing to wait for inside the frame.
    EXPECT_EQ(d.hazardCount, 0u);
    // Across frames: this frame's store to ao_half is ordered after the previous frame's.
    bool entry = false;
    for (const Hazard& h : schedule.entryHazards())
      entry |= h.resource == gen::ResourceId::ao_half && h.kind == HazardKind::WriteAfterWrite;
    EXPECT_TRUE(entry);
    // The caller reads only the output at frame exit; ao_half is an intermediate.
    for (const Hazard& h : schedule.exitHazards()) EXPECT_NE(h.resource, gen::ResourceId::ao_half);
  }
}

}  // namespace
}  // namespace sao::walkthrough
