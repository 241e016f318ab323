// Test helpers for the normals encodings (sao::NormalsEncoding): a view rotation, and a scene's
// camera-space normals (renderNormals) re-encoded in world space and/or as the signed octahedral
// map, in double, as an engine's G-buffer pass would write them. Shared by the CPU, GL and Vulkan
// tests.
#pragma once
#include <array>
#include <cmath>

#include "sao/camera.h"
#include "sao/image.h"

namespace sao::test {

// A world -> camera rotation R = Rx(pitch) * Ry(yaw) * Rz(roll) (radians), column-major 3x3.
inline std::array<double, 9> viewRotation(double yaw, double pitch, double roll) {
  auto mul = [](const std::array<double, 9>& a, const std::array<double, 9>& b) {
    std::array<double, 9> r{};
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 3; ++col)
        for (int k = 0; k < 3; ++k) r[std::size_t(col * 3 + row)] += a[std::size_t(k * 3 + row)] * b[std::size_t(col * 3 + k)];
    return r;
  };
  const double cy = std::cos(yaw), sy = std::sin(yaw), cp = std::cos(pitch), sp = std::sin(pitch);
  const double cr = std::cos(roll), sr = std::sin(roll);
  const std::array<double, 9> rx{1, 0, 0, 0, cp, sp, 0, -sp, cp};
  const std::array<double, 9> ry{cy, 0, -sy, 0, 1, 0, sy, 0, cy};
  const std::array<double, 9> rz{cr, sr, 0, -sr, cr, 0, 0, 0, 1};
  return mul(rx, mul(ry, rz));
}

// The signed octahedral map of a unit vector: (x, y) / (|x| + |y| + |z|), the lower hemisphere
// (z < 0) folded out into the corners.
inline void octahedralEncode(double x, double y, double z, double& ex, double& ey) {
  const double l1 = std::fabs(x) + std::fabs(y) + std::fabs(z);
  double px = x / l1, py = y / l1;
  if (z < 0) {
    const double sx = px >= 0 ? 1.0 : -1.0, sy = py >= 0 ? 1.0 : -1.0;
    const double qx = (1.0 - std::fabs(py)) * sx, qy = (1.0 - std::fabs(px)) * sy;
    px = qx;
    py = qy;
  }
  ex = px;
  ey = py;
}

// The camera-space normals image `n` (4 channels, (0,0,0,0) where there is no surface) in
// `encoding`, with `rotation` the world -> camera rotation R (world normal = R^T n). Octahedral
// results hold (ex, ey, 0, 0); texels without a surface stay 0.
inline FloatImage encodeNormals(const FloatImage& n, NormalsEncoding encoding, const std::array<double, 9>& rotation) {
  FloatImage out(n.extent, 4);
  const bool world = encoding == NormalsEncoding::WorldXyz || encoding == NormalsEncoding::WorldOctahedral;
  const bool octahedral = encoding == NormalsEncoding::CameraOctahedral || encoding == NormalsEncoding::WorldOctahedral;
  for (std::uint32_t y = 0; y < n.extent.height; ++y)
    for (std::uint32_t x = 0; x < n.extent.width; ++x) {
      double v[3] = {n.at(x, y, 0), n.at(x, y, 1), n.at(x, y, 2)};
      if (v[0] == 0 && v[1] == 0 && v[2] == 0) continue;
      if (world) {  // R^T v: the dot product of v with each column of R
        double w[3];
        for (int c = 0; c < 3; ++c)
          w[c] = rotation[std::size_t(c * 3)] * v[0] + rotation[std::size_t(c * 3 + 1)] * v[1] +
                 rotation[std::size_t(c * 3 + 2)] * v[2];
        for (int c = 0; c < 3; ++c) v[c] = w[c];
      }
      if (octahedral) {
        const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        double ex, ey;
        octahedralEncode(v[0] / l, v[1] / l, v[2] / l, ex, ey);
        out.at(x, y, 0) = float(ex);
        out.at(x, y, 1) = float(ey);
      } else {
        for (int c = 0; c < 3; ++c) out.at(x, y, std::uint32_t(c)) = float(v[c]);
      }
    }
  return out;
}

}  // namespace sao::test
