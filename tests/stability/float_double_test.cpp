// The float path's own error: the CPU reference in float (what a GPU computes) against the same
// formulas in double, on the default built-in scene ("sponza-like", view 0 "nave", as sao-render
// builds it: reversed-Z D32F, [0, 1] clip, infinite far, depth by ray casting), at a reduced
// 320x180. The GPU backends run the same case and are compared with the double reference too.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "sao/raytrace/raytrace.h"
#include "sao/scenes/scene.h"
#include "stability_support.h"

namespace sao::stability {
namespace {

struct Diff {
  double worst = 0, mean = 0, p999 = 0;
  std::size_t over255 = 0, n = 0;
  std::uint32_t worstX = 0, worstY = 0;
};

Diff compare(const FloatImage& a, const FloatImage& b, std::uint32_t channel = 0) {
  Diff d;
  std::vector<double> all;
  for (std::uint32_t y = 0; y < a.extent.height; ++y)
    for (std::uint32_t x = 0; x < a.extent.width; ++x) {
      const double e = std::fabs(double(a.at(x, y, channel)) - double(b.at(x, y, channel)));
      all.push_back(e);
      d.mean += e;
      d.over255 += e > 1.0 / 255;
      if (e > d.worst) d.worst = e, d.worstX = x, d.worstY = y;
    }
  d.n = all.size();
  d.mean /= double(d.n);
  std::sort(all.begin(), all.end());
  d.p999 = all[std::min(all.size() - 1, std::size_t(0.999 * double(all.size())))];
  return d;
}

std::string text(const Diff& d) {
  return fmt("worst %.3g at (%u, %u), mean %.2g, 99.9th percentile %.3g, %zu of %zu pixels > 1/255", d.worst, d.worstX,
             d.worstY, d.mean, d.p999, d.over255, d.n);
}

TEST(FloatVsDouble, DefaultSceneWorstAODifference) {
  scenes::Scene scene;
  ASSERT_TRUE(scenes::makeBuiltinScene(scenes::kDefaultScene, scene).ok());
  const scenes::View& view = scene.views.front();
  const Camera cam = scenes::makeCamera(view, 320, 180, INFINITY, ClipDepth::ZeroToOne, true, 0);
  std::unique_ptr<raytrace::RayScene> rays;
  ASSERT_TRUE(raytrace::RayScene::create(scene.mesh, rays).ok());
  raytrace::Primary primary;
  ASSERT_TRUE(raytrace::castPrimary(*rays, view, cam, DepthFormat::D32F, primary).ok());
  std::vector<bool> sky(std::size_t(cam.width) * cam.height);
  for (std::uint32_t y = 0; y < cam.height; ++y)
    for (std::uint32_t x = 0; x < cam.width; ++x) sky[std::size_t(y) * cam.width + x] = primary.position.at(x, y, 3) == 0.0f;
  CaseOptions o;
  o.skyMask = &sky;
  // rg32f intermediates: the float path's arithmetic against double's (binary16 storage would add
  // its own 2^-12 to ao_raw's A; HalfIntermediates and WorldScale measure that).
  Settings settings = fullResolution();
  settings.half_intermediates = false;
  const CaseRuns runs = runCase("sponza-like 320x180, default settings, rg32f intermediates", settings, cam,
                                {&primary.depth, nullptr, nullptr}, o);
  const BackendRun* dbl = runs.find("cpu-double");
  const BackendRun* flt = runs.find("cpu");
  ASSERT_TRUE(dbl && flt);
  const Diff raw = compare(flt->out.aoRaw, dbl->out.aoRaw);
  const Diff fin = compare(flt->out.ao, dbl->out.ao);
  // The float path's error: rounding in eq. 2-10 (a few ulps of A), tap addresses int(h·u) that
  // flip by one pixel where h·u is within an ulp of an integer (moving one tap term), and the
  // binary16 output (half a binary16 ulp, <= 2^-12 below 1). Bound: 1/255 on every pixel.
  EXPECT_LE(fin.worst, 1.0 / 255) << text(fin);
  report("float vs double CPU reference, default scene sponza-like (view 'nave', 320x180, reversed-Z D32F, default settings with rg32f intermediates)",
         "final AO within 1/255 on every pixel", "final AO: " + text(fin) + "; before the blur (ao_raw): " + text(raw));
  for (const char* gpu : {"gl", "vulkan"})
    if (const BackendRun* g = runs.find(gpu)) {
      const Diff dg = compare(g->out.ao, dbl->out.ao), df = compare(g->out.ao, flt->out.ao);
      EXPECT_LE(dg.worst, 1.0 / 255) << gpu << ": " << text(dg);
      report(fmt("%s vs the CPU references on the default scene (320x180)", gpu), "within 1/255 of cpu-double",
             "vs cpu-double: " + text(dg) + "; vs cpu: " + text(df));
    }
}

}  // namespace
}  // namespace sao::stability
