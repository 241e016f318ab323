#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "sao/scenes/scene.h"

namespace sao::scenes {
namespace {

constexpr double kPi = std::numbers::pi;

// A Sponza-like atrium: a floor and end walls, two storeys of arcades (pillars and arches) on
// both long sides, thin curtain panels hanging in the upper arcade, stairs at the far end.
Scene sponzaLike() {
  MeshBuilder b;
  const double halfLength = 14.0, halfWidth = 5.0, storey = 5.0;
  b.box({-halfLength, -0.2, -halfWidth - 3}, {halfLength, 0.0, halfWidth + 3});             // floor
  b.box({-halfLength - 0.5, 0, -halfWidth - 3}, {-halfLength, 2 * storey + 2, halfWidth + 3});  // end walls
  b.box({halfLength, 0, -halfWidth - 3}, {halfLength + 0.5, 2 * storey + 2, halfWidth + 3});
  for (double side : {-1.0, 1.0}) {
    const double zPillars = side * halfWidth, zWall = side * (halfWidth + 3);
    b.box({-halfLength, 0, std::min(zWall, zWall + side * 0.5)}, {halfLength, 2 * storey + 2, std::max(zWall, zWall + side * 0.5)});
    // Gallery floor over the aisle.
    b.box({-halfLength, storey, std::min(zPillars, zWall)}, {halfLength, storey + 0.3, std::max(zPillars, zWall)});
    for (int i = 0; i <= 7; ++i) {
      const double x = -halfLength + 1.5 + i * (2 * halfLength - 3) / 7.0;
      b.cylinder({x, 0, zPillars}, 0.35, storey - 1.5, 16);                       // lower pillar
      b.box({x - 0.5, storey - 1.5, zPillars - 0.5}, {x + 0.5, storey - 1.2, zPillars + 0.5});  // capital
      b.cylinder({x, storey + 0.3, zPillars}, 0.25, storey - 1.2, 12);            // upper pillar
      if (i < 7) {
        const double span = (2 * halfLength - 3) / 7.0;
        const double xc = x + span * 0.5, inner = span * 0.5 - 0.45;
        b.arch({xc, storey - 1.2 - 0.3, zPillars}, inner, 0.35, 0.7, 12);
        b.arch({xc, 2 * storey - 0.9 - 0.3, zPillars}, inner, 0.3, 0.5, 12);
        // Curtain-like thin panels hanging in the upper arcade, slightly folded.
        for (int k = 0; k < 4; ++k) {
          const double x0 = xc - inner + k * inner * 0.5, x1 = x0 + inner * 0.5;
          const double fold = (k % 2 ? 0.12 : -0.12) * side;
          b.quad({x0, storey + 0.5, zPillars - side * 0.3}, {x1, storey + 0.5, zPillars - side * 0.3 + fold},
                 {x1, 2 * storey - 1.4, zPillars - side * 0.3 + fold}, {x0, 2 * storey - 1.4, zPillars - side * 0.3});
          b.quad({x1, storey + 0.5, zPillars - side * 0.3 + fold}, {x0, storey + 0.5, zPillars - side * 0.3},
                 {x0, 2 * storey - 1.4, zPillars - side * 0.3}, {x1, 2 * storey - 1.4, zPillars - side * 0.3 + fold});
        }
      }
    }
  }
  b.stairs({halfLength - 4.5, 0, -1.5}, 3.0, 0.35, 0.2, 8);
  b.box({-3, 0, -1}, {-1.8, 0.8, 1});  // a plinth and a sphere in the nave
  b.sphere({1.5, 0.7, 0.3}, 0.7, 16, 32);
  Scene s{"sponza-like", b.build(), {}, {}, {}};
  s.views.push_back({"nave", {-12.0, 1.7, 0.8}, {4.0, 2.5, -0.5}, {0, 1, 0}, 1.2, 0.1});
  s.views.push_back({"gallery", {-10.0, 7.0, -6.5}, {6.0, 4.0, 2.0}, {0, 1, 0}, 1.1, 0.1});
  s.views.push_back({"stairs", {2.0, 1.5, 2.5}, {11.0, 0.8, 0.0}, {0, 1, 0}, 1.0, 0.1});
  return s;
}

Scene spherePlane() {
  MeshBuilder b;
  b.box({-10, -0.1, -10}, {10, 0, 10});
  b.sphere({0, 1.0, 0}, 1.0, 48, 96);
  Scene s{"sphere-plane", b.build(), {}, {}, {}};
  s.views.push_back({"front", {0, 2.2, 5.0}, {0, 0.6, 0}, {0, 1, 0}, 0.9, 0.1});
  s.views.push_back({"top", {0.01, 7.0, 0.5}, {0, 0, 0}, {0, 1, 0}, 0.9, 0.1});
  return s;
}

Scene crease() {
  MeshBuilder b;
  b.box({-10, -0.1, -10}, {10, 0, 10});   // floor
  b.box({-10, 0, -10.1}, {10, 10, -10});  // wall: a 90 degree crease with the floor along z = -10
  Scene s{"crease", b.build(), {}, {}, {}};
  s.views.push_back({"corner", {0, 3.0, -4.0}, {0, 0, -10.0}, {0, 1, 0}, 1.0, 0.1});
  return s;
}

Scene thin() {
  MeshBuilder b;
  b.box({-6, -0.1, -6}, {6, 0, 2});
  b.box({-6, 0, -3.1}, {6, 4, -3.0});  // the wall behind
  // Deterministic pseudo-random grass: a small LCG, not std::rand.
  unsigned state = 12345u;
  auto rnd = [&]() {
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) / double(1u << 24);
  };
  for (int i = 0; i < 600; ++i) {
    const glm::dvec3 base(-3 + 6 * rnd(), 0, -2.5 + 3.5 * rnd());
    b.blade(base, 0.03 + 0.02 * rnd(), 0.3 + 0.4 * rnd(), {0.15 * (rnd() - 0.5), 0, 0.15 * (rnd() - 0.5)}, kPi * rnd());
  }
  for (int i = 0; i < 9; ++i) b.cylinder({-2.4 + 0.6 * i, 0, -2.6}, 0.02, 2.5, 8);  // thin rods
  Scene s{"thin", b.build(), {}, {}, {}};
  s.views.push_back({"front", {0, 1.2, 3.0}, {0, 0.6, -2.0}, {0, 1, 0}, 0.9, 0.05});
  return s;
}

Scene gears() {
  MeshBuilder b;
  b.box({-6, -0.2, -6}, {6, 0, 6});
  b.gear({0, 0, 0}, 1.6, 1.9, 0.3, 20);
  b.box({-2.5, 0.3, -2.5}, {2.5, 0.45, 2.5});  // plate
  b.gear({0.6, 0.45, 0.4}, 1.0, 1.25, 0.35, 14);
  b.gear({-1.2, 0.45, -1.0}, 0.6, 0.8, 0.5, 10);
  b.cylinder({0.6, 0.8, 0.4}, 0.25, 0.8, 24);  // axle
  b.gear({2.6, 0, 1.8}, 0.7, 0.9, 0.25, 12);
  b.box({1.8, 0.25, 1.0}, {3.4, 0.35, 2.6});
  Scene s{"gears", b.build(), {}, {}, {}};
  s.views.push_back({"oblique", {6.5, 5.5, 7.5}, {0.5, 0.2, 0.5}, {0, 1, 0}, 0.75, 0.1});
  return s;
}

constexpr std::string_view kNames[] = {"sponza-like", "sphere-plane", "crease", "thin", "gears"};

}  // namespace

std::span<const std::string_view> builtinSceneNames() { return kNames; }

Status makeBuiltinScene(std::string_view name, Scene& out) {
  if (name == "sponza-like") out = sponzaLike();
  else if (name == "sphere-plane") out = spherePlane();
  else if (name == "crease") out = crease();
  else if (name == "thin") out = thin();
  else if (name == "gears") out = gears();
  else {
    std::string known;
    for (auto n : kNames) known += (known.empty() ? "" : ", ") + std::string(n);
    return Status::error(StatusCode::InvalidInput,
                         "unknown built-in scene '" + std::string(name) + "' (built-in: " + known + ")");
  }
  out.units = DeclaredUnits{LengthUnit::Metre, "built-in scene"};
  return Status::success();
}

glm::dmat4 viewMatrix(const View& v) {
  const glm::dvec3 f = glm::normalize(v.target - v.eye);
  const glm::dvec3 s = glm::normalize(glm::cross(f, v.up));
  const glm::dvec3 u = glm::cross(s, f);
  glm::dmat4 m(1.0);
  m[0][0] = s.x; m[1][0] = s.y; m[2][0] = s.z;
  m[0][1] = u.x; m[1][1] = u.y; m[2][1] = u.z;
  m[0][2] = -f.x; m[1][2] = -f.y; m[2][2] = -f.z;
  m[3][0] = -glm::dot(s, v.eye);
  m[3][1] = -glm::dot(u, v.eye);
  m[3][2] = glm::dot(f, v.eye);
  return m;
}

Camera makeCamera(const View& v, std::uint32_t width, std::uint32_t height, double farDistance, ClipDepth clip,
                  bool reversedZ, std::uint32_t guardBand) {
  // The projection covers the viewport; the guard band extends the frustum by guardBand pixels on
  // each side, so the depth input is rendered with a wider frustum of the same pixel scale.
  Camera c;
  if (v.orthographic()) {
    const double fallback = 1000.0 * std::max(glm::length(v.target - v.eye), v.nearDistance);
    const double far = std::isfinite(farDistance) ? farDistance : v.orthoFar > v.nearDistance ? v.orthoFar : fallback;
    c = orthographicCamera(0.5 * v.orthoHeight, width, height, v.nearDistance, far, clip, reversedZ);
  } else {
    c = perspectiveCamera(v.fovyRadians, width, height, v.nearDistance, farDistance, clip, reversedZ);
  }
  c.guardBand = guardBand;
  c.view = viewArray(v);  // the pose: temporal accumulation reprojects through it
  return c;
}

std::array<double, 16> viewArray(const View& view) {
  const glm::dmat4 m = viewMatrix(view);
  std::array<double, 16> a{};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) a[std::size_t(c * 4 + r)] = m[c][r];
  return a;
}

namespace {

void meshBounds(const Mesh& mesh, glm::dvec3 fallback, glm::dvec3& lo, glm::dvec3& hi) {
  lo = glm::dvec3(std::numeric_limits<double>::max());
  hi = -lo;
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  if (mesh.positions.empty()) lo = hi = fallback;
}

}  // namespace

void fitOrthoFar(View& v, const Mesh& mesh) {
  glm::dvec3 lo, hi;
  meshBounds(mesh, v.target, lo, hi);
  fitOrthoFar(v, lo, hi);
}

View toOrthographic(View v, glm::dvec3 lo, glm::dvec3 hi) {
  const glm::dvec3 d = v.target - v.eye;
  const double distance = glm::length(d);
  const glm::dvec3 f = d / distance;
  if (!v.orthographic()) v.orthoHeight = 2.0 * distance * std::tan(0.5 * v.fovyRadians);
  double back = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 q((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
    back = std::max(back, 2.0 * v.nearDistance - glm::dot(q - v.eye, f));
  }
  v.eye -= f * back;
  fitOrthoFar(v, lo, hi);
  return v;
}

View toOrthographic(const View& v, const Mesh& mesh) {
  glm::dvec3 lo, hi;
  meshBounds(mesh, v.target, lo, hi);
  return toOrthographic(v, lo, hi);
}

void fitOrthoFar(View& v, glm::dvec3 lo, glm::dvec3 hi) {
  const glm::dvec3 forward = glm::normalize(v.target - v.eye);
  double deepest = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 q((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
    deepest = std::max(deepest, glm::dot(q - v.eye, forward));
  }
  // 1% beyond the mesh: nothing of it is clipped by the far plane.
  v.orthoFar = std::max(2.0 * v.nearDistance, 1.01 * deepest);
}

}  // namespace sao::scenes
