#include "sao/raytrace/raytrace.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "sampling.h"
#include "sao/cpu/parallel.h"

namespace sao::raytrace {

struct RayScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

RayScene::~RayScene() = default;

Status RayScene::create(const scenes::Mesh& mesh, std::unique_ptr<RayScene>& out) {
  if (mesh.triangleCount() == 0) return Status::error(StatusCode::InvalidInput, "the scene has no triangles");
  for (auto i : mesh.indices)
    if (i >= mesh.positions.size())
      return Status::error(StatusCode::InvalidInput, "mesh index " + std::to_string(i) + " is out of range");
  std::unique_ptr<RayScene> rs(new RayScene());
  rs->impl_ = std::make_unique<Impl>();
  Impl& im = *rs->impl_;
  im.device = rtcNewDevice(nullptr);
  if (!im.device) return Status::error(StatusCode::DriverError, "Embree could not create a device");
  im.scene = rtcNewScene(im.device);
  RTCGeometry geom = rtcNewGeometry(im.device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), mesh.positions.size()));
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(unsigned), mesh.triangleCount()));
  if (!v || !idx) {
    rtcReleaseGeometry(geom);
    return Status::error(StatusCode::DriverError, "Embree could not allocate the mesh buffers");
  }
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    v[3 * i] = mesh.positions[i].x;
    v[3 * i + 1] = mesh.positions[i].y;
    v[3 * i + 2] = mesh.positions[i].z;
  }
  std::copy(mesh.indices.begin(), mesh.indices.end(), idx);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(im.scene, geom);
  rtcReleaseGeometry(geom);
  rtcSetSceneBuildQuality(im.scene, RTC_BUILD_QUALITY_HIGH);
  rtcCommitScene(im.scene);
  if (rtcGetDeviceError(im.device) != RTC_ERROR_NONE)
    return Status::error(StatusCode::DriverError, "Embree failed to build the scene");
  out = std::move(rs);
  return Status::success();
}

RayScene::Hit RayScene::intersect(glm::dvec3 o, glm::dvec3 d, double tFar, double tNear) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh{};
  rh.ray.org_x = float(o.x); rh.ray.org_y = float(o.y); rh.ray.org_z = float(o.z);
  rh.ray.dir_x = float(d.x); rh.ray.dir_y = float(d.y); rh.ray.dir_z = float(d.z);
  rh.ray.tnear = float(tNear);
  rh.ray.tfar = float(tFar);
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &ctx, &rh);
  Hit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.hit = true;
  h.t = rh.ray.tfar;
  h.normal = glm::normalize(glm::dvec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
  return h;
}

bool RayScene::occluded(glm::dvec3 o, glm::dvec3 d, double tFar) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r{};
  r.org_x = float(o.x); r.org_y = float(o.y); r.org_z = float(o.z);
  r.dir_x = float(d.x); r.dir_y = float(d.y); r.dir_z = float(d.z);
  r.tnear = 0.0f;
  r.tfar = float(tFar);
  r.mask = 0xffffffffu;
  rtcOccluded1(impl_->scene, &ctx, &r);
  return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

namespace {

using cpu::parallelFor;

double P(const Camera& c, int row, int col) { return c.projection[col * 4 + row]; }

// The camera-space primary ray through the centre of depth-input texel (x, y), with direction
// z = -1 (so the ray parameter t is -z): perspective rays leave the eye; orthographic rays are
// parallel, from the point of the plane z = 0 (the view plane through the eye) under the texel.
struct CameraRay {
  glm::dvec3 origin{0, 0, 0};
  glm::dvec3 direction{0, 0, -1};
};

CameraRay cameraRay(const Camera& c, std::uint32_t x, std::uint32_t y) {
  const double ndcX = 2.0 * (double(x) - c.guardBand + 0.5) / c.width - 1.0;
  const double ndcY = (c.flipY ? -1.0 : 1.0) * (2.0 * (double(y) - c.guardBand + 0.5) / c.height - 1.0);
  CameraRay r;
  if (c.kind == ProjectionKind::Orthographic)  // ndc = P00 x + P03 (no division by -z)
    r.origin = {(ndcX - P(c, 0, 3)) / P(c, 0, 0), (ndcY - P(c, 1, 3)) / P(c, 1, 1), 0.0};
  else
    r.direction = {(ndcX + P(c, 0, 2)) / P(c, 0, 0), (ndcY + P(c, 1, 2)) / P(c, 1, 1), -1.0};
  return r;
}

double windowDepth(const Camera& c, double z) {
  const double ndc = c.kind == ProjectionKind::Orthographic ? P(c, 2, 2) * z + P(c, 2, 3)
                                                            : (P(c, 2, 2) * z + P(c, 2, 3)) / (-z);
  return c.clipDepth == ClipDepth::ZeroToOne ? ndc : 0.5 * ndc + 0.5;
}

// The layers a rasteriser's depth prepass (layer 1) and a depth-peeling prepass with a minimum
// separation (layer 2) would produce. `minSeparation` < 0 casts layer 1; otherwise layer 2: per
// texel, the first hit whose camera-space z lies at least minSeparation behind layer 1's (the
// ray's parameter t is -z, since the camera-space direction has z = -1).
Status castLayer(const RayScene& scene, const scenes::View& view, const Camera& camera, DepthFormat format,
                 double minSeparation, Primary& out, unsigned threads) {
  DepthModel model;
  if (Status s = analyze(camera, model); !s) return s;
  const Extent e{camera.width + 2 * camera.guardBand, camera.height + 2 * camera.guardBand};
  const glm::dmat4 toCamera = scenes::viewMatrix(view);
  const glm::dmat4 toWorld = glm::inverse(toCamera);
  const double clearDepth = camera.reversedZ ? 0.0 : 1.0;
  const double farT = std::isinf(model.farDistance) ? std::numeric_limits<float>::max() : model.farDistance;

  out.depth.extent = e;
  out.depth.format = format;
  out.depth.texels.assign(std::size_t(e.width) * e.height, encodeDepth(format, clearDepth));
  if (format == DepthFormat::LinearZ) std::fill(out.depth.texels.begin(), out.depth.texels.end(), encodeDepth(format, 0.0));
  out.position = FloatImage(e, 4, 0.0f);
  out.normal = FloatImage(e, 4, 0.0f);
  parallelFor(e.height, threads, [&](std::uint32_t y) {
    for (std::uint32_t x = 0; x < e.width; ++x) {
      const CameraRay ray = cameraRay(camera, x, y);
      const glm::dvec3 originWorld = glm::dvec3(toWorld * glm::dvec4(ray.origin, 1.0));
      const glm::dvec3 dirWorld = glm::dvec3(toWorld * glm::dvec4(ray.direction, 0.0));
      auto hit = scene.intersect(originWorld, dirWorld, farT);
      // Depth clipping as a rasteriser would: nothing nearer than the near plane or beyond the far.
      if (!hit.hit || hit.t < model.nearDistance) continue;
      if (minSeparation >= 0) {
        const double tNear = hit.t + minSeparation;
        if (!(tNear < farT)) continue;
        hit = scene.intersect(originWorld, dirWorld, farT, tNear);
        if (!hit.hit) continue;
      }
      const glm::dvec3 pc = ray.origin + ray.direction * hit.t;
      glm::dvec3 nc = glm::normalize(glm::dvec3(toCamera * glm::dvec4(hit.normal, 0.0)));
      if (glm::dot(nc, ray.direction) > 0) nc = -nc;  // face the camera
      const std::size_t i = std::size_t(y) * e.width + x;
      out.depth.texels[i] = format == DepthFormat::LinearZ ? encodeDepth(format, pc.z) : encodeDepth(format, windowDepth(camera, pc.z));
      out.position.at(x, y, 0) = float(pc.x);
      out.position.at(x, y, 1) = float(pc.y);
      out.position.at(x, y, 2) = float(pc.z);
      out.position.at(x, y, 3) = 1.0f;
      out.normal.at(x, y, 0) = float(nc.x);
      out.normal.at(x, y, 1) = float(nc.y);
      out.normal.at(x, y, 2) = float(nc.z);
    }
  });
  return Status::success();
}

}  // namespace

Status castPrimary(const RayScene& scene, const scenes::View& view, const Camera& camera, DepthFormat format,
                   Primary& out, unsigned threads) {
  return castLayer(scene, view, camera, format, -1.0, out, threads);
}

Status castSecondLayer(const RayScene& scene, const scenes::View& view, const Camera& camera, DepthFormat format,
                       double minSeparation, Primary& out, unsigned threads) {
  if (!(minSeparation > 0) || !std::isfinite(minSeparation))
    return Status::error(StatusCode::InvalidInput, "castSecondLayer: the minimum separation must be a finite number > 0, not " +
                                                       std::to_string(minSeparation));
  return castLayer(scene, view, camera, format, minSeparation, out, threads);
}

namespace {

// `rays` cosine-weighted rays about n from p (offset along n by `offset`), seeded by `seed`:
// perRay(direction, clear) with clear true when the ray travels `radius` without a hit.
template <typename PerRay>
void traceCosineRays(const RayScene& scene, glm::dvec3 p, glm::dvec3 n, double radius, std::uint32_t rays,
                     std::uint64_t seed, double offset, PerRay perRay) {
  const detail::Frame frame(n);
  const glm::dvec3 origin = p + n * offset;
  std::uint64_t state = seed;
  detail::splitmix(state);
  for (std::uint32_t r = 0; r < rays; ++r) {
    double cosTheta = 0;
    const glm::dvec3 dir = detail::cosineDirection(frame, state, cosTheta);
    perRay(dir, !scene.occluded(origin, dir, radius));
  }
}

}  // namespace

double visibilityAt(const RayScene& scene, glm::dvec3 p, glm::dvec3 n, double radius, std::uint32_t rays,
                    std::uint64_t seed, double offset) {
  std::uint32_t open = 0;
  traceCosineRays(scene, p, n, radius, rays, seed, offset, [&](glm::dvec3, bool clear) { open += clear; });
  return rays ? double(open) / rays : 1.0;
}

glm::dvec3 bentNormalAt(const RayScene& scene, glm::dvec3 p, glm::dvec3 n, double radius, std::uint32_t rays,
                        std::uint64_t seed, double offset) {
  glm::dvec3 sum(0.0);
  traceCosineRays(scene, p, n, radius, rays, seed, offset, [&](glm::dvec3 dir, bool clear) {
    if (clear) sum += dir;
  });
  const double l = glm::length(sum);
  return l > 0 ? sum / l : n;
}

namespace {

// The per-pixel references' loop: for each AO viewport pixel with geometry, its visible point p and
// geometric normal n in world space, its seed and its ray origin's offset along n, in parallel rows
// (o.progress after each). Checks the options and the primary images first.
template <typename PerPixel>
Status forEachReferencePixel(const Camera& camera, const Primary& primary, const scenes::View& view,
                             const ReferenceOptions& o, PerPixel perPixel) {
  if (!(o.radius > 0) || !std::isfinite(o.radius))
    return Status::error(StatusCode::InvalidInput, "reference radius must be a finite number > 0");
  if (o.rays == 0) return Status::error(StatusCode::InvalidInput, "reference needs at least one ray per pixel");
  const Extent input{camera.width + 2 * camera.guardBand, camera.height + 2 * camera.guardBand};
  if (primary.position.extent != input || primary.normal.extent != input)
    return Status::error(StatusCode::InvalidInput, "primary images do not match the camera's depth extent");
  const glm::dmat4 toWorld = glm::inverse(scenes::viewMatrix(view));
  const std::uint32_t g = camera.guardBand;
  std::mutex progressMutex;
  std::uint32_t rowsDone = 0;
  parallelFor(camera.height, o.threads, [&](std::uint32_t y) {
    for (std::uint32_t x = 0; x < camera.width; ++x) {
      if (primary.position.at(x + g, y + g, 3) == 0.0f) continue;  // sky
      const glm::dvec3 pc(primary.position.at(x + g, y + g, 0), primary.position.at(x + g, y + g, 1),
                          primary.position.at(x + g, y + g, 2));
      const glm::dvec3 ncam(primary.normal.at(x + g, y + g, 0), primary.normal.at(x + g, y + g, 1),
                            primary.normal.at(x + g, y + g, 2));
      const glm::dvec3 p = glm::dvec3(toWorld * glm::dvec4(pc, 1.0));
      const glm::dvec3 n = glm::normalize(glm::dvec3(toWorld * glm::dvec4(ncam, 0.0)));
      perPixel(x, y, p, n, detail::pixelSeed(o.seed, x, y), 1e-4 * std::max(1.0, glm::length(pc)));
    }
    if (o.progress) {
      std::lock_guard lock(progressMutex);
      o.progress(++rowsDone, camera.height);
    }
  });
  return Status::success();
}

}  // namespace

Status referenceBentNormals(const RayScene& scene, const Camera& camera, const Primary& primary,
                            const scenes::View& view, const ReferenceOptions& o, FloatImage& bent) {
  const glm::dmat4 fromWorld = scenes::viewMatrix(view);
  bent = FloatImage({camera.width, camera.height}, 3, 0.0f);
  return forEachReferencePixel(camera, primary, view, o, [&](std::uint32_t x, std::uint32_t y, glm::dvec3 p, glm::dvec3 n,
                                                              std::uint64_t seed, double offset) {
    const glm::dvec3 b = bentNormalAt(scene, p, n, o.radius, o.rays, seed, offset);
    const glm::dvec3 bc = glm::normalize(glm::dvec3(fromWorld * glm::dvec4(b, 0.0)));
    for (std::uint32_t c = 0; c < 3; ++c) bent.at(x, y, c) = float(bc[int(c)]);
  });
}

Status referenceAmbientOcclusion(const RayScene& scene, const Camera& camera, const Primary& primary,
                                 const scenes::View& view, const ReferenceOptions& o, FloatImage& ao) {
  ao = FloatImage({camera.width, camera.height}, 1, 1.0f);
  return forEachReferencePixel(camera, primary, view, o, [&](std::uint32_t x, std::uint32_t y, glm::dvec3 p, glm::dvec3 n,
                                                              std::uint64_t seed, double offset) {
    ao.at(x, y) = float(visibilityAt(scene, p, n, o.radius, o.rays, seed, offset));
  });
}

}  // namespace sao::raytrace
