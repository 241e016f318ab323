// Private to sao_scenes: assimp's ai_assert throws instead of aborting (assimp_assert.cpp).
#pragma once
#include <stdexcept>

namespace sao::scenes::detail {

// What a failed ai_assert throws; assimp's Importer catches it and fails the read.
struct AssimpCheckFailed : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// True: the replacement of Assimp::aiAssertViolation is linked in. Calling this from the mesh
// reader also makes sure the linker keeps that object file.
bool assimpAssertionsThrow();

}  // namespace sao::scenes::detail
