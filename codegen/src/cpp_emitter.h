// Writes the generated C++ glue: settings + metadata, the parameter block struct, variants,
// resources, the pass table and the embedded shader blobs.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "effect_model.h"
#include "pass_builder.h"
#include "spirv_facts.h"

namespace sao::codegen {

struct CompiledPassVariant {
  PassVariant variant;
  int glslBlob = 0;   // index into glslBlobs
  int spirvBlob = 0;  // index into spirvBlobs
  SpirvFacts facts;   // shared memory and push constants, read from its SPIR-V
  int esslBlob = -1;  // index into esslBlobs; -1: the variant does not exist on GLES
};

// The push-constant block of the variants that declare one (main.cpp checks that they all declare
// the same), or nullptr when none does.
const SpirvFacts* pushConstantFacts(const std::vector<CompiledPassVariant>& passVariants);

struct GeneratedCode {
  std::string header;
  std::string source;
  std::string glesSource;  // esslSource(): <name>_effect_gles.cpp
};

GeneratedCode emitCpp(const Effect& effect, const std::vector<CompiledPassVariant>& passVariants,
                      const std::vector<std::string>& glslBlobs, const std::vector<std::vector<uint32_t>>& spirvBlobs,
                      const std::vector<std::string>& esslBlobs);

}  // namespace sao::codegen
