// glslang (library API) and SPIRV-Tools (validator, optimizer) behind two calls.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "diagnostics.h"
#include "effect_model.h"
#include "source_loader.h"

namespace sao::codegen {

class GlslangProcess {  // glslang needs one process-wide initialisation
 public:
  GlslangProcess();
  ~GlslangProcess();
};

// Compiles GLSL 4.30 as OpenGL compiles it (no SPIR-V); errors mapped to the annotated source.
// When `block` is given, checks glslang's std140 offsets against ours.
bool checkOpenGl(const std::vector<SourceLine>& shader, const SourceLoc& passLoc, const ParamBlock* block,
                 Diagnostics& diags);

// Compiles to SPIR-V 1.3 for Vulkan 1.1, validates, runs spirv-opt's performance passes and
// validates again. Returns false (with diagnostics) on any failure.
bool compileVulkan(const std::vector<SourceLine>& shader, const SourceLoc& passLoc, std::vector<uint32_t>& spirv,
                   Diagnostics& diags);

// GL text (the GLES composition) to SPIR-V for OpenGL (GL units as bindings, no push constants),
// validated and optimised like compileVulkan: what the GLSL ES 3.10 is written from.
bool compileOpenGlSpirv(const std::vector<SourceLine>& shader, const SourceLoc& passLoc, std::vector<uint32_t>& spirv,
                        Diagnostics& diags);

// Compiles generated GLSL ES 3.10 as an ES 3.1 driver would (glslang's ES front end).
bool checkEssl(const std::string& essl, const SourceLoc& passLoc, Diagnostics& diags);

// Compiles generated HLSL (entry main) with glslang's HLSL front end to SPIR-V for Vulkan 1.1: textures
// and their samplers combined, each resource at the binding
// bindingOf(register class 'b' 't' 's' 'u', register) gives (-1: an error); validated, and optimised
// when `optimise` (a module that runs; a check alone needs validation only).
bool compileHlsl(const std::string& hlsl, const SourceLoc& passLoc, const std::function<int(char, int)>& bindingOf,
                 bool optimise, std::vector<uint32_t>& spirv, Diagnostics& diags);

}  // namespace sao::codegen
