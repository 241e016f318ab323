// The CPU reference compiled unchanged against the extended effect: it has no kernel for the new
// pass and says so, naming it (docs/adding-a-pass.md, "The CPU oracle": the one edit outside
// effect/ that a new pass needs is its kernel in backends/cpu).
#include <gtest/gtest.h>

#include "sao/cpu/reference.h"
#include "walkthrough_case.h"

namespace sao::walkthrough {
namespace {

TEST(ExtendedEffect, CpuReferenceNamesThePassItHasNoKernelFor) {
  const DepthImage depth = caseDepth();
  cpu::Inputs inputs;
  inputs.depth = &depth;
  cpu::Result result;
  const Status st = cpu::run(cases()[0].settings, caseCamera(), inputs, {cpu::Precision::Float, 2}, result);
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_EQ(st.message, "the plan holds pass 'ao_halve', which the CPU reference does not implement");
  EXPECT_TRUE(result.ao.data.empty()) << "a refused run leaves the result default-constructed";
}

}  // namespace
}  // namespace sao::walkthrough
