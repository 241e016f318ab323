// HLSL and GLSL ES 3.10 written from the validated SPIR-V by SPIRV-Cross, and the HLSL register of
// each binding (one rule, used by the writer, the pass description and the round trip).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "pass_builder.h"

namespace sao::codegen {

// HLSL registers: the parameter block b0, the push constants b1; reads t0, t1 ... in binding order,
// each with its sampler at the same s register; writes u0, u1 ... (an array takes one per slot).
inline constexpr int kHlslParamsRegister = 0;
inline constexpr int kHlslPushRegister = 1;
struct HlslRegister {
  char cls = 't';  // 't' (with 's' of the same number) or 'u'
  int index = 0;
};
std::vector<HlslRegister> hlslRegisters(const PassVariant& pv);

// From the Vulkan SPIR-V: HLSL for shader model 50 or 60 (entry point main), resources at
// hlslRegisters(pv). Returns false with `error` set when SPIRV-Cross cannot write it.
bool writeHlsl(const std::vector<uint32_t>& vulkanSpirv, const PassVariant& pv, int shaderModel, std::string& hlsl,
               std::string& error);

// From the OpenGL SPIR-V of the GLES composition (bindings are GL units): GLSL ES 3.10.
bool writeEssl(const std::vector<uint32_t>& openGlSpirv, std::string& essl, std::string& error);

}  // namespace sao::codegen
