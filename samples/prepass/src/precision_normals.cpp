// Compiled with -ffp-contract=off -fno-fast-math: every operation below is one binary32 operation
// in the order effect/include/sao_normal.glsl writes it (the CPU reference's kernels do the same).
#include <bit>
#include <cmath>
#include <cstdint>

#include "precision_internal.h"

namespace sao::prepass::detail {
namespace {

struct V3 {
  float x, y, z;
};
V3 sub(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
float dot(V3 a, V3 b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }
V3 cross(V3 a, V3 b) { return {a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y}; }

bool isSky(float z) {
  const std::uint32_t b = std::bit_cast<std::uint32_t>(z);
  return !(b > 0x80000000u && b < 0xFF800000u);
}
bool isFinite(float x) { return (std::bit_cast<std::uint32_t>(x) & 0x7F800000u) != 0x7F800000u; }

struct Proj {
  float ax, ay, bx, by;
  bool ortho;
  V3 position(float px, float py, float z) const {
    const float w = ortho ? 1.0f : z;
    return {w * (px * ax + bx), w * (py * ay + by), z};
  }
};

V3 tangent(V3 c, float px, float py, float sx, float sy, float zm, float zp, const Proj& p) {
  const bool okm = !isSky(zm), okp = !isSky(zp);
  if (okp && (!okm || std::abs(zp - c.z) < std::abs(c.z - zm))) return sub(p.position(px + sx, py + sy, zp), c);
  if (okm) return sub(c, p.position(px - sx, py - sy, zm));
  return sub(p.position(px + sx, py + sy, c.z), c);
}

}  // namespace

std::array<float, 3> reconstructNormal(const FloatImage& csz0, int cx, int cy, const ParamBlock& params) {
  const Proj p{params.proj_info.x, params.proj_info.y, params.proj_info.z, params.proj_info.w, params.ortho != 0};
  const int w = int(csz0.extent.width), h = int(csz0.extent.height);
  auto z = [&](int x, int y) { return (x < 0 || y < 0 || x >= w || y >= h) ? 0.0f : csz0.at(std::uint32_t(x), std::uint32_t(y)); };
  const float pcx = float(cx) + 0.5f, pcy = float(cy) + 0.5f;
  const V3 c = p.position(pcx, pcy, z(cx, cy));
  const V3 dx = tangent(c, pcx, pcy, 1.0f, 0.0f, z(cx - 1, cy), z(cx + 1, cy), p);
  const V3 dy = tangent(c, pcx, pcy, 0.0f, 1.0f, z(cx, cy - 1), z(cx, cy + 1), p);
  V3 n = cross(dx, dy);
  if (p.ax * p.ay < 0.0f) n = {-n.x, -n.y, -n.z};
  const float l2 = dot(n, n);
  if (isFinite(l2) && l2 > 0.0f) {
    const float s = 1.0f / std::sqrt(l2);
    return {n.x * s, n.y * s, n.z * s};
  }
  return {0.0f, 0.0f, 1.0f};
}

}  // namespace sao::prepass::detail
