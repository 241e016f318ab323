// The error-vs-reference view's data: the Embree ray-traced near-field AO for one view (computed
// on request, low ray count), and the AO's error against it.
#pragma once
#include <array>
#include <memory>
#include <vector>

#include "sao/image.h"
#include "sao/raytrace/raytrace.h"
#include "sao/samples/metrics.h"
#include "sao/scenes/scene.h"

namespace sao::viewer {

class Reference {
 public:
  void setScene(const scenes::Scene* scene);  // forgets the reference and the ray scene
  // Traces `rays` cosine-weighted rays per pixel within `radius` (scene units) for the view and camera.
  Status compute(const scenes::View& view, const Camera& camera, double radius, std::uint32_t rays);
  bool available() const { return !image_.data.empty(); }
  // Whether the reference belongs to this view, camera (size and projection: the panel's framing
  // shifts it) and radius.
  bool matches(const scenes::View& view, const Camera& camera, double radius) const;
  // The depth a prepass draws for the view and camera (D32F, ray cast on the reference's ray
  // scene): the scale check's input (sao/samples/scale_warnings.h).
  Status castDepth(const scenes::View& view, const Camera& camera, DepthImage& out);
  const FloatImage& image() const { return image_; }  // AO extent, row 0 at ndc y = -1
  double seconds() const { return seconds_; }
  std::uint32_t rays() const { return rays_; }
  // RMSE, bias, ... of `ao` (1 channel, the same extent) over the pixels with geometry.
  samples::ReferenceComparison compare(const FloatImage& ao) const;

 private:
  Status ensureRayScene();
  const scenes::Scene* scene_ = nullptr;
  std::unique_ptr<raytrace::RayScene> rays_scene_;
  FloatImage image_;
  std::vector<unsigned char> mask_;
  scenes::View view_;
  std::array<double, 16> projection_{};
  std::uint32_t width_ = 0, height_ = 0, rays_ = 0;
  double radius_ = 0, seconds_ = 0;
};

}  // namespace sao::viewer
