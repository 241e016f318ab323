// Temporal accumulation (the `temporal` setting, the TEMPORAL variant of ao_sample): what an
// effect keeps between frames, and the one contract every backend follows for when the history
// may be reused (docs/effect-math.md, "Temporal").
//
// The history is two images (the effect's `history` resource, history=true): frame t writes copy
// `parity` and reads copy parity ^ 1, which frame t - 1 wrote. It is reused only when the frame
// before ran on the same effect with the same settings and plan: create(), a settings change, a
// new plan (a resize, new kinds of input) and Inputs::resetHistory (a camera cut) start again
// from this frame alone. The previous frame's camera is the one that frame ran with, unless the
// caller names another (Inputs::previousCamera); it must plan as this frame's camera does.
#pragma once
#include <cstdint>

#include "sao/camera.h"
#include "sao/constants.h"
#include "sao/settings.h"

namespace sao {

struct TemporalHistory {
  bool holdsFrame = false;   // a frame wrote copy parity ^ 1 since the last reset
  std::uint32_t parity = 0;  // the copy the next frame writes
  Camera camera;             // the camera of the frame that wrote it
  Settings settings;         // ... and its settings (a change starts again)
};

// The copy of an owned image a binding or hazard names this frame: for a history, the previous
// frame's for a read (ScheduledBinding::previousFrame) and this frame's otherwise; 0 for any other
// image (it has one).
inline std::uint32_t imageCopy(std::uint32_t parity, gen::ResourceId id, bool previousFrame) {
  if (!gen::kResources[static_cast<std::size_t>(id)].history) return 0;
  return previousFrame ? parity ^ 1u : parity;
}

// Fills the block's previous-frame members for the frame about to run with `current` and
// `settings`: from `previous` (the caller's) or else the history's own camera, or none (history_valid
// = 0) after a reset, a settings change, a history camera of another projection kind or with
// `reset`. Refuses (InvalidCamera, naming `previousCamera`) a previous camera that is invalid, lacks
// Camera::view, or differs from `current` in size, guard band or projection kind (the history's
// reprojection takes both as the current one's kind). Allocates nothing.
Status prepareTemporalFrame(const TemporalHistory& h, const Settings& settings, const Camera& current,
                            const Camera* previous, bool reset, ParamBlock& block);

// After the frame's commands were issued: it wrote copy h.parity with `current`.
void finishTemporalFrame(TemporalHistory& h, const Settings& settings, const Camera& current);

}  // namespace sao
