// Private to sao_scenes: the checks a glTF passes before tinygltf parses it. tinygltf 2.7.0 skips
// members of the wrong type without a word, reads glTF 1.0 as if it were 2.0, accepts invalid
// byteStrides and checks no accessor against its buffer view; the files a glTF names are opened
// here only when they are regular files (a FIFO would block, a device never end).
#pragma once
#include <filesystem>
#include <optional>
#include <string_view>

#include "sao/status.h"

namespace sao::scenes::detail {

// A binary glTF (.glb): the "glTF" magic, version 2, the header's length and each chunk's length
// within the data (a JSON chunk first, then optionally a BIN chunk), a JSON chunk without a
// byte-order mark that passes checkGltfJson. IoError "NAME: binary glTF: ..." otherwise.
// `folder` as in checkGltfJson.
Status checkGlb(std::string_view bytes, std::string_view name, const std::optional<std::filesystem::path>& folder);

// The text of a .gltf file (or a GLB's JSON chunk), IoError "NAME: ..." unless:
//   - it is valid JSON ("not valid JSON (at byte N)"; a UTF-8 byte-order mark before it is
//     allowed) nested at most 64 deep;
//   - it is glTF 2.0 ("glTF 1.0 is not supported (glTF 2.0 only): ..." for an asset.version of
//     "1.0" or 1, or no asset);
//   - its members have the schema's types (gltf_schema.h);
//   - every buffer or image data URI has its comma within its first 127 characters, and a
//     buffer's is of glTF 2.0's media types (without parameters), base64, and exactly byteLength
//     bytes;
//   - every other buffer URI names a regular file of byteLength bytes in `folder` (none: data in
//     memory, which opens no file);
//   - every mesh primitive has a POSITION attribute, a mode from 0 to 6 other than a line loop (2),
//     no Draco compression, and sets of TEXCOORD_n, COLOR_n, JOINTS_n and WEIGHTS_n numbered from 0;
//   - every camera has the values sao can use (checkGltfCameras, gltf_cameras.h);
//   - its buffer views and accessors pass checkGltfAccessors (gltf_accessors.h).
Status checkGltfJson(std::string_view text, std::string_view name,
                     const std::optional<std::filesystem::path>& folder = std::nullopt);

}  // namespace sao::scenes::detail
