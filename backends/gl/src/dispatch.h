// Running the planned passes: bindings per pass variant from gen::PassVariantInfo::bindings
// (binding N = texture unit N for samplers, image unit N for images), aliases from the plan,
// per=mip passes once per level through single-level views, a barrier after every dispatch.
#pragma once
#include <vector>

#include "gl_functions.h"
#include "inputs.h"
#include "programs.h"
#include "resources.h"
#include "timing.h"

namespace sao::gl::detail {

struct PassResources {
  const Resources* owned = nullptr;
  const CheckedInputs* inputs = nullptr;
  GLuint nearestSampler = 0;  // GL_NEAREST, compare mode none: inputs and single-level images
  GLuint mipSampler = 0;      // GL_NEAREST_MIPMAP_NEAREST: MIP chains read at explicit lods
};

// The texture that serves `id` (input, owned image or output), 0 if none.
GLuint textureFor(const PassResources& r, gen::ResourceId id);

// Programs of every planned pass, compiled before anything is dispatched.
Status preparePrograms(Programs& programs, const Plan& plan, std::vector<GLuint>& out, std::uint64_t& compiled);

void dispatchPasses(const GlFunctions& gl, const Plan& plan, const std::vector<GLuint>& programs,
                    const PassResources& r, PassTimer& timer);

}  // namespace sao::gl::detail
