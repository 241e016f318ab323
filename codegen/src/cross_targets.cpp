#include "cross_targets.h"

#include <spirv_cross/spirv_glsl.hpp>
#include <spirv_cross/spirv_hlsl.hpp>

#include <exception>

namespace sao::codegen {

std::vector<HlslRegister> hlslRegisters(const PassVariant& pv) {
  std::vector<HlslRegister> out;
  int t = 0, u = 0;
  for (const Binding& b : pv.bindings) {
    out.push_back(b.write ? HlslRegister{'u', u} : HlslRegister{'t', t});
    (b.write ? u : t) += b.write ? b.slots : 1;
  }
  return out;
}

bool writeHlsl(const std::vector<uint32_t>& vulkanSpirv, const PassVariant& pv, int shaderModel, std::string& hlsl,
               std::string& error) {
  try {
    spirv_cross::CompilerHLSL compiler(vulkanSpirv);
    spirv_cross::CompilerHLSL::Options options;
    options.shader_model = uint32_t(shaderModel);
    compiler.set_hlsl_options(options);
    auto bind = [&](uint32_t set, uint32_t binding, char cls, int index) {
      spirv_cross::HLSLResourceBinding rb;
      rb.stage = spv::ExecutionModelGLCompute;
      rb.desc_set = set;
      rb.binding = binding;
      (cls == 'b' ? rb.cbv : cls == 'u' ? rb.uav : rb.srv).register_binding = uint32_t(index);
      if (cls == 't') rb.sampler.register_binding = uint32_t(index);
      compiler.add_hlsl_resource_binding(rb);
    };
    bind(0, 0, 'b', kHlslParamsRegister);
    bind(spirv_cross::ResourceBindingPushConstantDescriptorSet, spirv_cross::ResourceBindingPushConstantBinding, 'b',
         kHlslPushRegister);
    const auto registers = hlslRegisters(pv);
    for (std::size_t i = 0; i < pv.bindings.size(); ++i)
      bind(0, uint32_t(pv.bindings[i].binding), registers[i].cls, registers[i].index);
    hlsl = compiler.compile();
    // Every resource the module declares got its register above (none left at SPIRV-Cross's default).
    const spirv_cross::ShaderResources res = compiler.get_shader_resources();
    for (const auto* list : {&res.sampled_images, &res.storage_images, &res.uniform_buffers})
      for (const spirv_cross::Resource& r : *list) {
        const uint32_t set = compiler.get_decoration(r.id, spv::DecorationDescriptorSet);
        const uint32_t binding = compiler.get_decoration(r.id, spv::DecorationBinding);
        if (!compiler.is_hlsl_resource_binding_used(spv::ExecutionModelGLCompute, set, binding)) {
          error = "resource '" + r.name + "' (binding " + std::to_string(binding) + ") has no HLSL register";
          return false;
        }
      }
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
}

bool writeEssl(const std::vector<uint32_t>& openGlSpirv, std::string& essl, std::string& error) {
  try {
    spirv_cross::CompilerGLSL compiler(openGlSpirv);
    spirv_cross::CompilerGLSL::Options options;
    options.es = true;
    options.version = 310;
    options.vulkan_semantics = false;
    compiler.set_common_options(options);
    essl = compiler.compile();
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
}

}  // namespace sao::codegen
