// Orbit and fly camera over a scenes::View: drag to rotate (orbit about the target, or look
// around in fly mode), right/middle drag to pan, wheel to dolly, WASD to move, Q/E down/up, Shift
// to go faster.
#pragma once
#include <glm/glm.hpp>

#include "sao/scenes/scene.h"
#include "window.h"

namespace sao::viewer {

class CameraController {
 public:
  enum class Mode { Orbit, Fly };

  void reset(const scenes::View& view);  // eye, target, field of view (or view height) and near plane
  // The scene's bounding box: an orthographic view's far plane lies just beyond it.
  void setSceneBounds(glm::dvec3 lo, glm::dvec3 hi) { boundsMin_ = lo, boundsMax_ = hi; }
  // Applies this frame's input (pass an empty Input and keys=false while the UI has the mouse).
  void update(const Input& input, const Window& window, bool keys, double seconds);
  scenes::View view() const;             // the current view (y up)
  // Turns the eye about the vertical through the orbit target by `radians` (a scripted orbit).
  void orbitBy(double radians);
  bool changedSince(const scenes::View& v) const;

  Mode mode = Mode::Orbit;
  double speed = 2.0;  // metres per second for WASD (Shift: 4x)
  // Orthographic (O key): the view height is what the field of view spans at the target distance,
  // so the toggle keeps the framing of the target; the orbit wheel then zooms.
  bool orthographic = false;

 private:
  glm::dvec3 forward() const;
  scenes::View base_;
  glm::dvec3 eye_{0, 1, 5};
  double yaw_ = 0, pitch_ = 0, distance_ = 5;
  glm::dvec3 boundsMin_{-1}, boundsMax_{1};
};

}  // namespace sao::viewer
