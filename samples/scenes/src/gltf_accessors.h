// Private to sao_scenes: the glTF 2.0 rules on buffer views and accessors that tinygltf 2.7.0 does
// not check: it reads a byteStride it cannot parse as 0 (packed) and checks no accessor against its
// view. (Index values are checked as the mesh is read: gltf_mesh.h.)
#pragma once
#include <string_view>

#include <nlohmann/json.hpp>

#include "sao/status.h"

namespace sao::scenes::detail {

// IoError "NAME: glTF: ..." unless, for every accessor of a mesh primitive (an attribute or its
// indices) that has a buffer view (the glTF 2.0 specification, "Buffers and Buffer Views" and
// "Accessors"):
//   - the view's byteStride, when given, is a multiple of 4 in [4, 252] and at least the
//     accessor's element size;
//   - the accessor's last element ends within the view;
// the view lies within its buffer's byteLength; the indices of every triangle primitive are SCALAR
// of an unsigned integer type; an image's buffer view lies within its buffer. `doc` has passed
// checkGltfTypes (gltf_schema.h).
Status checkGltfAccessors(const nlohmann::json& doc, std::string_view name);

}  // namespace sao::scenes::detail
