// The frame around the plan, decided once for every backend (GL, Vulkan, the CPU reference and an
// engine's own renderer): what a frame adds to the parameter block, and when a new camera keeps
// the plan.
//
// computeConstants fills what the settings and the camera give. A frame adds what its inputs give
// (the region's offset, the output's channel mask and blend: FrameValues; the depth's samples:
// PlanInputs) and its number (the frame's spiral). Backends check a frame's output use and build
// the block here and nowhere else.
#pragma once
#include <cstdint>

#include "sao/constants.h"
#include "sao/output.h"
#include "sao/plan.h"

namespace sao {

// What changes per frame without changing the plan.
struct FrameValues {
  // Where the region of Plan::inputExtent texels starts inside the inputs (Inputs::region); (0, 0)
  // without one. Each coordinate at most INT32_MAX (the shaders' int): the backends' input checks
  // put it inside an image, whose sides are far below that.
  Offset inputOffset;
  std::uint32_t frameIndex = 0;  // Inputs::frameIndex: the frame's spiral (sao/spiral.h)
  // Which channels of the output take A, and how (sao/output.h; Inputs::outputChannels and
  // ::outputBlend on every backend): block values, so they change per frame without a new plan.
  std::uint32_t outputChannels = kAllChannels;
  OutputBlend outputBlend = OutputBlend::Replace;
};

// Whether a frame of `plan` may write its output with `frame`'s channel mask and blend: Ok, or
// InvalidInput prefixed by `who` for a mask the output's format cannot take, an unknown blend,
// multiply or a mask that keeps channels of an effect-owned output (it holds nothing to keep), and
// the bent normal output (BENT_NORMALS: it fills every channel) with a mask or blend that keeps the
// caller's texels. Allocates only for an error's message.
Status checkFrameOutput(const Plan& plan, const PlanInputs& inputs, const FrameValues& frame, const char* who);

// The frame's members of a block that computeConstants filled for the same inputs: input_offset,
// output_mask, output_blend, depth_samples, frame_phase and frame_alpha_offset (`frame` checked by
// checkFrameOutput). Allocates nothing.
void completeFrame(ParamBlock& block, const PlanInputs& inputs, const FrameValues& frame);

// computeConstants(settings, camera, inputs.depthEncoding) and completeFrame: the whole block of a
// frame but the temporal members (sao/temporal.h). Allocates only for an error's message.
Status frameConstants(const Settings& settings, const Camera& camera, const PlanInputs& inputs,
                      const FrameValues& frame, ParamBlock& out);

// The one rule for whether `next` plans exactly as `planned` did with these settings, so that a new
// camera per frame (TAA jitter, the other eye of a stereo pair, an animated field of view, another
// projection kind) needs only a new parameter block: the same viewport and guard band (every
// image's extent) and the same csz MIP levels (from the projection scale, the near distance, the
// projection kind and metersToViewUnits). Nothing else of a camera reaches the plan: the projection
// kind, clip range, reversed-Z, flipY and normals encoding are block values. Ok when it keeps the
// plan; InvalidInput naming what differs, or `next`'s own InvalidCamera, when not. Allocates only
// for an error's message.
Status checkCameraKeepsPlan(const Settings& settings, const Camera& planned, const Camera& next);

// checkCameraKeepsPlan(...).ok() without a message.
bool cameraKeepsPlan(const Settings& settings, const Camera& planned, const Camera& next);

}  // namespace sao
