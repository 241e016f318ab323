// The dedicated scene of the precision measurement and its analytic truth.
#include <algorithm>
#include <cmath>

#include "precision_internal.h"

namespace sao::prepass {
namespace {

// Rounds to a multiple of 2^-12: with |v| < 2^11 every sum below stays exactly representable in
// float (at most 23 significant bits), so the float mesh is exactly these parallelograms.
double snap(double v) { return std::round(v * 4096.0) / 4096.0; }
glm::dvec3 snap(glm::dvec3 v) { return {snap(v.x), snap(v.y), snap(v.z)}; }

}  // namespace

void precisionScene(double aspect, scenes::Mesh& mesh, scenes::View& view, std::vector<PrecisionPanel>& panels) {
  view = scenes::View{};
  view.name = "precision";
  view.eye = {0, 0, 0};
  view.target = {0, 0, -1};
  view.up = {0, 1, 0};
  view.fovyRadians = 1.0;
  view.nearDistance = 0.1;
  const double tanV = std::tan(0.5 * view.fovyRadians), tanH = tanV * aspect;
  const double distances[3] = {1.0, 10.0, 100.0};
  const double columns[3] = {-2.0 / 3.0, 0.0, 2.0 / 3.0};  // ndc x of each panel's centre
  const double yaw = 0.25 * 3.14159265358979323846, pitch = 20.0 / 180.0 * 3.14159265358979323846;
  panels.clear();
  scenes::MeshBuilder builder;
  for (int i = 0; i < 3; ++i) {
    const double d = distances[i];
    const double halfU = 0.8 * tanH * d / 3.0, halfV = 0.6 * tanV * d;
    const glm::dvec3 centre(columns[i] * tanH * d, 0.0, -d);
    // Turned 45 degrees about y (z varies across the panel) and tipped 20 degrees about x.
    const glm::dvec3 u = snap(2.0 * halfU * glm::dvec3(std::cos(yaw), 0.0, std::sin(yaw)));
    const glm::dvec3 v = snap(2.0 * halfV * glm::dvec3(0.0, std::cos(pitch), -std::sin(pitch)));
    const glm::dvec3 corner = snap(centre - 0.5 * u - 0.5 * v);
    panels.push_back({corner, u, v});
    builder.quad(corner, corner + u, corner + u + v, corner + v);
  }
  mesh = builder.build();
}

namespace detail {

Truth panelTruth(const std::vector<PrecisionPanel>& panels, const scenes::View& view, const Camera& c) {
  Truth t;
  const std::uint32_t g = c.guardBand;
  t.extent = {c.width + 2 * g, c.height + 2 * g};
  const std::size_t n = std::size_t(t.extent.width) * t.extent.height;
  t.z.assign(n, 0.0);
  t.normal.assign(n, glm::dvec3(0.0));
  t.inside.assign(n, 0);
  std::vector<int> face(n, -1);
  const glm::dmat4 toCamera = scenes::viewMatrix(view);
  struct CamPanel {
    glm::dvec3 corner, u, v, n;
  };
  std::vector<CamPanel> cp;
  for (const auto& p : panels) {
    CamPanel q;
    q.corner = glm::dvec3(toCamera * glm::dvec4(p.corner, 1.0));
    q.u = glm::dvec3(toCamera * glm::dvec4(p.edgeU, 0.0));
    q.v = glm::dvec3(toCamera * glm::dvec4(p.edgeV, 0.0));
    q.n = glm::normalize(glm::cross(q.u, q.v));
    cp.push_back(q);
  }
  auto P = [&](int r, int col) { return c.projection[col * 4 + r]; };
  DepthModel model;
  (void)analyze(c, model);
  for (std::uint32_t y = 0; y < t.extent.height; ++y)
    for (std::uint32_t x = 0; x < t.extent.width; ++x) {
      // The ray through the texel centre, as raytrace::castPrimary casts it.
      const double ndcX = 2.0 * (double(x) - g + 0.5) / c.width - 1.0;
      const double ndcY = (c.flipY ? -1.0 : 1.0) * (2.0 * (double(y) - g + 0.5) / c.height - 1.0);
      const glm::dvec3 dir((ndcX + P(0, 2)) / P(0, 0), (ndcY + P(1, 2)) / P(1, 1), -1.0);
      double best = INFINITY;
      int bestFace = -1;
      for (std::size_t k = 0; k < cp.size(); ++k) {
        const CamPanel& q = cp[k];
        const double denom = glm::dot(q.n, dir);
        if (denom == 0) continue;
        const double s = glm::dot(q.n, q.corner) / denom;  // the point is s * dir, z = -s
        if (!(s > model.nearDistance) || !(s < model.farDistance) || s >= best) continue;
        // Coordinates in the parallelogram: solve (p - corner) = a u + b v by the normal equations.
        const glm::dvec3 r = s * dir - q.corner;
        const double uu = glm::dot(q.u, q.u), uv = glm::dot(q.u, q.v), vv = glm::dot(q.v, q.v);
        const double ru = glm::dot(r, q.u), rv = glm::dot(r, q.v), det = uu * vv - uv * uv;
        const double a = (ru * vv - rv * uv) / det, b = (rv * uu - ru * uv) / det;
        if (a < 0 || a > 1 || b < 0 || b > 1) continue;
        best = s;
        bestFace = int(k);
      }
      if (bestFace < 0) continue;
      const std::size_t i = std::size_t(y) * t.extent.width + x;
      const glm::dvec3 p = best * dir;
      glm::dvec3 nn = cp[std::size_t(bestFace)].n;
      if (glm::dot(nn, p) > 0) nn = -nn;
      t.z[i] = p.z;
      t.normal[i] = nn;
      face[i] = bestFace;
    }
  const int w = int(t.extent.width), h = int(t.extent.height);
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      const int f = face[i];
      t.inside[i] = f >= 0 && face[i - 1] == f && face[i + 1] == f && face[i - w] == f && face[i + w] == f;
    }
  return t;
}

}  // namespace detail
}  // namespace sao::prepass
