// The near / far grid through the whole effect: finite on every convention and depth format.
#include <string>

#include "extremes_support.h"

namespace sao::stability {
namespace {

TEST(Cameras, NearFarGridThroughTheEffectIsFinite) {
  const double nears[] = {1e-4, 1e-2, 1.0, 10.0};
  const double fars[] = {10.0, 1e4, kInf};
  std::size_t runs = 0;
  for (double n : nears)
    for (double f : fars) {
      if (!(f > n)) continue;
      // The sphere-on-plane scene scaled so that it starts 3 near planes away.
      const test::Scene scene = scaledScene(test::sphereOnPlaneScene(), std::max(1.0, 3.0 * n));
      for (const Conv& cv : kConvs)
        for (DepthFormat fm : {DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F}) {
          const Camera cam = camera(64, 48, n, f, cv.clip, cv.reversed, 4);
          DepthModel m;
          // Finite far/near >= 1e6 runs as it is (finding F1, fixed).
          ASSERT_TRUE(analyze(cam, m).ok()) << describe(cam);
          const SceneRun r = runScene(fmt("near/far grid %s %s", describe(cam).c_str(), toString(fm)), fullResolution(), cam, scene, fm);
          runs += r.runs.runs.size();
        }
    }
  report("near {1e-4,1e-2,1,10} x far {10,1e4,inf} x 6 conventions x D16/D24/D32F through the effect (sphere-on-plane)",
         "no NaN/Inf; A in [0,1]; sky = 1", fmt("%zu runs pass", runs));
}

}  // namespace
}  // namespace sao::stability
