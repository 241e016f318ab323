// The prepass output feeds the effect exactly like the ray-cast depth does: the CPU reference (float
// mode, the GPU's arithmetic) on the rasterised depth gives the AO it gives on the ray-cast depth,
// and depth2 / normals select the TWO_LAYER and NORMALS_SUPPLIED variants.
#include <cmath>
#include <cstdio>

#include "prepass_support.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"

namespace sao::prepasstest {
namespace {

class EffectInput : public PrepassTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(EffectInput, CpuReferenceOnRasterisedDepth) {
  prepass::Prepass& prepass = backend(GetParam());
  const LoadedScene& ls = loadScene("sponza-like");
  const scenes::View& view = ls.scene.views.front();
  const Camera camera = scenes::makeCamera(view, 160, 90, INFINITY, ClipDepth::ZeroToOne, true, 16);
  prepass::PrepassOptions o;
  o.format = DepthFormat::D32F;
  o.secondLayer = true;
  prepass::PrepassResult raster;
  ASSERT_TRUE(prepass.render(ls.scene.mesh, view, camera, o, raster));
  raytrace::Primary ray;
  ASSERT_TRUE(raytrace::castPrimary(*ls.rays, view, camera, DepthFormat::D32F, ray));

  const Settings settings = presetSettings(Preset::Medium);
  cpu::Options co;
  co.precision = cpu::Precision::Float;
  cpu::Inputs fromRay, fromRaster;
  fromRay.depth = &ray.depth;
  fromRaster.depth = &raster.depth;
  cpu::Result a, b;
  ASSERT_TRUE(cpu::run(settings, camera, fromRay, co, a));
  ASSERT_TRUE(cpu::run(settings, camera, fromRaster, co, b));
  double worst = 0, sum = 0;
  std::size_t over = 0;
  for (std::size_t i = 0; i < a.ao.data.size(); ++i) {
    const double d = std::abs(double(a.ao.data[i]) - double(b.ao.data[i]));
    worst = std::max(worst, d);
    sum += d;
    over += d > 0.01;
  }
  const double mean = sum / double(a.ao.data.size());
  std::printf("%s: AO from rasterised vs ray-cast depth: mean |dA| %.2e, worst %.2e, %zu of %zu pixels off by > 0.01\n",
              GetParam().c_str(), mean, worst, over, a.ao.data.size());
  // Depth a few float ulps apart: the same AO except where a tap or a normal sits on a decision
  // boundary (forward/backward difference at a crease, the 2x2 and blur depth thresholds).
  EXPECT_LT(mean, 1e-3);
  EXPECT_LT(double(over), 0.002 * double(a.ao.data.size()));
  EXPECT_LT(worst, 0.25);

  cpu::Inputs full = fromRaster;
  full.depth2 = &raster.depth2;
  full.normals = &raster.normal;
  cpu::Result c;
  const Status s = cpu::run(settings, camera, full, co, c);
  ASSERT_TRUE(s) << s.message;
  EXPECT_EQ(c.csz2.size(), c.csz.size());
  EXPECT_FALSE(c.csz2.empty());
}

GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(EffectInput);  // a build without GL and Vulkan
INSTANTIATE_TEST_SUITE_P(Backends, EffectInput, ::testing::ValuesIn(backendNames()),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace sao::prepasstest
