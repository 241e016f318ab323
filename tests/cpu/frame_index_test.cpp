// Inputs::frameIndex on the CPU reference (sao::frameSpiral): frame 0 is the output without
// frames, later frames turn and shift the spiral (a different output), and a static camera's frames
// averaged reach what more taps reach: the mean of 16 frames of 4 taps is compared with single
// frames of 4 and 16 taps, against a 64-tap run (no blur, no quad averaging, so each pixel's A is its
// own taps').
#include <cmath>
#include <cstdio>
#include <vector>

#include "test_support.h"

namespace sao::test {
namespace {

using cpu::Precision;

Settings withTaps(int samples) {
  Settings s;
  s.samples = samples;
  s.quad_edge_threshold = 0.0f;  // no 2x2 averaging
  s.blur_radius = 0;             // no blur
  return s;
}

struct Scenario {
  Camera camera = testCamera(4, 1000.0, ClipDepth::NegativeOneToOne, false, 96, 64);
  DepthImage depth;
  Scenario() { depth = renderDepth(sphereOnPlaneScene(), camera, DepthFormat::D32F); }
  FloatImage run(const Settings& s, std::uint32_t frame) const {
    cpu::Inputs in;
    in.depth = &depth;
    in.frameIndex = frame;
    cpu::Result r;
    const Status st = cpu::run(s, camera, in, {Precision::Float, 2}, r);
    EXPECT_TRUE(st.ok()) << st.message;
    return r.ao;
  }
};

double rmse(const FloatImage& a, const FloatImage& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i) sum += (double(a.data[i]) - b.data[i]) * (double(a.data[i]) - b.data[i]);
  return std::sqrt(sum / double(a.data.size()));
}

TEST(FrameIndex, FrameZeroIsTheOutputWithoutFramesAndOthersDiffer) {
  const Scenario sc;
  cpu::Inputs in;
  in.depth = &sc.depth;
  cpu::Result plain;
  ASSERT_TRUE(cpu::run(withTaps(8), sc.camera, in, {Precision::Float, 2}, plain).ok());
  const FloatImage zero = sc.run(withTaps(8), 0);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < zero.data.size(); ++i) differ += zero.data[i] != plain.ao.data[i];
  EXPECT_EQ(differ, 0u);
  for (std::uint32_t frame : {1u, 2u, 77u}) {
    const FloatImage f = sc.run(withTaps(8), frame);
    std::size_t changed = 0;
    for (std::size_t i = 0; i < f.data.size(); ++i) changed += f.data[i] != zero.data[i];
    // Sky and open floor are 1 in every frame; the rest (a fifth of this view) moves.
    EXPECT_GT(changed, f.data.size() / 10) << "frame " << frame << " moved too few pixels' taps";
  }
}

TEST(FrameIndex, SixteenFramesOfFourTapsAverageTowardsTheConvergedResult) {
  const Scenario sc;
  const FloatImage converged = sc.run(withTaps(64), 0);
  FloatImage mean(converged.extent, 1);
  for (std::uint32_t frame = 0; frame < 16; ++frame) {
    const FloatImage f = sc.run(withTaps(4), frame);
    for (std::size_t i = 0; i < f.data.size(); ++i) mean.data[i] += f.data[i] / 16.0f;
  }
  const double single4 = rmse(sc.run(withTaps(4), 0), converged);
  const double single16 = rmse(sc.run(withTaps(16), 0), converged);
  const double mean16x4 = rmse(mean, converged);
  std::printf("FRAMES RMSE vs 64 taps: 1 frame x 4 taps %.4f, 1 frame x 16 taps %.4f, mean of 16 frames x 4 taps %.4f\n",
              single4, single16, mean16x4);
  EXPECT_LT(mean16x4, 0.6 * single4) << "the frames' taps do not add up";
}

}  // namespace
}  // namespace sao::test
