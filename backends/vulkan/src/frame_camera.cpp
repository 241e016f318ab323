// Inputs::camera: a camera per record (TAA jitter, an animated field of view, a new view rotation)
// without update(). Its parameter block goes into the record's ring slot only; the plan, the
// images and the pipelines stay those of Config::camera, so the camera must plan exactly as that
// one does: core's one rule, sao::checkCameraKeepsPlan (sao/frame.h), which allocates nothing when
// the camera keeps the plan (record() must not allocate; sao::plan() would). The normals encoding
// must still fit Config::normalsFormat's channels (create()'s check).
#include <string>

#include "effect_impl.h"

namespace sao::vk {

Status cameraParams(const EffectState& e, const Camera& camera, ParamBlock& out) {
  const Config& c = e.config;
  // Messages are built only on the error paths.
  auto invalid = [](Status st) { return Status::error(st.code, "record(): Inputs::camera: " + st.message); };
  if (Status st = computeConstants(c.settings, camera, e.planInputs.depthEncoding, out); !st) return invalid(st);
  if (Status st = checkNormalsFormat(c.normalsFormat, camera.normalsEncoding); !st) return invalid(st);
  if (Status st = checkCameraKeepsPlan(c.settings, c.camera, camera); !st)
    return Status::error(st.code, "record(): Inputs::camera " + st.message + "; the plan is Config::camera's: call update()");
  return Status::success();
}

Status recordParams(EffectState& e, const Inputs& inputs, ParamBlock& out, bool& own) {
  own = inputs.camera != nullptr;
  if (inputs.camera) {
    if (Status st = cameraParams(e, *inputs.camera, out); !st) return st;
  }
  e.historyValid = false;
  if (!e.config.settings.temporal) return Status::success();
  if (!own) out = e.params;
  own = true;
  const Camera& camera = inputs.camera ? *inputs.camera : e.config.camera;
  if (Status st = prepareTemporalFrame(e.temporal, e.config.settings, camera, inputs.previousCamera,
                                       inputs.resetHistory, out);
      !st)
    return st;
  e.historyValid = out.history_valid != 0;
  return Status::success();
}

void recordDone(EffectState& e, const Inputs& inputs) {
  if (!e.config.settings.temporal) return;
  finishTemporalFrame(e.temporal, e.config.settings, inputs.camera ? *inputs.camera : e.config.camera);
}

}  // namespace sao::vk
