// A pass variant's HLSL and GLSL ES 3.10, each written from SPIR-V (cross_targets.h) and checked by
// compiling it again: the HLSL back to SPIR-V for Vulkan (the round trip), the GLSL ES with the ES
// front end. Diagnostics name the pass variant.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "diagnostics.h"
#include "effect_model.h"
#include "pass_builder.h"

namespace sao::codegen {

// HLSL for shader model 50 or 60 from the variant's Vulkan SPIR-V; its round trip's SPIR-V (with the
// variant's Vulkan bindings) in roundTrip, optimised when keepRoundTrip (a module that will run).
bool hlslOf(const Effect& effect, const std::vector<uint32_t>& spirv, const PassVariant& pv, int model,
            const std::string& pushBlock, bool keepRoundTrip, const SourceLoc& loc, std::string& hlsl,
            std::vector<uint32_t>& roundTrip, Diagnostics& diags);

// GLSL ES 3.10 from the variant's GLES composition (pass_builder.h, Target::OpenGLES).
bool esslOf(const Effect& effect, const PassVariant& pv, const SourceLoc& loc, std::string& essl, Diagnostics& diags);

}  // namespace sao::codegen
