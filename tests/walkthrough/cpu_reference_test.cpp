// The CPU reference compiled unchanged against the extended effect runs the new pass through the
// walkthrough's CPU passes (cpu_passes.h, named by sao_generate_effect's CPU_PASSES), and sao's
// own passes alone refuse it, naming it (docs/adding-a-pass.md, section 3). This file is compiled
// with sao_cpu's floating-point options: it instantiates the same pass templates.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>

#include "cpu_passes.h"
#include "sao/cpu/reference.h"
#include "sao/schedule.h"
#include "walkthrough_case.h"

namespace sao::walkthrough {
namespace {

constexpr std::size_t kHalf = static_cast<std::size_t>(gen::ResourceId::ao_half);

TEST(ExtendedEffect, CpuReferenceRunsTheNewPassIntoItsImage) {
  const DepthImage depth = caseDepth();
  cpu::Inputs inputs;
  inputs.depth = &depth;
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    for (cpu::Precision precision : {cpu::Precision::Float, cpu::Precision::Double}) {
      SCOPED_TRACE(cpu::toString(precision));
      cpu::Result r;
      const Status st = cpu::run(c.settings, caseCamera(), inputs, {precision, 2, true}, r);
      ASSERT_TRUE(st.ok()) << st.message;
      ASSERT_FALSE(r.timings.passes.empty());
      EXPECT_EQ(r.timings.passes.back().pass, "ao_halve");
      ASSERT_EQ(r.images[kHalf].size(), 1u);
      const FloatImage& half = r.images[kHalf][0];
      EXPECT_EQ(half.extent, r.ao.extent);
      ASSERT_EQ(half.channels, 1u);
      ASSERT_EQ(half.data.size(), r.ao.data.size());
      // ao_halve reads the output pass's input, whose A the output copies at full resolution: exactly
      // ao * 0.5 in both precisions.
      std::size_t differ = 0, occluded = 0;
      for (std::size_t i = 0; i < half.data.size(); ++i) {
        differ += std::bit_cast<std::uint32_t>(half.data[i]) != std::bit_cast<std::uint32_t>(r.ao.data[i] * 0.5f);
        occluded += r.ao.data[i] < 0.9f;
      }
      EXPECT_EQ(differ, 0u);
      EXPECT_GT(occluded, r.ao.data.size() / 50) << "the scene should darken some pixels";
      for (std::size_t k = 0; k < r.images.size(); ++k) {
        // ao_half is the new pass's; ao_low (the blur's image, read by output and by ao_halve) is
        // there when the blur runs, history with temporal (the second case); the rest have named
        // Result fields or are not planned.
        if (k == kHalf || k == static_cast<std::size_t>(gen::ResourceId::ao_low) ||
            k == static_cast<std::size_t>(gen::ResourceId::history))
          continue;
        EXPECT_TRUE(r.images[k].empty()) << gen::kResources[k].name << " has a named Result field";
      }
    }
  }
}

TEST(ExtendedEffect, SaoPassesAloneNameThePassTheyHaveNoKernelFor) {
  const DepthImage depth = caseDepth();
  cpu::Inputs inputs;
  inputs.depth = &depth;
  cpu::Result r;
  const Status ran = cpu::run(cases()[0].settings, caseCamera(), inputs, {cpu::Precision::Float, 2}, r);
  ASSERT_TRUE(ran.ok()) << ran.message;
  const Schedule schedule = makeSchedule(r.plan);
  ASSERT_FALSE(schedule.dispatches.empty());
  const ScheduledDispatch& last = schedule.dispatches.back();
  ASSERT_EQ(last.pass, gen::PassId::ao_halve);
  cpu::PassContext<float> ctx(inputs, r.plan, r.params, 1);
  const Status st = cpu::runSaoPass(ctx, last, schedule.bindingsOf(last));
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_EQ(st.message, "the plan holds pass 'ao_halve', which the CPU reference does not implement");
}

}  // namespace
}  // namespace sao::walkthrough
