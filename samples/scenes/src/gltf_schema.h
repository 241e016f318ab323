// Private to sao_scenes: the types of a glTF 2.0 document's members (the specification's JSON
// schema, types only). tinygltf skips a member of the wrong type without a word (a mesh whose
// "primitives" is not an array loads as a mesh without primitives), so they are named here first.
#pragma once
#include <string_view>

#include <nlohmann/json.hpp>

#include "sao/status.h"

namespace sao::scenes::detail {

// IoError "NAME: glTF: PATH is WHAT; glTF 2.0 requires WANTED" (say "meshes[0].primitives is an
// object; glTF 2.0 requires an array") for the first member of the wrong type, and for buffers and
// buffer views of byteLength 0 (the schema's minimum is 1). Members the schema does not name, and
// the contents of "extras", are not checked; asset.version is checked before (gltf_checks.h) and a
// bufferView's byteStride after (gltf_accessors.h), with messages of their own.
Status checkGltfTypes(const nlohmann::json& doc, std::string_view name);

}  // namespace sao::scenes::detail
