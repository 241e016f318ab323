// Embree-backed ray casting of a scene: the depth a rasterising prepass would produce (for the
// CPU path and for checking prepasses), a second depth layer, camera-space positions and geometric
// normals, and the two ray-traced references: near-field ambient occlusion and the AlchemyAO
// obscurance integral that the effect's estimator approximates (docs/reference.md).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>

#include "sao/image.h"
#include "sao/scenes/scene.h"
#include "sao/settings.h"
#include "sao/status.h"

namespace sao::raytrace {

class RayScene {
 public:
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // Builds the acceleration structure; InvalidInput for an empty mesh, DriverError if Embree fails.
  static Status create(const scenes::Mesh& mesh, std::unique_ptr<RayScene>& out);

  struct Hit {
    bool hit = false;
    double t = 0;
    glm::dvec3 normal{0, 0, 0};  // geometric, unit, world space (as wound)
  };
  // The first hit with tNear <= t <= tFar (t in units of |direction|).
  Hit intersect(glm::dvec3 origin, glm::dvec3 direction, double tFar, double tNear = 0) const;
  bool occluded(glm::dvec3 origin, glm::dvec3 direction, double tFar) const;

 private:
  RayScene() = default;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// What the camera sees, one sample at each texel centre of the depth input (viewport + guard band).
struct Primary {
  DepthImage depth;        // quantised to the requested format (clear value where nothing is hit)
  FloatImage position;     // 4 channels: camera-space x, y, z, 1 (w = 0 where nothing is hit)
  FloatImage normal;       // 4 channels: camera-space geometric normal facing the camera, 0
};

// Casts the primary rays of `camera` for `view`: from the eye (perspective) or parallel, from the
// view plane through the eye (orthographic). Rows: row 0 at ndc y = -1.
Status castPrimary(const RayScene& scene, const scenes::View& view, const Camera& camera, DepthFormat format,
                   Primary& out, unsigned threads = 0);

// The second depth layer of a deep G-buffer, by ray casting: per texel, the primary ray continued
// past its first hit (the one castPrimary reports) to the first surface whose camera-space z is at
// least `minSeparation` (view units, > 0) behind it. Front and back faces both count (no culling).
// Texels without a first hit, or with nothing behind it, hold the clear value (w = 0), as in
// castPrimary. InvalidInput for a separation that is not finite and > 0.
Status castSecondLayer(const RayScene& scene, const scenes::View& view, const Camera& camera, DepthFormat format,
                       double minSeparation, Primary& out, unsigned threads = 0);

struct ReferenceOptions {
  double radius = 1.0;        // metres (world units)
  std::uint32_t rays = 256;   // cosine-weighted rays per pixel
  std::uint64_t seed = 1;     // results are a pure function of (scene, view, options)
  unsigned threads = 0;
  // Optional: called after each finished row with (rows done, rows), from the threads that trace
  // the rows (the caller's among them) but never two calls at once. For progress reports; it must
  // not throw.
  std::function<void(std::uint32_t, std::uint32_t)> progress;
};

// Near-field visibility at one world-space point with unit normal n: the fraction of `rays`
// cosine-weighted rays (origin offset along n by `offset`) that travel `radius` without a hit.
double visibilityAt(const RayScene& scene, glm::dvec3 p, glm::dvec3 n, double radius, std::uint32_t rays,
                    std::uint64_t seed, double offset);

// The bent normal at the same point, from the same rays as visibilityAt (same seed and offset):
// the mean direction of the cosine-weighted rays that travel `radius` without a hit, normalised,
// or n when none does. Its expectation is the cosine-weighted mean unoccluded direction, the one
// the effect's bent_normals estimates (docs/effect-math.md 5.10).
glm::dvec3 bentNormalAt(const RayScene& scene, glm::dvec3 p, glm::dvec3 n, double radius, std::uint32_t rays,
                        std::uint64_t seed, double offset);

// referenceAmbientOcclusion's bent normals: camera space, 3 channels, per AO viewport pixel (the
// same rays per pixel as its visibility); 0 for sky.
Status referenceBentNormals(const RayScene& scene, const Camera& camera, const Primary& primary,
                            const scenes::View& view, const ReferenceOptions& options, FloatImage& bent);

// Near-field ambient occlusion over the AO viewport (the depth input minus its guard band): the
// fraction of cosine-weighted rays from each visible point (offset along its geometric normal by
// 1e-4 * distance) that travel `radius` without a hit. Sky pixels are 1.
Status referenceAmbientOcclusion(const RayScene& scene, const Camera& camera, const Primary& primary,
                                 const scenes::View& view, const ReferenceOptions& options, FloatImage& ao);

// The settings of the effect's estimator (AlchemyAO eq. 10) that the obscurance reference uses, in
// the effect's units: metres, converted to view units with Camera::metersToViewUnits u.
struct ObscuranceOptions {
  double radius = 1.0;      // r, metres: only occluders closer than r count
  double intensity = 1.0;   // sigma, unitless (the effect's 2*sigma*r/s, r in view units: the terms are 1/length)
  double bias = 0.02;       // beta, unitless: the numerator is v.n + z_C*beta
  double epsilon = 1e-4;    // epsilon, square metres, added to v.v
  double contrast = 1.0;    // k: the output is clamp(1 - obscurance, 0, 1)^k
  std::uint32_t rays = 256; // cosine-weighted rays per pixel
  std::uint64_t seed = 1;   // results are a pure function of (scene, view, options), not of threads
  unsigned threads = 0;
};

// The options matching effect settings `s` (radius, intensity, bias, epsilon, contrast).
ObscuranceOptions obscuranceOptions(const Settings& s, std::uint32_t rays, std::uint64_t seed = 1);

// The obscurance integral at camera-space-z `zC` point p (world space, on a surface, unit normal n),
// all lengths in view units (r and epsilon already scaled by u, sigma by r):
//   O = (sigma/pi) * Integral over the hemisphere of H(r - t) max(0, t cos + zC beta) / (t^2 + eps) dw
// with t the distance to the first hit along w and cos = w.n, estimated from `rays` cosine-weighted
// rays (mean of sigma H(r - t) max(0, t cos + zC beta) / (cos (t^2 + eps)); derivation in
// docs/reference.md). Rays start at p and ignore hits nearer than `tMin`. Not clamped; 0 with no rays.
double obscuranceAt(const RayScene& scene, glm::dvec3 p, glm::dvec3 n, double zC, double radius, double intensity,
                    double bias, double epsilon, std::uint32_t rays, std::uint64_t seed, double tMin);

// The AlchemyAO obscurance reference over the AO viewport, comparable with the effect's output:
// per pixel with geometry, O from obscuranceAt at the visible point with its geometric normal
// (tMin = 1e-4 * max(1, distance to the eye)), then clamp(1 - O, 0, 1)^k. The clamp applies to
// the converged mean, not to each ray. Sky pixels are 1. InvalidInput for settings outside their
// ranges (radius, epsilon > 0; intensity, bias >= 0; contrast > 0; rays > 0), or primary images
// that do not match the camera.
Status referenceObscurance(const RayScene& scene, const Camera& camera, const Primary& primary,
                           const scenes::View& view, const ObscuranceOptions& options, FloatImage& ao);

}  // namespace sao::raytrace
