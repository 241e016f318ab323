// Inputs::camera: a camera per record (TAA jitter, an animated field of view, a new view rotation)
// without update(). Its parameter block goes into the record's ring slot only; the plan, the
// images and the pipelines stay those of Config::camera, so the camera must plan exactly as that
// one does.
//
// What is compared, and why not sao::plan(): plan() allocates (its passes, aliases and images are
// std::vectors), and record() must not. The camera reaches the plan through three calls only
// (backends/core/src/plan.cpp):
//  * analyze(): validity, nothing planned; computeConstants() runs the same check (and create()'s
//    normals-encoding check), so an invalid camera gets create()'s code and message;
//  * checkExtents(): width, height and guardBand give the input and AO extents, and through them
//    every image's extent: compared with Config::camera's;
//  * mipLevelsNeeded(): the csz levels (the csz image's levels and the mips pass's dispatches),
//    from the projection scale, the near distance, the projection kind, metersToViewUnits and the
//    size; computeConstants() writes the same value minus one as max_mip: compared with
//    plan.cszLevels.
// The variants (and so the pipelines) come from the settings and PlanInputs (the depth encoding
// from Config::depthFormat, normals, second layer, output), never from the camera: the projection
// kind, clip range, reversed-Z, flipY and normals encoding are block values. The encoding must still
// fit Config::normalsFormat's channels (create()'s check).
#include <string>

#include "effect_impl.h"

namespace sao::vk {

Status cameraParams(const EffectState& e, const Camera& camera, ParamBlock& out) {
  const Config& c = e.config;
  // Messages are built only on the error paths.
  auto invalid = [](Status st) { return Status::error(st.code, "record(): Inputs::camera: " + st.message); };
  if (Status st = computeConstants(c.settings, camera, depthEncodingOf(c.depthFormat), out); !st) return invalid(st);
  if (Status st = checkNormalsFormat(c.normalsFormat, camera.normalsEncoding); !st) return invalid(st);
  const Camera& planned = c.camera;
  if (camera.width != planned.width || camera.height != planned.height || camera.guardBand != planned.guardBand) {
    auto size = [](const Camera& k) {
      return std::to_string(k.width) + "x" + std::to_string(k.height) + " with guard band " + std::to_string(k.guardBand);
    };
    return Status::error(StatusCode::InvalidInput,
                         "record(): Inputs::camera is " + size(camera) + " but Config::camera (the plan) is " +
                             size(planned) + ": a new size or guard band changes every image; call update()");
  }
  const auto levels = static_cast<std::uint32_t>(out.max_mip) + 1;
  if (levels != e.plan.cszLevels)
    return Status::error(StatusCode::InvalidInput,
                         "record(): Inputs::camera needs " + std::to_string(levels) +
                             " csz MIP levels but the plan (Config::camera) has " + std::to_string(e.plan.cszLevels) +
                             " (the largest projected radius, from the projection scale, near distance, projection "
                             "kind and metersToViewUnits, selects them): this camera changes the plan; call update()");
  // The members the backend sets from Config after computeConstants (checkConfig): the output's
  // channel mask, blend and the depth input's sample count.
  out.output_mask = e.params.output_mask;
  out.output_blend = e.params.output_blend;
  out.depth_samples = e.params.depth_samples;
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
