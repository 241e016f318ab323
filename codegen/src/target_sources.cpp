#include "target_sources.h"

#include <cctype>

#include "cross_targets.h"
#include "shader_compiler.h"

namespace sao::codegen {

namespace {

// The HLSL as glslang compiles it for Vulkan, with the Vulkan attributes DXC's SPIR-V back end reads
// too: the push-constant cbuffer marked [[vk::push_constant]] without its Direct3D register b1, and
// each UAV's format ([[vk::image_format]]; Direct3D's typed UAVs take the view's, Vulkan's storage
// images must name it to be loaded from without shaderStorageImageReadWithoutFormat).
std::string hlslForVulkan(std::string hlsl, const Effect& effect, const PassVariant& pv, const std::string& pushBlock) {
  if (!pushBlock.empty()) {
    const std::string decl = "cbuffer " + pushBlock, reg = " : register(b" + std::to_string(kHlslPushRegister);
    if (const auto at = hlsl.find(decl); at != std::string::npos) {
      const auto end = hlsl.find(')', at);  // "register(b1)" or, from SM 5.1, "register(b1, space0)"
      if (hlsl.compare(at + decl.size(), reg.size(), reg) == 0 && end != std::string::npos)
        hlsl.erase(at + decl.size(), end + 1 - (at + decl.size()));
      hlsl.insert(at, "[[vk::push_constant]] ");
    }
  }
  for (const Binding& b : pv.bindings) {
    if (!b.write) continue;
    const std::string name = " out_" + effect.resources[b.resource].name;
    for (auto at = hlsl.find("RWTexture2D<"); at != std::string::npos; at = hlsl.find("RWTexture2D<", at + 1)) {
      const auto nameAt = hlsl.find('>', at) + 1;
      if (hlsl.compare(nameAt, name.size(), name) != 0 || std::isalnum(static_cast<unsigned char>(hlsl[nameAt + name.size()])) ||
          hlsl[nameAt + name.size()] == '_')
        continue;
      hlsl.insert(at, "[[vk::image_format(\"" + b.format + "\")]] ");
      break;
    }
  }
  return hlsl;
}

// The Vulkan binding of HLSL register (class, index) in pass variant pv; -1: none.
int vulkanBindingOf(const PassVariant& pv, char cls, int index) {
  if (cls == 'b') return index == kHlslParamsRegister ? 0 : -1;
  const auto registers = hlslRegisters(pv);
  for (std::size_t i = 0; i < registers.size(); ++i)
    if (registers[i].cls == (cls == 's' ? 't' : cls) && registers[i].index == index) return pv.bindings[i].binding;
  return -1;
}

}  // namespace

bool hlslOf(const Effect& effect, const std::vector<uint32_t>& spirv, const PassVariant& pv, int model, const std::string& pushBlock,
            bool keepRoundTrip, const SourceLoc& loc, std::string& hlsl, std::vector<uint32_t>& roundTrip,
            Diagnostics& diags) {
  std::string why;
  if (!writeHlsl(spirv, pv, model, hlsl, why)) {
    diags.error(loc, "pass variant " + pv.stem + ": SPIRV-Cross cannot write HLSL SM " + std::to_string(model / 10) +
                         "." + std::to_string(model % 10) + ": " + why);
    return false;
  }
  Diagnostics inner;
  const bool ok = compileHlsl(hlslForVulkan(hlsl, effect, pv, pushBlock), loc,
                              [&](char cls, int index) { return vulkanBindingOf(pv, cls, index); }, keepRoundTrip,
                              roundTrip, inner);
  for (const auto& d : inner.all())  // glslang's lines refer to the HLSL, not the annotated source
    if (d.severity == "error") diags.error(loc, "pass variant " + pv.stem + ": its HLSL SM " + std::to_string(model) + ": " + d.message);
  return ok;
}

bool esslOf(const Effect& effect, const PassVariant& pv, const SourceLoc& loc, std::string& essl, Diagnostics& diags) {
  std::vector<uint32_t> spirv;
  if (!compileOpenGlSpirv(composeShader(effect, pv, Target::OpenGLES), loc, spirv, diags)) return false;
  std::string why;
  if (!writeEssl(spirv, essl, why)) {
    diags.error(loc, "pass variant " + pv.stem + ": SPIRV-Cross cannot write GLSL ES 3.10: " + why);
    return false;
  }
  return checkEssl(essl, loc, diags);
}

}  // namespace sao::codegen
