// Facts about a compiled pass variant that its SPIR-V states and that a host must know to run it:
// the shared memory its work group declares and its push-constant block. Read from the module, so
// they follow the shader source and are never kept by hand beside it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace sao::codegen {

struct PushConstantMember {
  std::string name;
  std::string glslType;  // "int", "uint" or "float": the only members supported (32-bit scalars)
  std::uint32_t offset = 0;
};

struct SpirvFacts {
  // Bytes of every Workgroup variable, tightly packed (scalars of their width, vectors, arrays and
  // structs without padding): what GL_MAX_COMPUTE_SHARED_MEMORY_SIZE / maxComputeSharedMemorySize
  // must hold.
  std::uint32_t sharedBytes = 0;
  // The push-constant block (none: empty name, 0 bytes): its type name, members and size (the end
  // of its last member).
  std::string pushConstantBlock;
  std::vector<PushConstantMember> pushConstants;
  std::uint32_t pushConstantBytes = 0;
};

// Reads `spirv`; false with `error` set for a module it cannot size (an array whose length is not a
// constant, a push-constant member that is not a 32-bit scalar, a missing member name or offset).
bool readSpirvFacts(const std::vector<std::uint32_t>& spirv, SpirvFacts& out, std::string& error);

}  // namespace sao::codegen
