// The parameter block: parse its members and lay them out by std140, refusing members whose
// std140 layout differs from a naive C++ struct (vec3, scalar arrays, bool, mat2/mat3).
#pragma once
#include <vector>

#include "diagnostics.h"
#include "effect_model.h"

namespace sao::codegen {

// `lines` start at the line after `#pragma sao block`. Returns the block, consumed line count.
ParamBlock parseParamBlock(const std::string& name, const SourceLoc& directiveLoc,
                           const std::vector<SourceLine>& lines, size_t first, Diagnostics& diags);

}  // namespace sao::codegen
