#include "prepass_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#ifdef SAO_PREPASS_HAVE_GL
#include <epoxy/gl.h>
#endif

namespace sao::prepasstest {

#ifdef SAO_PREPASS_HAVE_GL
prepass::GlPrepass& glPrepass() {
  static std::unique_ptr<prepass::GlPrepass> p = [] {
    std::unique_ptr<prepass::GlPrepass> q;
    const Status s = prepass::GlPrepass::create(q);
    if (!s) {
      std::fprintf(stderr, "GlPrepass::create: %s\n", s.message.c_str());
      std::abort();
    }
    std::printf("OpenGL prepass: %s\n", q->description().c_str());
    return q;
  }();
  return *p;
}
#endif

#ifdef SAO_PREPASS_HAVE_VULKAN
prepass::VkPrepass& vkPrepass() {
  static std::unique_ptr<prepass::VkPrepass> p = [] {
    vk::headless::Options o;
    o.validation = true;
    o.synchronizationValidation = true;
    std::unique_ptr<prepass::VkPrepass> q;
    const Status s = prepass::VkPrepass::create(q, o);
    if (!s) {
      std::fprintf(stderr, "VkPrepass::create: %s\n", s.message.c_str());
      std::abort();
    }
    std::printf("Vulkan prepass: %s\n", q->description().c_str());
    return q;
  }();
  return *p;
}
#endif

std::vector<std::string> backendNames() {
  std::vector<std::string> names;
#ifdef SAO_PREPASS_HAVE_GL
  names.push_back("gl");
#endif
#ifdef SAO_PREPASS_HAVE_VULKAN
  names.push_back("vulkan");
#endif
  return names;
}

prepass::Prepass& backend(const std::string& name) {
#ifdef SAO_PREPASS_HAVE_GL
  if (name == "gl") return glPrepass();
#endif
#ifdef SAO_PREPASS_HAVE_VULKAN
  if (name == "vulkan") return vkPrepass();
#endif
  std::fprintf(stderr, "no prepass backend '%s' in this build\n", name.c_str());
  std::abort();
}

void PrepassTest::SetUp() {
#ifdef SAO_PREPASS_HAVE_GL
  glPrepass().context()->clearMessages();
#endif
#ifdef SAO_PREPASS_HAVE_VULKAN
  (void)vkPrepass().context().takeMessages();
#endif
}

void PrepassTest::TearDown() {
#ifdef SAO_PREPASS_HAVE_GL
  for (const auto& m : glPrepass().context()->messages())
    if (m.type == GL_DEBUG_TYPE_ERROR || m.type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR ||
        m.type == GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR)
      ADD_FAILURE() << "GL debug message: " << gl::HeadlessContext::format(m);
  glPrepass().context()->clearMessages();
#endif
#ifdef SAO_PREPASS_HAVE_VULKAN
  const auto messages = vkPrepass().context().takeMessages();
  if (!messages.empty()) ADD_FAILURE() << "Vulkan validation:\n" << vk::headless::toString(messages);
#endif
}

const LoadedScene& loadScene(const std::string& name) {
  static std::map<std::string, std::unique_ptr<LoadedScene>> cache;
  auto& slot = cache[name];
  if (!slot) {
    slot = std::make_unique<LoadedScene>();
    Status s = scenes::makeBuiltinScene(name, slot->scene);
    if (s) s = raytrace::RayScene::create(slot->scene.mesh, slot->rays);
    if (!s) {
      std::fprintf(stderr, "scene %s: %s\n", name.c_str(), s.message.c_str());
      std::abort();
    }
  }
  return *slot;
}

double depthQuantum(DepthFormat format, double d) {
  switch (format) {
    case DepthFormat::D16: return 1.0 / 65535.0;
    case DepthFormat::D24: return 1.0 / 16777215.0;
    default: {
      const float f = float(d);
      return double(std::nextafter(f, 2.0f)) - double(f);
    }
  }
}

// Orthographic models have c0 = 0 and a linear z = d c1 + c2.
double dzdd(const DepthModel& m, double z) { return m.c0 == 0 ? std::abs(m.c1) : z * z * std::abs(m.c1 / m.c0); }

double worldScale(const scenes::Mesh& mesh, const scenes::View& view) {
  double r = std::max({std::abs(view.eye.x), std::abs(view.eye.y), std::abs(view.eye.z)});
  for (const auto& p : mesh.positions) r = std::max({r, double(std::abs(p.x)), double(std::abs(p.y)), double(std::abs(p.z))});
  return r;
}

double zBound(const Camera& c, const DepthModel& model, DepthFormat format, double z, double d, double scale) {
  constexpr double kUlp = 0x1p-24;
  const double p22 = c.projection[2 * 4 + 2], p23 = c.projection[3 * 4 + 2];
  const bool half = c.clipDepth == ClipDepth::NegativeOneToOne;
  // The rounding of ndc.z = (p22 z + p23) / -z, or p22 z + p23 for an orthographic camera. The
  // rasteriser interpolates the vertices' depths, which may lie anywhere in the depth range: the
  // perspective terms are ~1 (|p22| ~ 1), and an orthographic depth, linear in z with small
  // p22 z + p23 near the near plane, gets that 1 added.
  const double ndcTerms = c.kind == ProjectionKind::Orthographic ? 1.0 + std::abs(p22 * z) + std::abs(p23)
                                                                 : std::abs(p22) + std::abs(p23) / std::abs(z);
  const double terms = (half ? 0.5 : 1.0) * ndcTerms + (half ? 1.0 : 0.0);
  const double dd = depthQuantum(format, d) + 8.0 * kUlp * terms;
  return dzdd(model, z) * dd + 1e-6 * std::abs(z) + 8.0 * kUlp * scale;
}

namespace {

bool hitAt(const FloatImage& position, int x, int y) { return position.at(std::uint32_t(x), std::uint32_t(y), 3) != 0.0f; }

glm::dvec3 vec(const FloatImage& img, int x, int y) {
  return {img.at(std::uint32_t(x), std::uint32_t(y), 0), img.at(std::uint32_t(x), std::uint32_t(y), 1),
          img.at(std::uint32_t(x), std::uint32_t(y), 2)};
}

double windowDepth(const Camera& c, double z) {
  const double ndc = c.kind == ProjectionKind::Orthographic ? c.projection[10] * z + c.projection[14]
                                                            : (c.projection[10] * z + c.projection[14]) / (-z);
  return c.clipDepth == ClipDepth::ZeroToOne ? ndc : 0.5 * ndc + 0.5;
}

}  // namespace

RayAgreement compareWithRayCast(const prepass::PrepassResult& raster, const raytrace::Primary& ray,
                                const Camera& camera, DepthFormat format, double scale) {
  RayAgreement a;
  DepthModel model;
  if (!analyze(camera, model)) return a;
  const int w = int(ray.position.extent.width), h = int(ray.position.extent.height);
  a.pixels = std::size_t(w) * h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool r = hitAt(raster.position, x, y), t = hitAt(ray.position, x, y);
      // 3x3 neighbourhood in the ray cast: uniform coverage, and all on one plane.
      bool uniform = true, interior = t;
      const glm::dvec3 pc = vec(ray.position, x, y), nc = vec(ray.normal, x, y);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= w || yy >= h) {
            interior = false;
            continue;
          }
          const bool tn = hitAt(ray.position, xx, yy);
          uniform = uniform && tn == t;
          if (!interior || !tn) {
            interior = false;
            continue;
          }
          const glm::dvec3 pn = vec(ray.position, xx, yy), nn = vec(ray.normal, xx, yy);
          interior = glm::length(glm::cross(nn, nc)) < 1e-4 && glm::dot(nn, nc) > 0 &&
                     std::abs(glm::dot(nc, pn - pc)) < 1e-5 * glm::length(pc);
        }
      if (r != t) {
        ++a.coverageMismatch;
        if (uniform) ++a.mismatchOffSilhouette;
      }
      if (!r || !t) continue;
      const double zRay = pc.z;
      const double d = raster.depth.value(std::uint32_t(x), std::uint32_t(y));
      const double zRaster = linearZ(model, camera.kind, d);
      const double dz = std::abs(zRaster - zRay);
      const double dTrue = windowDepth(camera, zRay);
      if (dz > 100.0 * zBound(camera, model, format, zRay, dTrue, scale)) ++a.surfaceMismatch;
      if (!interior) continue;
      ++a.interior;
      a.zWorstAbs = std::max(a.zWorstAbs, dz);
      a.zWorstRelative = std::max(a.zWorstRelative, dz / std::abs(zRay));
      a.zWorstQuanta = std::max(a.zWorstQuanta, dz / (dzdd(model, zRay) * depthQuantum(format, dTrue)));
      a.zWorstBoundRatio = std::max(a.zWorstBoundRatio, dz / zBound(camera, model, format, zRay, dTrue, scale));
      const glm::dvec3 nr = vec(raster.normal, x, y);
      a.normalWorstDeg = std::max(a.normalWorstDeg, std::atan2(glm::length(glm::cross(nr, nc)), glm::dot(nr, nc)) *
                                                         180.0 / 3.14159265358979323846);
      const glm::dvec3 pr = vec(raster.position, x, y);
      a.positionWorstRel = std::max(a.positionWorstRel, glm::length(pr - pc) / glm::length(pc));
    }
  return a;
}

std::string describe(const RayAgreement& a) {
  char buf[640];
  std::snprintf(buf, sizeof buf,
                "coverage mismatch %zu/%zu (%.3f%%, %zu off silhouettes), other surface %zu (%.3f%%); interior %zu: "
                "|dz| worst %.3e (rel %.2e, "
                "%.2f quanta, %.3f of bound), normal worst %.2e deg, position worst rel %.2e",
                a.coverageMismatch, a.pixels, 100.0 * double(a.coverageMismatch) / double(a.pixels),
                a.mismatchOffSilhouette, a.surfaceMismatch, 100.0 * double(a.surfaceMismatch) / double(a.pixels), a.interior, a.zWorstAbs, a.zWorstRelative, a.zWorstQuanta, a.zWorstBoundRatio,
                a.normalWorstDeg, a.positionWorstRel);
  return buf;
}

}  // namespace sao::prepasstest
