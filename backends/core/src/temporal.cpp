#include "sao/temporal.h"

#include <string>

namespace sao {

Status prepareTemporalFrame(const TemporalHistory& h, const Settings& settings, const Camera& current,
                            const Camera* previous, bool reset, ParamBlock& block) {
  if (previous) {
    auto bad = [](const std::string& why) {
      return Status::error(StatusCode::InvalidCamera, "Inputs::previousCamera " + why);
    };
    DepthModel model;
    if (Status st = analyze(*previous, model); !st) return bad("is invalid: " + st.message);
    if (!previous->view) return bad("has no Camera::view: the history cannot be reprojected without it");
    if (previous->width != current.width || previous->height != current.height ||
        previous->guardBand != current.guardBand || previous->kind != current.kind)
      return bad("differs from this frame's camera in size, guard band or projection kind: the history of "
                 "another plan cannot be reused (set Inputs::resetHistory)");
  }
  // The plan's rule (sao/frame.h) lets a camera change its projection kind; the history cannot
  // follow (its reprojection takes both cameras as the current one's kind): start again.
  const bool reuse = !reset && settings.temporal && h.holdsFrame && h.settings == settings && h.camera.kind == current.kind;
  setPreviousFrame(block, current, reuse ? (previous ? previous : &h.camera) : nullptr);
  return Status::success();
}

void finishTemporalFrame(TemporalHistory& h, const Settings& settings, const Camera& current) {
  h.holdsFrame = true;
  h.parity ^= 1u;
  h.camera = current;
  h.settings = settings;
}

}  // namespace sao
