// Embree-backed ray casting of a scene: the depth a rasterising prepass would produce (for the
// CPU path and for checking prepasses), camera-space positions and geometric normals, and the
// ray-traced ambient-occlusion reference.
#pragma once
#include <cstdint>
#include <memory>

#include "sao/image.h"
#include "sao/scenes/scene.h"
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
  Hit intersect(glm::dvec3 origin, glm::dvec3 direction, double tFar) const;
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

// Casts the primary rays of `camera` (perspective) for `view`. Rows: row 0 at ndc y = -1.
Status castPrimary(const RayScene& scene, const scenes::View& view, const Camera& camera, DepthFormat format,
                   Primary& out, unsigned threads = 0);

struct ReferenceOptions {
  double radius = 1.0;        // metres (world units)
  std::uint32_t rays = 256;   // cosine-weighted rays per pixel
  std::uint64_t seed = 1;     // results are a pure function of (scene, view, options)
  unsigned threads = 0;
};

// Near-field visibility at one world-space point with unit normal n: the fraction of `rays`
// cosine-weighted rays (origin offset along n by `offset`) that travel `radius` without a hit.
double visibilityAt(const RayScene& scene, glm::dvec3 p, glm::dvec3 n, double radius, std::uint32_t rays,
                    std::uint64_t seed, double offset);

// Near-field ambient occlusion over the AO viewport (the depth input minus its guard band): the
// fraction of cosine-weighted rays from each visible point (offset along its geometric normal by
// 1e-4 * distance) that travel `radius` without a hit. Sky pixels are 1.
Status referenceAmbientOcclusion(const RayScene& scene, const Camera& camera, const Primary& primary,
                                 const scenes::View& view, const ReferenceOptions& options, FloatImage& ao);

}  // namespace sao::raytrace
