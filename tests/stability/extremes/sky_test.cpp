// Sky frames: an all-sky frame is 1 everywhere with +0.0 keys; sky next to geometry with an infinite far
// plane (and a sky checkerboard) leaves every intermediate finite.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "extremes_support.h"

namespace sao::stability {
namespace {

TEST(Sky, AllSkyFrameIsOneEverywhere) {
  std::size_t runs = 0;
  for (const Conv& cv : kConvs)
    for (bool ortho : {false, true})
      for (DepthFormat fm : {DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F, DepthFormat::LinearZ}) {
        const Camera cam = convCamera(cv, 64, 48, 4, ortho);
        CaseOptions o;
        o.dumpPasses = true;
        const SceneRun r = runScene(fmt("all sky, %s %s", describe(cam).c_str(), toString(fm)), fullResolution(), cam,
                                    test::skyScene(), fm, o);
        for (const BackendRun& b : r.runs.runs) {
          ++runs;
          EXPECT_EQ(range(b.out.ao).min, 1.0) << b.name;
          if (const FloatImage* raw = b.intermediate("ao_raw")) {
            std::size_t nonZeroKeys = 0;
            for (std::size_t i = 0; i < raw->data.size(); i += 2)
              nonZeroKeys += std::bit_cast<std::uint32_t>(raw->data[i + 1]) != 0u;
            EXPECT_EQ(nonZeroKeys, 0u) << b.name << ": sky keys must be +0.0";
          }
        }
      }
  report("all-sky frame (6 conventions x persp/ortho x D16/D24/D32F/R32F)", "A = 1 on every pixel, keys +0.0",
         fmt("A = 1 exactly in all %zu backend runs", runs));
}

TEST(Sky, SkyNextToGeometryWithInfiniteFar) {
  // A floor to the horizon and a sphere, nothing behind: half the frame is sky, and the floor
  // pixels next to the horizon hold the largest finite depths the format can store.
  test::Scene scene = test::sphereOnPlaneScene();
  scene.planes.pop_back();  // no wall
  double minGeom = 1;
  std::size_t runs = 0;
  for (const Conv& cv : kConvs) {
    if (!std::isinf(cv.far)) continue;
    for (DepthFormat fm : {DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F, DepthFormat::LinearZ}) {
      const Camera cam = convCamera(cv, 64, 48, 4);
      CaseOptions o;
      o.dumpPasses = true;
      const SceneRun r = runScene(fmt("sky next to geometry, %s %s", describe(cam).c_str(), toString(fm)), fullResolution(), cam,
                                  scene, fm, o);
      const std::vector<bool> geom = notMask(r.sky);
      for (const BackendRun& b : r.runs.runs) {
        ++runs;
        for (const auto& [name, img] : b.out.intermediates)
          EXPECT_TRUE(allFinite(img)) << b.name << ": intermediate " << name << " holds NaN or Inf";
        minGeom = std::min(minGeom, range(b.out.ao, &geom).min);
      }
    }
  }
  // The same with every other texel sky (a checkerboard): every geometry pixel borders sky.
  for (bool reversed : {false, true}) {
    const Camera cam = camera(64, 48, 0.1, kInf, ClipDepth::ZeroToOne, reversed, 4);
    DepthImage depth = renderGpuDepth(test::sphereOnPlaneScene(), cam, DepthFormat::D32F);
    std::vector<bool> sky(std::size_t(cam.width) * cam.height);
    for (std::uint32_t y = 0; y < depth.extent.height; ++y)
      for (std::uint32_t x = 0; x < depth.extent.width; ++x)
        if ((x + y) & 1) depth.texels[std::size_t(y) * depth.extent.width + x] = storeDepth(DepthFormat::D32F, reversed ? 0.0f : 1.0f);
    for (std::uint32_t y = 0; y < cam.height; ++y)
      for (std::uint32_t x = 0; x < cam.width; ++x) sky[std::size_t(y) * cam.width + x] = ((x + 4 + y + 4) & 1) != 0;
    CaseOptions o;
    o.skyMask = &sky;
    o.dumpPasses = true;
    const CaseRuns runsCb = runCase(fmt("sky checkerboard, %s", describe(cam).c_str()), fullResolution(), cam, {&depth, nullptr, nullptr}, o);
    for (const BackendRun& b : runsCb.runs) {
      ++runs;
      for (const auto& [name, img] : b.out.intermediates) EXPECT_TRUE(allFinite(img)) << b.name << " " << name;
    }
  }
  report("sky next to geometry, infinite far (4 conventions x D16/D24/D32F/R32F; sky checkerboard)",
         "A = 1 on sky; every intermediate finite; A in [0,1]",
         fmt("%zu runs: sky exactly 1, no NaN/Inf in csz/ao_raw/ao_low/ao; lowest A on geometry %.3f", runs, minGeom));
}

}  // namespace
}  // namespace sao::stability
