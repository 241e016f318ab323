#include "reference.h"

#include <chrono>

namespace sao::viewer {

void Reference::setScene(const scenes::Scene* scene) {
  scene_ = scene;
  rays_scene_.reset();
  image_ = {};
  mask_.clear();
}

// The ray scene of the current scene, built once per scene (setScene forgets it).
Status Reference::ensureRayScene() {
  if (!scene_) return Status::error(StatusCode::InvalidInput, "no scene to trace");
  if (rays_scene_) return Status::success();
  return raytrace::RayScene::create(scene_->mesh, rays_scene_);
}

Status Reference::compute(const scenes::View& view, const Camera& camera, double radius, std::uint32_t rays) {
  const auto t0 = std::chrono::steady_clock::now();
  if (Status s = ensureRayScene(); !s) return s;
  raytrace::Primary primary;
  if (Status s = raytrace::castPrimary(*rays_scene_, view, camera, DepthFormat::D32F, primary); !s) return s;
  raytrace::ReferenceOptions options;
  options.radius = radius;
  options.rays = rays;
  FloatImage ao;
  if (Status s = raytrace::referenceAmbientOcclusion(*rays_scene_, camera, primary, view, options, ao); !s) return s;
  image_ = std::move(ao);
  mask_ = samples::geometryMask(primary.position, camera.guardBand);
  view_ = view;
  projection_ = camera.projection;
  width_ = camera.width;
  height_ = camera.height;
  radius_ = radius;
  rays_ = rays;
  seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return Status::success();
}

Status Reference::castDepth(const scenes::View& view, const Camera& camera, DepthImage& out) {
  if (Status s = ensureRayScene(); !s) return s;
  raytrace::Primary primary;
  if (Status s = raytrace::castPrimary(*rays_scene_, view, camera, DepthFormat::D32F, primary); !s) return s;
  out = std::move(primary.depth);
  return Status::success();
}

bool Reference::matches(const scenes::View& view, const Camera& camera, double radius) const {
  return available() && camera.width == width_ && camera.height == height_ && camera.projection == projection_ &&
         radius == radius_ &&
         view.eye == view_.eye && view.target == view_.target && view.fovyRadians == view_.fovyRadians && view.orthoHeight == view_.orthoHeight &&
         view.nearDistance == view_.nearDistance;
}

samples::ReferenceComparison Reference::compare(const FloatImage& ao) const {
  return samples::compareToReference(ao, image_, mask_);
}

}  // namespace sao::viewer
