// Camera paths: a scene view moved over frames, for measuring AO while the camera moves (flicker,
// disocclusion; issue 18 [temporal]). Each path is a deterministic function of the base view and
// the frame number: frame 0 is the base view's start of the path, frame N-1 its end.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "sao/scenes/scene.h"

namespace sao::scenes {

enum class PathKind : std::uint8_t {
  Orbit,   // the eye turns about the vertical through the target, 30 degrees in all (-15 to +15)
  Dolly,   // the eye moves straight at the target, from the base distance to 60 % of it
  Strafe,  // eye and target move together sideways (horizontal, across the view), 30 % of the
           // eye-target distance in all (-15 % to +15 %), past what lies between them
};

// "orbit", "dolly", "strafe", in PathKind order.
std::span<const std::string_view> pathNames();
std::string_view toString(PathKind kind);
// The path of a name in pathNames(); nullopt for any other word.
std::optional<PathKind> parsePathKind(std::string_view name);

// The view of `frame` (0 .. frames-1) along the path: the base view's projection, name and up, a
// moved eye (and target, for Strafe). Orbit and Strafe pass through the base view in their middle,
// Dolly starts there. A single frame is the base view.
// Orbit and Strafe need a view direction that is not vertical (the scenes' views never are).
View pathView(const View& base, PathKind kind, std::uint32_t frame, std::uint32_t frames);

}  // namespace sao::scenes
