// Framing the scene for the part of the window the panel leaves free: what the camera shows over
// the whole window is shown inside the strip beside the panel instead (scaled about the window's
// centre and shifted sideways: an off-axis projection, which the effect, the composite and the
// reference's ray caster all read from Camera::projection).
#pragma once
#include "sao/camera.h"

namespace sao::viewer {

// A vertical strip of the window, as fractions of its width: [x0, x1) within [0, 1].
struct Strip {
  double x0 = 0, x1 = 1;
  bool operator==(const Strip&) const = default;
};

// The wider of the strips left and right of a panel spanning [panelX0, panelX1) (fractions of the
// window's width), or the whole window when the panel is not shown or leaves less than a quarter
// of the width on both sides (a panel that wide is not worth framing around).
Strip freeStrip(bool panelShown, double panelX0, double panelX1);

// Scales camera.projection's x and y by the strip's width and moves the window's centre to the
// strip's centre, so that the whole-window picture lands inside the strip (with more of the scene
// above and below it). The whole window leaves the camera as it is.
void frameInStrip(Camera& camera, Strip strip);

}  // namespace sao::viewer
