#include "sao/prepass/precision.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>

#include "precision_internal.h"
#include "sao/cpu/reference.h"
#include "sao/raytrace/raytrace.h"

namespace sao::prepass {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

// Truth from the ray cast: z and normals of castPrimary; "inside a face" where the 4 neighbours
// are hit, their normals agree with the pixel's to 1e-5 rad and they lie on the pixel's plane.
Status rayTruth(const scenes::Mesh& mesh, const scenes::View& view, const Camera& camera, detail::Truth& t) {
  std::unique_ptr<raytrace::RayScene> scene;
  if (Status s = raytrace::RayScene::create(mesh, scene); !s) return s;
  raytrace::Primary primary;
  if (Status s = raytrace::castPrimary(*scene, view, camera, DepthFormat::D32F, primary); !s) return s;
  t.extent = primary.position.extent;
  const int w = int(t.extent.width), h = int(t.extent.height);
  const std::size_t n = std::size_t(w) * h;
  t.z.assign(n, 0.0);
  t.normal.assign(n, glm::dvec3(0.0));
  t.inside.assign(n, 0);
  std::vector<glm::dvec3> pos(n);
  std::vector<unsigned char> hit(n, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      if (primary.position.at(x, y, 3) == 0.0f) continue;
      hit[i] = 1;
      pos[i] = {primary.position.at(x, y, 0), primary.position.at(x, y, 1), primary.position.at(x, y, 2)};
      t.z[i] = pos[i].z;
      t.normal[i] = glm::normalize(
          glm::dvec3(primary.normal.at(x, y, 0), primary.normal.at(x, y, 1), primary.normal.at(x, y, 2)));
    }
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      if (!hit[i]) continue;
      bool same = true;
      for (std::size_t j : {i - 1, i + 1, i - std::size_t(w), i + std::size_t(w)}) {
        same = same && hit[j] && glm::length(glm::cross(t.normal[i], t.normal[j])) < 1e-5 &&
               glm::dot(t.normal[i], t.normal[j]) > 0 &&
               std::abs(glm::dot(t.normal[i], pos[j] - pos[i])) < 1e-5 * glm::length(pos[i]);
      }
      t.inside[i] = same;
    }
  return Status::success();
}

double percentile99(std::vector<double>& v) {
  if (v.empty()) return 0;
  const std::size_t k = std::size_t(std::floor(0.99 * double(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

using TruthFn = std::function<Status(const Camera&, detail::Truth&)>;

Status measure(Prepass& prepass, const scenes::Mesh& mesh, const scenes::View& view, const PrecisionOptions& o,
               const TruthFn& truthFor, std::vector<PrecisionRow>& rows) {
  rows.clear();
  if (o.width == 0 || o.height == 0) return Status::error(StatusCode::InvalidExtent, "precision: zero image size");
  if (o.binCentres.empty()) return Status::error(StatusCode::InvalidInput, "precision: no distance bins");
  for (double c : o.binCentres)
    if (!(c > 0) || !std::isfinite(c))
      return Status::error(StatusCode::InvalidInput, "precision: bin centres must be finite and > 0");
  const ClipDepth standardClip =
      prepass.supportsClip(ClipDepth::NegativeOneToOne) ? ClipDepth::NegativeOneToOne : ClipDepth::ZeroToOne;
  std::vector<bool> conventions;
  if (o.standard) conventions.push_back(false);
  if (o.reversed) conventions.push_back(true);

  // The x/y of the projection (hence the truth) is the same for every depth convention.
  detail::Truth truth;
  {
    const Camera any = scenes::makeCamera(view, o.width, o.height, INFINITY, ClipDepth::ZeroToOne, true, 0);
    if (Status s = truthFor(any, truth); !s) return s;
  }
  cpu::Options cpuOptions;
  cpuOptions.precision = cpu::Precision::Float;  // the GPU's arithmetic
  Settings settings{};
  settings.samples = 1;
  settings.blur_radius = 0;
  settings.use_z_hierarchy = false;

  for (DepthFormat format : o.formats)
    for (double far : o.farPlanes)
      for (bool reversed : conventions) {
        const ClipDepth clip = reversed ? ClipDepth::ZeroToOne : standardClip;
        const Camera camera = scenes::makeCamera(view, o.width, o.height, far, clip, reversed, 0);
        PrepassOptions po;
        po.format = format;
        PrepassResult raster;
        if (Status s = prepass.render(mesh, view, camera, po, raster); !s) return s;
        cpu::Inputs in;
        in.depth = &raster.depth;
        cpu::Result ref;
        if (Status s = cpu::run(settings, camera, in, cpuOptions, ref); !s) return s;
        const FloatImage& csz = ref.csz.at(0);
        const double u = camera.metersToViewUnits;
        for (double centre : o.binCentres) {
          const double lo = centre / std::sqrt(10.0), hi = centre * std::sqrt(10.0);
          std::vector<double> zErr, nErr;
          PrecisionRow row;
          row.format = format;
          row.farPlane = far;
          row.reversed = reversed;
          row.clip = clip;
          row.distanceBin = centre;
          for (std::uint32_t y = 0; y < truth.extent.height; ++y)
            for (std::uint32_t x = 0; x < truth.extent.width; ++x) {
              const std::size_t i = std::size_t(y) * truth.extent.width + x;
              const double dist = -truth.z[i] / u;
              if (!truth.inside[i] || !(dist >= lo && dist < hi)) continue;
              ++row.pixels;
              const float z = csz.at(x, y);
              if (!(z < 0.0f)) {  // sky: +0.0 from the linear_z pass
                ++row.lost;
                continue;
              }
              zErr.push_back(std::abs(double(z) - truth.z[i]) / u);
              const auto n = detail::reconstructNormal(csz, int(x), int(y), ref.params);
              const glm::dvec3 nr(n[0], n[1], n[2]);
              nErr.push_back(std::atan2(glm::length(glm::cross(nr, truth.normal[i])), glm::dot(nr, truth.normal[i])) *
                             kRadToDeg);
            }
          if (row.pixels == 0) continue;
          row.zWorstM = zErr.empty() ? 0 : *std::max_element(zErr.begin(), zErr.end());
          row.normalWorstDeg = nErr.empty() ? 0 : *std::max_element(nErr.begin(), nErr.end());
          row.zP99M = percentile99(zErr);
          row.normalP99Deg = percentile99(nErr);
          rows.push_back(row);
        }
      }
  return Status::success();
}

}  // namespace

Status measurePrecision(Prepass& prepass, const PrecisionOptions& o, std::vector<PrecisionRow>& rows) {
  scenes::Mesh mesh;
  scenes::View view;
  std::vector<PrecisionPanel> panels;
  precisionScene(o.height ? double(o.width) / o.height : 1.0, mesh, view, panels);
  return measure(
      prepass, mesh, view, o,
      [&](const Camera& c, detail::Truth& t) {
        t = detail::panelTruth(panels, view, c);
        return Status::success();
      },
      rows);
}

Status measurePrecision(Prepass& prepass, const scenes::Mesh& mesh, const scenes::View& view,
                        const PrecisionOptions& o, std::vector<PrecisionRow>& rows) {
  return measure(
      prepass, mesh, view, o, [&](const Camera& c, detail::Truth& t) { return rayTruth(mesh, view, c, t); }, rows);
}

std::string formatPrecisionTable(const std::vector<PrecisionRow>& rows) {
  std::string s = "format  far     depth            bin[m]  pixels    lost  z worst [m]  z p99 [m]   n worst[deg]  n p99[deg]\n";
  char line[256];
  for (const auto& r : rows) {
    char far[16];
    if (std::isinf(r.farPlane))
      std::snprintf(far, sizeof far, "inf");
    else
      std::snprintf(far, sizeof far, "%g", r.farPlane);
    const char* conv = r.reversed ? "reversed [0,1]" : (r.clip == ClipDepth::NegativeOneToOne ? "standard [-1,1]" : "standard [0,1]");
    std::snprintf(line, sizeof line, "%-6s  %-6s  %-15s  %6g  %7zu  %6zu  %11.3e  %10.3e  %12.4f  %10.4f\n",
                  sao::toString(r.format), far, conv, r.distanceBin, r.pixels, r.lost, r.zWorstM, r.zP99M,
                  r.normalWorstDeg, r.normalP99Deg);
    s += line;
  }
  return s;
}

}  // namespace sao::prepass
