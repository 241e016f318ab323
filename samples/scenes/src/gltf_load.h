// Private to sao_scenes: a glTF 2.0 document (.gltf text or .glb bytes), already checked by
// gltf_checks.h, parsed by tinygltf into its Model. Images are not decoded; files other than
// buffers next to a .gltf file are never opened, and those only when they are regular files.
#pragma once
#include <filesystem>
#include <optional>
#include <string_view>

#include "sao/status.h"
#include "tinygltf.h"

namespace sao::scenes::detail {

// `binary`: a .glb; `folder`: where a file's external buffers are (none for data in memory, which
// opens no file). IoError "NAME: tinygltf: REASON" when tinygltf refuses the data.
Status parseGltf(std::string_view bytes, bool binary, const std::optional<std::filesystem::path>& folder,
                 std::string_view name, tinygltf::Model& model);

}  // namespace sao::scenes::detail
