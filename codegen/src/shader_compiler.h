// glslang (library API) and SPIRV-Tools (validator, optimizer) behind two calls.
#pragma once
#include <cstdint>
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

}  // namespace sao::codegen
