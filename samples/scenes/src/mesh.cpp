#include "sao/scenes/mesh.h"

#include <cmath>
#include <numbers>

namespace sao::scenes {

namespace {
constexpr double kPi = std::numbers::pi;
}

void Mesh::append(const Mesh& other, const glm::dmat4& transform) {
  const auto base = static_cast<std::uint32_t>(positions.size());
  for (const auto& p : other.positions) positions.push_back(glm::vec3(transform * glm::dvec4(glm::dvec3(p), 1.0)));
  for (auto i : other.indices) indices.push_back(base + i);
}

std::uint32_t MeshBuilder::vertex(glm::dvec3 p) {
  mesh_.positions.push_back(glm::vec3(p));
  return static_cast<std::uint32_t>(mesh_.positions.size() - 1);
}

void MeshBuilder::tri(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  mesh_.indices.insert(mesh_.indices.end(), {a, b, c});
}

MeshBuilder& MeshBuilder::quad(glm::dvec3 p0, glm::dvec3 p1, glm::dvec3 p2, glm::dvec3 p3) {
  const auto a = vertex(p0), b = vertex(p1), c = vertex(p2), d = vertex(p3);
  tri(a, b, c);
  tri(a, c, d);
  return *this;
}

MeshBuilder& MeshBuilder::box(glm::dvec3 lo, glm::dvec3 hi) {
  return orientedBox((lo + hi) * 0.5, (hi - lo) * 0.5, 0.0);
}

MeshBuilder& MeshBuilder::orientedBox(glm::dvec3 c, glm::dvec3 h, double yaw) {
  const double cs = std::cos(yaw), sn = std::sin(yaw);
  auto P = [&](double sx, double sy, double sz) {
    const glm::dvec3 l(sx * h.x, sy * h.y, sz * h.z);
    return c + glm::dvec3(cs * l.x + sn * l.z, l.y, -sn * l.x + cs * l.z);
  };
  quad(P(-1, -1, 1), P(1, -1, 1), P(1, 1, 1), P(-1, 1, 1));      // +z
  quad(P(1, -1, -1), P(-1, -1, -1), P(-1, 1, -1), P(1, 1, -1));  // -z
  quad(P(1, -1, 1), P(1, -1, -1), P(1, 1, -1), P(1, 1, 1));      // +x
  quad(P(-1, -1, -1), P(-1, -1, 1), P(-1, 1, 1), P(-1, 1, -1));  // -x
  quad(P(-1, 1, 1), P(1, 1, 1), P(1, 1, -1), P(-1, 1, -1));      // +y
  quad(P(-1, -1, -1), P(1, -1, -1), P(1, -1, 1), P(-1, -1, 1));  // -y
  return *this;
}

MeshBuilder& MeshBuilder::cylinder(glm::dvec3 base, double r, double height, int segments) {
  for (int i = 0; i < segments; ++i) {
    const double a0 = 2 * kPi * i / segments, a1 = 2 * kPi * (i + 1) / segments;
    const glm::dvec3 d0(std::cos(a0) * r, 0, -std::sin(a0) * r), d1(std::cos(a1) * r, 0, -std::sin(a1) * r);
    const glm::dvec3 up(0, height, 0);
    quad(base + d0, base + d1, base + d1 + up, base + d0 + up);
    const auto c0 = vertex(base), c1 = vertex(base + up);
    const auto b0 = vertex(base + d0), b1 = vertex(base + d1), t0 = vertex(base + d0 + up), t1 = vertex(base + d1 + up);
    tri(c0, b1, b0);
    tri(c1, t0, t1);
  }
  return *this;
}

MeshBuilder& MeshBuilder::sphere(glm::dvec3 c, double r, int rings, int segments) {
  auto P = [&](int ring, int seg) {
    const double th = kPi * ring / rings, ph = 2 * kPi * seg / segments;
    return c + r * glm::dvec3(std::sin(th) * std::cos(ph), std::cos(th), -std::sin(th) * std::sin(ph));
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const auto a = vertex(P(i, j)), b = vertex(P(i + 1, j)), cc = vertex(P(i + 1, j + 1)), d = vertex(P(i, j + 1));
      if (i != 0) tri(a, b, d);
      if (i != rings - 1) tri(b, cc, d);
    }
  return *this;
}

MeshBuilder& MeshBuilder::arch(glm::dvec3 c, double inner, double ringDepth, double thickness, int segments) {
  const double outer = inner + ringDepth, hz = thickness * 0.5;
  for (int i = 0; i < segments; ++i) {
    const double a0 = kPi * i / segments, a1 = kPi * (i + 1) / segments;
    auto at = [&](double a, double rad, double z) { return c + glm::dvec3(std::cos(a) * rad, std::sin(a) * rad, z); };
    quad(at(a1, inner, hz), at(a0, inner, hz), at(a0, outer, hz), at(a1, outer, hz));          // front (+z)
    quad(at(a0, inner, -hz), at(a1, inner, -hz), at(a1, outer, -hz), at(a0, outer, -hz));      // back
    quad(at(a0, inner, -hz), at(a0, inner, hz), at(a1, inner, hz), at(a1, inner, -hz));        // intrados (faces centre)
    quad(at(a1, outer, -hz), at(a1, outer, hz), at(a0, outer, hz), at(a0, outer, -hz));        // extrados
  }
  return *this;
}

MeshBuilder& MeshBuilder::gear(glm::dvec3 base, double root, double tip, double thickness, int teeth) {
  // The outline alternates root and tip radius over 4 points per tooth.
  const int n = teeth * 4;
  auto radiusAt = [&](int k) { return (k % 4 == 1 || k % 4 == 2) ? tip : root; };
  auto P = [&](int k, double y) {
    const double a = 2 * kPi * k / n;
    return base + glm::dvec3(std::cos(a) * radiusAt(k), y, -std::sin(a) * radiusAt(k));
  };
  const glm::dvec3 top = base + glm::dvec3(0, thickness, 0);
  for (int k = 0; k < n; ++k) {
    const int k1 = (k + 1) % n;
    quad(P(k, 0), P(k1, 0), P(k1, thickness), P(k, thickness));
    const auto ct = vertex(top), cb = vertex(base);
    const auto t0 = vertex(P(k, thickness)), t1 = vertex(P(k1, thickness)), b0 = vertex(P(k, 0)), b1 = vertex(P(k1, 0));
    tri(ct, t0, t1);
    tri(cb, b1, b0);
  }
  return *this;
}

MeshBuilder& MeshBuilder::stairs(glm::dvec3 o, double width, double depth, double rise, int steps) {
  for (int i = 0; i < steps; ++i)
    box(o + glm::dvec3(0, 0, i * depth), o + glm::dvec3(width, (i + 1) * rise, (i + 1) * depth));
  return *this;
}

MeshBuilder& MeshBuilder::blade(glm::dvec3 base, double width, double height, glm::dvec3 lean, double yaw) {
  const glm::dvec3 side(std::cos(yaw) * width * 0.5, 0, -std::sin(yaw) * width * 0.5);
  const glm::dvec3 tip = base + glm::dvec3(0, height, 0) + lean;
  const auto a = vertex(base - side), b = vertex(base + side), t = vertex(tip);
  tri(a, b, t);
  tri(b, a, t);  // two-sided
  return *this;
}

}  // namespace sao::scenes
