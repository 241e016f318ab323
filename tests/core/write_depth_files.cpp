// Writes the depth files of render_depth_contract.sh into a folder: what a user might hand
// `sao-render --depth` that is not hardware depth, and a sky written as -0.0.
//   write_depth_files DIR
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "sao/io.h"

namespace {

constexpr std::uint32_t kW = 48, kH = 32;

// A floor rising toward the horizon, sky above: reversed-Z, infinite far, so the sky is 0.
float floorDepth(std::uint32_t y, float sky) { return y >= kH / 2 ? sky : float(0.1 / (1.0 + (kH / 2 - y) * 0.25)); }

bool write(const std::string& path, const sao::DepthImage& depth, const sao::Camera& camera) {
  const sao::Status st = sao::writeDepthExr(path, depth, camera);
  if (!st) std::fprintf(stderr, "write_depth_files: %s\n", st.message.c_str());
  return st.ok();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: write_depth_files DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  const sao::Camera camera = sao::perspectiveCamera(1.0, kW, kH, 0.1, INFINITY, sao::ClipDepth::ZeroToOne, true);
  sao::DepthImage depth;
  depth.extent = {kW, kH};
  depth.format = sao::DepthFormat::D32F;
  depth.texels.resize(std::size_t(kW) * kH);
  auto fill = [&](float sky) {
    for (std::uint32_t y = 0; y < kH; ++y)
      for (std::uint32_t x = 0; x < kW; ++x)
        depth.texels[std::size_t(y) * kW + x] = std::bit_cast<std::uint32_t>(floorDepth(y, sky));
  };
  fill(0.0f);
  bool ok = write(dir + "/sky_plus_zero.exr", depth, camera);
  fill(-0.0f);
  ok = ok && write(dir + "/sky_minus_zero.exr", depth, camera);
  // NaN, infinities and values outside [0, 1] planted into the floor, first at (3, 2).
  fill(0.0f);
  const float bad[] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                       -std::numeric_limits<float>::infinity(), -0.5f, 1.5f};
  for (std::uint32_t i = 0; i < 5; ++i)
    depth.texels[std::size_t(2) * kW + 3 + i] = std::bit_cast<std::uint32_t>(bad[i]);
  ok = ok && write(dir + "/bad_values.exr", depth, camera);
  // A camera-less float EXR of distances in metres (1 m to 9 m), as some renderers export depth.
  sao::FloatImage metres({kW, kH}, 1);
  for (std::uint32_t y = 0; y < kH; ++y)
    for (std::uint32_t x = 0; x < kW; ++x) metres.at(x, y) = 1.0f + 8.0f * float(y) / float(kH);
  const sao::Status st = sao::writeFloatExr(dir + "/linear_metres.exr", metres, {"Z"});
  if (!st) std::fprintf(stderr, "write_depth_files: %s\n", st.message.c_str());
  return ok && st.ok() ? 0 : 1;
}
