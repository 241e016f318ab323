// Running the schedule (sao/schedule.h): for each dispatch, its program, its resolved bindings
// (binding N = texture unit N for sampled reads, image unit N for stores) and the memory barrier
// its hazards need; the frame's entry and exit hazards around them.
#pragma once
#include <vector>

#include "gl_functions.h"
#include "inputs.h"
#include "programs.h"
#include "resources.h"
#include "sao/schedule.h"
#include "sao/temporal.h"
#include "timing.h"

namespace sao::gl::detail {

struct PassResources {
  const Resources* owned = nullptr;
  const CheckedInputs* inputs = nullptr;
  GLuint nearestSampler = 0;  // GL_NEAREST, compare mode none: inputs, single levels
  GLuint mipSampler = 0;      // GL_NEAREST_MIPMAP_NEAREST: whole MIP chains read at explicit lods
  std::uint32_t historyParity = 0;  // the history copy this frame writes (sao/temporal.h)
};

// The texture that serves `id` (input, owned image or output), 0 if none; for a history, this
// frame's copy, or the previous frame's with `previousFrame`.
GLuint textureFor(const PassResources& r, gen::ResourceId id, bool previousFrame = false);

// The glMemoryBarrier bits that resolve `hazards` (0: none needed).
GLbitfield barrierBits(std::span<const Hazard> hazards);

// Programs of every planned pass, compiled before anything is dispatched.
Status preparePrograms(Programs& programs, const Plan& plan, std::vector<GLuint>& out, std::uint64_t& compiled);

// Entry barrier, every dispatch, exit barrier. Allocates nothing (the timer reuses its storage).
void runSchedule(const GlFunctions& gl, const Plan& plan, const Schedule& schedule, const std::vector<GLuint>& programs,
                 const PassResources& r, PassTimer& timer);

}  // namespace sao::gl::detail
