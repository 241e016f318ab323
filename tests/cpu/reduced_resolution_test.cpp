// The CPU reference at resolution_divisor 2 and 4: reduced images of the viewport over the divisor
// (rounded up), float against double, no seam at odd sizes, and the upsample's rule at
// silhouettes (a pixel whose z matches none of its 2x2 low texels takes the nearest in z).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "untuned_settings.h"
#include "sao/presets.h"
#include "seam_metric.h"
#include "test_support.h"

namespace sao::test {
namespace {

// The untuned medium: the seam bound below was set against its full-resolution output (<= 0.36/255),
// whose 7-tap blur smooths more than the tuned presets' do.
Settings reduced(int divisor) {
  Settings s = test::untunedMedium();
  s.resolution_divisor = divisor;
  return s;
}

const FloatImage& aoLow(const cpu::Result& r) {
  return r.images[static_cast<std::size_t>(gen::ResourceId::ao_low)].at(0);
}

TEST(ReducedResolution, ImagesAreTheViewportOverTheDivisorRoundedUp) {
  const Camera cam = testCamera(8, 1000.0, ClipDepth::NegativeOneToOne, false, 97, 61);
  const DepthImage depth = renderDepth(sphereOnPlaneScene(), cam, DepthFormat::D32F);
  for (int d : {2, 4}) {
    const cpu::Result r = runOrFail(reduced(d), cam, {&depth}, cpu::Precision::Float);
    const Extent low{(97u + d - 1) / d, (61u + d - 1) / d};
    EXPECT_EQ(r.aoRaw.extent, low) << d;
    ASSERT_EQ(r.images[static_cast<std::size_t>(gen::ResourceId::ao_low)].size(), 1u) << d;
    EXPECT_EQ(aoLow(r).extent, low) << d;
    EXPECT_EQ(r.ao.extent, (Extent{97, 61})) << d;
    EXPECT_TRUE(allFinite(r.ao)) << d;
    // Every reduced pixel's key is the z of the viewport pixel it stands for: min(p*d + d/2, size - 1).
    for (std::uint32_t y = 0; y < low.height; ++y)
      for (std::uint32_t x = 0; x < low.width; ++x) {
        const std::uint32_t fx = std::min(x * d + d / 2, 96u), fy = std::min(y * d + d / 2, 60u);
        ASSERT_EQ(r.aoRaw.at(x, y, 1), r.csz[0].at(fx + 8, fy + 8)) << d << " at " << x << "," << y;
      }
  }
}

// Float (the GPU's arithmetic) and double agree as closely at reduced resolution as at full.
TEST(ReducedResolution, FloatMatchesDouble) {
  const Camera cam = testCamera();
  for (const char* name : {"sphere", "stairs", "rods"}) {
    const Scene scene = std::string(name) == "sphere" ? sphereOnPlaneScene()
                        : std::string(name) == "stairs" ? stairsScene() : rodsScene();
    const DepthImage depth = renderDepth(scene, cam, DepthFormat::D32F);
    for (int d : {2, 4}) {
      const cpu::Result f = runOrFail(reduced(d), cam, {&depth}, cpu::Precision::Float);
      const cpu::Result g = runOrFail(reduced(d), cam, {&depth}, cpu::Precision::Double);
      const Agreement a = compare(f.ao, g.ao, 0, 2.0 / 255.0, 4.0 / 255.0, "", "", nullptr);
      std::printf("%s d=%d float vs double: max %.3f/255 p99.9 %.3f/255\n", name, d, a.maxAbs * 255, a.p999 * 255);
      EXPECT_TRUE(acceptable(a)) << name << " divisor " << d;
    }
  }
}

// At odd sizes no row or column stands out from its neighbours (seam_metric.h). On an open plane
// A is 1 everywhere (eq. 1: coplanar taps add nothing), so any other value is an unwritten or
// misread texel. In the vertical crease A depends on the column alone, so row means are flat; in
// the horizontal one, column means are.
TEST(ReducedResolution, NoSeamAtOddSizes) {
  for (auto [w, h] : {std::pair{641u, 359u}, std::pair{97u, 61u}}) {
    const Camera cam = testCamera(0, 1000.0, ClipDepth::NegativeOneToOne, false, w, h);
    const DepthImage plane = renderDepth(planeScene(3.0), cam, DepthFormat::D32F);
    const DepthImage vertical = renderDepth(creaseScene(2.0), cam, DepthFormat::D32F);
    const DepthImage horizontal = renderDepth(horizontalCreaseScene(2.0), cam, DepthFormat::D32F);
    for (int d : {1, 2, 4}) {
      const cpu::Result p = runOrFail(reduced(d), cam, {&plane}, cpu::Precision::Float);
      EXPECT_EQ(*std::min_element(p.ao.data.begin(), p.ao.data.end()), 1.0f) << w << "x" << h << " d=" << d;
      const std::uint32_t margin = 2 * d;  // the last two blocks
      const SeamScore rows = seamScore(runOrFail(reduced(d), cam, {&vertical}, cpu::Precision::Float).ao, margin);
      const SeamScore cols = seamScore(runOrFail(reduced(d), cam, {&horizontal}, cpu::Precision::Float).ao, margin);
      std::printf("seam %ux%u d=%d: rows %.4f/255 (row %u), columns %.4f/255 (column %u)\n", w, h, d, rows.row * 255,
                  rows.worstRow, cols.column * 255, cols.worstColumn);
      EXPECT_LT(rows.row, kSeamBound) << w << "x" << h << " d=" << d << " row " << rows.worstRow;
      EXPECT_LT(cols.column, kSeamBound) << w << "x" << h << " d=" << d << " column " << cols.worstColumn;
    }
  }
}

// The metric sees a seam: one column of a seam-free output raised by 1/255 scores above the bound.
TEST(ReducedResolution, SeamMetricSeesOneOffColumn) {
  const Camera cam = testCamera(0, 1000.0, ClipDepth::NegativeOneToOne, false, 641, 359);
  const DepthImage horizontal = renderDepth(horizontalCreaseScene(2.0), cam, DepthFormat::D32F);
  FloatImage ao = runOrFail(reduced(2), cam, {&horizontal}, cpu::Precision::Float).ao;
  ASSERT_LT(seamScore(ao, 4).column, kSeamBound);
  for (std::uint32_t y = 0; y < ao.extent.height; ++y) ao.at(320, y) += float(1.0 / 255.0);
  const SeamScore s = seamScore(ao, 4);
  EXPECT_GT(s.column, kSeamBound);
  EXPECT_EQ(s.worstColumn, 320u);
}

// The depth-blind upsample the depth-aware one is measured against: bilinear between the same
// representative pixels of the same low (A, key) image, sky texels left out.
double bilinearUpsample(const FloatImage& low, std::uint32_t x, std::uint32_t y, int d, std::uint32_t W,
                        std::uint32_t H) {
  auto rep = [d](int q, std::uint32_t n) { return std::min(q * d + d / 2, int(n) - 1); };
  const int lastX = int(low.extent.width) - 1, lastY = int(low.extent.height) - 1;
  const int q0x = std::min(std::max(int(x) - d / 2, 0) / d, lastX), q0y = std::min(std::max(int(y) - d / 2, 0) / d, lastY);
  const int q1x = std::min(q0x + 1, lastX), q1y = std::min(q0y + 1, lastY);
  const double tx = std::clamp(double(int(x) - rep(q0x, W)) / std::max(rep(q1x, W) - rep(q0x, W), 1), 0.0, 1.0);
  const double ty = std::clamp(double(int(y) - rep(q0y, H)) / std::max(rep(q1y, H) - rep(q0y, H), 1), 0.0, 1.0);
  double sum = 0, wsum = 0;
  for (int j = 0; j < 4; ++j) {
    const int qx = (j & 1) ? q1x : q0x, qy = (j & 2) ? q1y : q0y;
    const double w = ((j & 1) ? tx : 1 - tx) * ((j & 2) ? ty : 1 - ty);
    if (low.at(qx, qy, 1) >= 0.0f) continue;  // sky
    sum += w * low.at(qx, qy, 0);
    wsum += w;
  }
  return wsum > 0 ? sum / wsum : 1.0;
}

// Silhouettes: near depth discontinuities (a relative z step over 1/16 between 4-neighbours, within
// 3 px), the depth-aware upsample stays closer to the full-resolution output than a depth-blind
// bilinear upsample of the same low image, whose pixels on one side take the other side's A (the
// halo); away from them the two are alike.
TEST(ReducedResolution, SilhouettesKeepTheirSide) {
  const Camera cam = testCamera(8, 1000.0, ClipDepth::NegativeOneToOne, false, 320, 180);
  for (const char* name : {"sphere", "rods", "stairs"}) {
    const Scene scene = std::string(name) == "sphere" ? sphereOnPlaneScene()
                        : std::string(name) == "stairs" ? stairsScene() : rodsScene();
    const DepthImage depth = renderDepth(scene, cam, DepthFormat::D32F);
    const cpu::Result full = runOrFail(reduced(1), cam, {&depth}, cpu::Precision::Float);
    const std::uint32_t W = 320, H = 180, g = 8;
    std::vector<int> edge(std::size_t(W) * H, 0);
    auto z = [&](std::uint32_t x, std::uint32_t y) { return double(full.csz[0].at(x + g, y + g)); };
    auto step = [&](double a, double b) {
      return (a < 0) != (b < 0) || std::fabs(a - b) > std::max(std::fabs(a), std::fabs(b)) / 16.0;
    };
    for (std::uint32_t y = 0; y < H; ++y)
      for (std::uint32_t x = 0; x < W; ++x)
        if ((x + 1 < W && step(z(x, y), z(x + 1, y))) || (y + 1 < H && step(z(x, y), z(x, y + 1))))
          for (int dy = -3; dy <= 4; ++dy)
            for (int dx = -3; dx <= 4; ++dx) {
              const int ex = int(x) + dx, ey = int(y) + dy;
              if (ex >= 0 && ey >= 0 && ex < int(W) && ey < int(H)) edge[std::size_t(ey) * W + ex] = 1;
            }
    for (int d : {2, 4}) {
      const cpu::Result r = runOrFail(reduced(d), cam, {&depth}, cpu::Precision::Float);
      double e[2] = {0, 0}, b[2] = {0, 0};
      std::size_t n[2] = {0, 0};
      for (std::uint32_t y = 0; y < H; ++y)
        for (std::uint32_t x = 0; x < W; ++x) {
          const int k = edge[std::size_t(y) * W + x];
          const double truth = full.ao.at(x, y);
          e[k] += std::fabs(double(r.ao.at(x, y)) - truth);
          b[k] += std::fabs((z(x, y) < 0 ? bilinearUpsample(aoLow(r), x, y, d, W, H) : 1.0) - truth);
          ++n[k];
        }
      ASSERT_GT(n[1], 0u) << name;
      ASSERT_GT(n[0], 0u) << name;
      for (int k = 0; k < 2; ++k) e[k] /= double(n[k]), b[k] /= double(n[k]);
      std::printf("%s d=%d: mean |A - A_full| near edges %.4f (bilinear %.4f, %zu px), elsewhere %.4f (bilinear %.4f)\n",
                  name, d, e[1], b[1], n[1], e[0], b[0]);
      EXPECT_LT(e[1], b[1]) << name << " d=" << d << ": the depth-aware upsample is no better at silhouettes";
    }
  }
}

}  // namespace
}  // namespace sao::test
