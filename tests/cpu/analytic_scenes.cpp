#include "analytic_scenes.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sao::test {
namespace {

Vec3 add(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 sub(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 scale(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 unit(Vec3 a) { return scale(a, 1.0 / std::sqrt(dot(a, a))); }

double P(const Camera& c, int row, int col) { return c.projection[std::size_t(col) * 4 + std::size_t(row)]; }

// Near / far distances from the projection (the core's own analysis).
void clipRange(const Camera& camera, double& nearDistance, double& farDistance) {
  DepthModel model;
  if (analyze(camera, model)) {
    nearDistance = model.nearDistance;
    farDistance = model.farDistance;
  } else {
    nearDistance = 0;
    farDistance = std::numeric_limits<double>::infinity();
  }
}

// The `layer`-th visible hit (inside the clip range), or false.
bool visibleHit(const Scene& scene, const Camera& camera, std::uint32_t x, std::uint32_t y, int layer, Hit& out) {
  double n, f;
  clipRange(camera, n, f);
  Vec3 o, d;
  viewRay(camera, x, y, o, d);
  int k = 0;
  for (const Hit& h : scene.trace(o, d)) {
    const double dist = -h.point.z;
    if (dist < n || dist > f) continue;
    if (k++ == layer) {
      out = h;
      return true;
    }
  }
  return false;
}

}  // namespace

std::vector<Hit> Scene::trace(Vec3 o, Vec3 d) const {
  std::vector<Hit> hits;
  auto addHit = [&](double t, Vec3 normal) {
    if (!(t > 0) || !std::isfinite(t)) return;
    hits.push_back({t, add(o, scale(d, t)), unit(normal)});
  };
  for (const Plane& p : planes) {
    const double den = dot(d, p.normal);
    if (den == 0) continue;
    const double t = dot(sub(p.point, o), p.normal) / den;
    const Vec3 q = add(o, scale(d, t));
    bool kept = true;
    for (const HalfSpace& h : p.keep) kept = kept && dot(sub(q, h.point), h.normal) <= 0;
    if (kept) addHit(t, p.normal);
  }
  for (const Sphere& s : spheres) {
    const Vec3 oc = sub(o, s.centre);
    const double a = dot(d, d), b = 2 * dot(oc, d), c = dot(oc, oc) - s.radius * s.radius;
    const double disc = b * b - 4 * a * c;
    if (disc <= 0) continue;
    const double r = std::sqrt(disc);
    for (double t : {(-b - r) / (2 * a), (-b + r) / (2 * a)}) addHit(t, sub(add(o, scale(d, t)), s.centre));
  }
  for (const Box& bx : boxes) {
    const double o3[3] = {o.x, o.y, o.z}, d3[3] = {d.x, d.y, d.z};
    const double lo[3] = {bx.lo.x, bx.lo.y, bx.lo.z}, hi[3] = {bx.hi.x, bx.hi.y, bx.hi.z};
    double tIn = -std::numeric_limits<double>::infinity(), tOut = std::numeric_limits<double>::infinity();
    int axisIn = -1, axisOut = -1;
    double signIn = 0, signOut = 0;
    bool miss = false;
    for (int a = 0; a < 3; ++a) {
      if (d3[a] == 0) {
        if (o3[a] < lo[a] || o3[a] > hi[a]) miss = true;
        continue;
      }
      double t1 = (lo[a] - o3[a]) / d3[a], t2 = (hi[a] - o3[a]) / d3[a];
      double s1 = -1, s2 = 1;  // outward normal sign of the lo / hi face
      if (t1 > t2) std::swap(t1, t2), std::swap(s1, s2);
      if (t1 > tIn) tIn = t1, axisIn = a, signIn = s1;
      if (t2 < tOut) tOut = t2, axisOut = a, signOut = s2;
    }
    if (miss || !(tIn < tOut) || axisIn < 0 || axisOut < 0) continue;
    double nIn[3] = {0, 0, 0}, nOut[3] = {0, 0, 0};
    nIn[axisIn] = signIn;
    nOut[axisOut] = signOut;
    addHit(tIn, {nIn[0], nIn[1], nIn[2]});
    addHit(tOut, {nOut[0], nOut[1], nOut[2]});
  }
  for (const Rod& r : rods) {
    const double ox = o.x - r.x, oz = o.z - r.z;
    const double a = d.x * d.x + d.z * d.z, b = 2 * (ox * d.x + oz * d.z), c = ox * ox + oz * oz - r.radius * r.radius;
    if (a == 0) continue;
    const double disc = b * b - 4 * a * c;
    if (disc <= 0) continue;
    const double s = std::sqrt(disc);
    for (double t : {(-b - s) / (2 * a), (-b + s) / (2 * a)}) {
      const Vec3 q = add(o, scale(d, t));
      if (q.y < r.yMin || q.y > r.yMax) continue;
      addHit(t, {q.x - r.x, 0, q.z - r.z});
    }
  }
  std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.t < b.t; });
  return hits;
}

Scene skyScene() { return Scene{"sky", {}, {}, {}, {}}; }

Scene planeScene(double distance) {
  Scene s{"plane", {}, {}, {}, {}};
  s.planes.push_back({{0, 0, -distance}, {0, 0, 1}, {}});
  return s;
}

Scene creaseScene(double distance) {
  Scene s{"crease", {}, {}, {}, {}};
  s.planes.push_back({{0, 0, -distance}, {1, 0, 1}, {{{0, 0, 0}, {1, 0, 0}}}});    // x <= 0
  s.planes.push_back({{0, 0, -distance}, {-1, 0, 1}, {{{0, 0, 0}, {-1, 0, 0}}}});  // x >= 0
  return s;
}

Scene sphereOnPlaneScene() {
  Scene s{"sphere_on_plane", {}, {}, {}, {}};
  s.planes.push_back({{0, -1, 0}, {0, 1, 0}, {}});
  s.planes.push_back({{0, 0, -8}, {0, 0, 1}, {}});
  s.spheres.push_back({{0, -0.5, -3}, 0.5});
  return s;
}

Scene stairsScene() {
  Scene s{"stairs", {}, {}, {}, {}};
  s.planes.push_back({{0, -1, 0}, {0, 1, 0}, {}});
  s.planes.push_back({{0, 0, -6}, {0, 0, 1}, {}});
  for (int i = 0; i < 6; ++i)
    s.boxes.push_back({{-1.5, -1.0, -2.0 - 0.3 * (i + 1)}, {1.5, -1.0 + 0.2 * (i + 1), -2.0 - 0.3 * i}});
  return s;
}

Scene rodsScene() {
  Scene s{"rods", {}, {}, {}, {}};
  s.planes.push_back({{0, 0, -4}, {0, 0, 1}, {}});
  for (int i = -2; i <= 2; ++i) s.rods.push_back({0.5 * i, -3.0, 0.02, -100, 100});
  return s;
}

Extent inputExtent(const Camera& c) { return {c.width + 2 * c.guardBand, c.height + 2 * c.guardBand}; }

void viewRay(const Camera& c, std::uint32_t x, std::uint32_t y, Vec3& origin, Vec3& dir) {
  const double X = double(x) + 0.5 - c.guardBand, Y = double(y) + 0.5 - c.guardBand;
  const double ndcX = 2.0 * X / c.width - 1.0;
  const double ndcY = (c.flipY ? -1.0 : 1.0) * (2.0 * Y / c.height - 1.0);
  if (c.kind == ProjectionKind::Perspective) {
    // ndc = (P00 x + P02 z) / -z: at z = -1, x = (ndc + P02) / P00.
    origin = {0, 0, 0};
    dir = {(ndcX + P(c, 0, 2)) / P(c, 0, 0), (ndcY + P(c, 1, 2)) / P(c, 1, 1), -1.0};
  } else {
    double n, f;
    clipRange(c, n, f);
    origin = {(ndcX - P(c, 0, 3)) / P(c, 0, 0), (ndcY - P(c, 1, 3)) / P(c, 1, 1), -n};
    dir = {0, 0, -1};
  }
}

double windowDepth(const Camera& c, double z) {
  const double clipZ = P(c, 2, 2) * z + P(c, 2, 3);
  const double clipW = P(c, 3, 2) * z + P(c, 3, 3);
  const double ndc = clipZ / clipW;
  return c.clipDepth == ClipDepth::ZeroToOne ? ndc : 0.5 * ndc + 0.5;
}

double clearDepth(const Camera& c) { return c.reversedZ ? 0.0 : 1.0; }

std::vector<double> renderZ(const Scene& scene, const Camera& camera, int layer) {
  const Extent e = inputExtent(camera);
  std::vector<double> z(std::size_t(e.width) * e.height, 0.0);
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x) {
      Hit h;
      if (visibleHit(scene, camera, x, y, layer, h)) z[std::size_t(y) * e.width + x] = h.point.z;
    }
  return z;
}

DepthImage renderDepth(const Scene& scene, const Camera& camera, DepthFormat format, int layer) {
  DepthImage img;
  img.extent = inputExtent(camera);
  img.format = format;
  const std::vector<double> z = renderZ(scene, camera, layer);
  img.texels.resize(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) {
    const bool sky = z[i] == 0.0;
    if (format == DepthFormat::LinearZ)
      img.texels[i] = encodeDepth(format, sky ? 0.0 : z[i]);
    else
      img.texels[i] = encodeDepth(format, sky ? clearDepth(camera) : windowDepth(camera, z[i]));
  }
  return img;
}

FloatImage renderNormals(const Scene& scene, const Camera& camera) {
  const Extent e = inputExtent(camera);
  FloatImage img(e, 4, 0.0f);
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x) {
      Hit h;
      if (!visibleHit(scene, camera, x, y, 0, h)) continue;
      Vec3 o, d;
      viewRay(camera, x, y, o, d);
      Vec3 n = h.normal;
      if (dot(n, d) > 0) n = scale(n, -1.0);  // toward the viewer
      img.at(x, y, 0) = float(n.x);
      img.at(x, y, 1) = float(n.y);
      img.at(x, y, 2) = float(n.z);
    }
  return img;
}

}  // namespace sao::test
