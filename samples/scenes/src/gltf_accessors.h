// Private to sao_scenes: the glTF 2.0 rules on buffer views and accessors that assimp 5.2 does not
// check. It reads an invalid byteStride as given (garbage geometry), and drops a triangle with an
// index out of range without a word ("has no faces" when it dropped them all).
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "sao/status.h"

namespace sao::scenes::detail {

// Reads `count` bytes at `offset` of buffer `index` into `out`; false when that buffer's data is
// not at hand (an external file from memory, a file that is missing): then its index values are
// not checked, and assimp reports the missing data.
using ReadBuffer = std::function<bool(std::size_t index, std::uint64_t offset, std::size_t count, std::string& out)>;

// IoError "NAME: glTF: ..." unless, for every accessor of a mesh primitive (an attribute or its
// indices) that has a buffer view (the glTF 2.0 specification, "Buffers and Buffer Views" and
// "Accessors"):
//   - the view's byteStride, when given, is a multiple of 4 in [4, 252] and at least the
//     accessor's element size;
//   - the accessor's last element ends within the view, and the view within its buffer's
//     byteLength;
// and every index of every triangle primitive (mode 4, 5, 6 or none) is below the vertex count of
// its POSITION accessor ("glTF: mesh M primitive P: index I (element K of accessor A) is not below
// the N vertices of its POSITION accessor B"). Members of the wrong type are left to assimp, which
// names them.
Status checkGltfAccessors(const nlohmann::json& doc, const ReadBuffer& read, std::string_view name);

}  // namespace sao::scenes::detail
