#include "camera_control.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

namespace sao::viewer {
namespace {
constexpr double kMaxPitch = 1.55;
}

void CameraController::reset(const scenes::View& view) {
  base_ = view;
  eye_ = view.eye;
  const glm::dvec3 d = view.target - view.eye;
  distance_ = std::max(glm::length(d), 1e-3);
  const glm::dvec3 f = d / distance_;
  pitch_ = std::asin(std::clamp(f.y, -1.0, 1.0));
  yaw_ = std::atan2(f.x, -f.z);
  speed = std::clamp(distance_ * 0.5, 0.5, 20.0);
  // An orthographic view keeps its height: the field of view that spans it at the target distance.
  orthographic = view.orthographic();
  if (orthographic) base_.fovyRadians = 2.0 * std::atan(0.5 * view.orthoHeight / distance_);
}

glm::dvec3 CameraController::forward() const {
  return {std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_), -std::cos(pitch_) * std::cos(yaw_)};
}

void CameraController::orbitBy(double radians) {
  const glm::dvec3 target = eye_ + forward() * distance_;
  yaw_ += radians;
  eye_ = target - forward() * distance_;
}

void CameraController::update(const Input& in, const Window& window, bool keys, double seconds) {
  const glm::dvec3 target = eye_ + forward() * distance_;
  if (in.left && (in.mouseDelta.x != 0 || in.mouseDelta.y != 0)) {
    yaw_ += in.mouseDelta.x * 0.005;
    pitch_ = std::clamp(pitch_ - in.mouseDelta.y * 0.005, -kMaxPitch, kMaxPitch);
    // Orbit keeps the target and moves the eye; fly keeps the eye.
    if (mode == Mode::Orbit) eye_ = target - forward() * distance_;
  }
  const glm::dvec3 f = forward();
  const glm::dvec3 right = glm::normalize(glm::cross(f, glm::dvec3(0, 1, 0)));
  const glm::dvec3 up = glm::cross(right, f);
  if (in.right || in.middle) {
    const double k = distance_ * 0.0015;
    eye_ += -right * in.mouseDelta.x * k + up * in.mouseDelta.y * k;
  }
  if (in.scroll != 0) {
    const double newDistance = std::clamp(distance_ * std::pow(0.9, in.scroll), 0.05, 1000.0);
    if (mode == Mode::Orbit) eye_ += f * (distance_ - newDistance);
    else eye_ += f * (distance_ - newDistance) * 0.5;  // fly: wheel steps forward, keeps the distance
    if (mode == Mode::Orbit) distance_ = newDistance;
  }
  if (keys) {
    glm::dvec3 move(0);
    if (window.keyDown(GLFW_KEY_W)) move += f;
    if (window.keyDown(GLFW_KEY_S)) move -= f;
    if (window.keyDown(GLFW_KEY_D)) move += right;
    if (window.keyDown(GLFW_KEY_A)) move -= right;
    if (window.keyDown(GLFW_KEY_E)) move += glm::dvec3(0, 1, 0);
    if (window.keyDown(GLFW_KEY_Q)) move -= glm::dvec3(0, 1, 0);
    const bool fast = window.keyDown(GLFW_KEY_LEFT_SHIFT) || window.keyDown(GLFW_KEY_RIGHT_SHIFT);
    if (glm::dot(move, move) > 0) eye_ += glm::normalize(move) * speed * (fast ? 4.0 : 1.0) * seconds;
  }
}

scenes::View CameraController::view() const {
  scenes::View v = base_;
  v.eye = eye_;
  v.target = eye_ + forward() * distance_;
  v.up = {0, 1, 0};
  v.orthoHeight = 0;
  // As tall as the field of view spans at the target; the eye pulled back clear of the scene.
  if (orthographic) return scenes::toOrthographic(v, boundsMin_, boundsMax_);
  return v;
}

bool CameraController::changedSince(const scenes::View& v) const {
  const scenes::View c = view();
  return glm::length(c.eye - v.eye) > 1e-9 || glm::length(c.target - v.target) > 1e-9 ||
         c.fovyRadians != v.fovyRadians || c.nearDistance != v.nearDistance || c.orthoHeight != v.orthoHeight;
}

}  // namespace sao::viewer
