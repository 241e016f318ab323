// Internal to sao::raytrace: the deterministic random directions that the references share. Every
// result is a pure function of its seed, whatever the thread count (rows run through
// sao::cpu::parallelFor).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include <glm/glm.hpp>

namespace sao::raytrace::detail {

inline std::uint64_t splitmix(std::uint64_t& s) {
  std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Uniform in [0, 1), 53 bits.
inline double uniform01(std::uint64_t& s) { return double(splitmix(s) >> 11) * 0x1.0p-53; }

// The per-pixel seed of the image references.
inline std::uint64_t pixelSeed(std::uint64_t seed, std::uint32_t x, std::uint32_t y) {
  return seed ^ (std::uint64_t(y) << 32) ^ x;
}

// An orthonormal frame (t, b, n) around the unit normal n.
struct Frame {
  glm::dvec3 t, b, n;
  explicit Frame(glm::dvec3 normal) : n(normal) {
    const glm::dvec3 a = std::fabs(n.x) > 0.5 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    t = glm::normalize(glm::cross(a, n));
    b = glm::cross(n, t);
  }
};

// A cosine-weighted direction about f.n (density cos(theta)/pi over the hemisphere): uniform on the
// unit disk, lifted to the hemisphere. `cosTheta` receives dot(direction, n), which is > 0 (at
// least about 1e-8, since u1 < 1).
inline glm::dvec3 cosineDirection(const Frame& f, std::uint64_t& state, double& cosTheta) {
  const double u1 = uniform01(state), u2 = uniform01(state);
  const double rad = std::sqrt(u1), phi = 2.0 * std::numbers::pi * u2;
  cosTheta = std::sqrt(std::max(0.0, 1.0 - u1));
  return f.t * (rad * std::cos(phi)) + f.b * (rad * std::sin(phi)) + f.n * cosTheta;
}

}  // namespace sao::raytrace::detail
