// The machine-readable description of the passes an engine's own renderer needs to run the effect
// from the shader files (`<effect>_passes.json`, installed beside them): per pass its local size,
// texels, levels and rules, and per compiled variant the variant values it was compiled for, its
// files, bindings (Vulkan binding, GL unit, resource, access, format, slots), shared memory and push
// constants; the parameter block's and the push-constant block's layouts.
#pragma once
#include <string>
#include <vector>

#include "cpp_emitter.h"
#include "effect_model.h"

namespace sao::codegen {

std::string passesJson(const Effect& effect, const std::vector<CompiledPassVariant>& compiled);

}  // namespace sao::codegen
