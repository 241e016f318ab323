// Private to sao_scenes: checks made before assimp sees a glTF, for what Debian's assimp 5.2 does
// not survive (found by tests/fuzz/fuzz_scene_file): a binary glTF chunk declaring more bytes than
// the file has is allocated before it is read (2.9 GB for a 600-byte file), invalid JSON can
// leave assimp's half-built objects leaked, a line-loop primitive whose first segment it drops
// makes it dereference a null pointer, and a data URI with a long header makes it read outside the
// string.
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "sao/status.h"

namespace sao::scenes::detail {

// Reads `count` bytes at `offset` into `out`; false if they are not there.
using ReadBytes = std::function<bool(std::uint64_t offset, std::size_t count, std::string& out)>;

// A binary glTF (.glb) of `size` bytes: when it starts with the "glTF" magic, it must be version 2,
// the header's length and each chunk's length must fit the file (a JSON chunk first, then
// optionally a BIN chunk), and the JSON chunk must not start with a byte-order mark and must pass
// checkGltfJson. IoError "NAME: binary
// glTF: ..." otherwise.
// Data without the magic is left to assimp (which refuses it). `folder` as in GltfBuffers.
Status checkGlb(std::uint64_t size, const ReadBytes& read, std::string_view name,
                const std::optional<std::filesystem::path>& folder = std::nullopt);

// Where checkGltfJson finds the data of a glTF's buffers, to check its index values (data URIs
// are always read).
struct GltfBuffers {
  ReadBytes binChunk;  // a .glb's BIN chunk: buffer 0 when it has no uri
  std::optional<std::filesystem::path> folder;  // the file's folder for buffers in other files; none in memory
};

// The text of a .gltf file (or a GLB's JSON chunk), IoError "NAME: ..." unless: it is valid JSON
// ("not valid JSON (at byte N)"; a UTF-8 byte-order mark before it is allowed), it is glTF 2.0
// ("glTF 1.0 is not supported (glTF 2.0 only): ..." for an asset.version of "1.0" or 1, or no
// asset), every buffer or image data URI has its comma within its first 127 characters, every
// mesh primitive has a POSITION attribute ("glTF: mesh M primitive P has no POSITION attribute")
// and is not a line loop (mode 2), and its buffer views, accessors and indices pass
// checkGltfAccessors (gltf_accessors.h).
Status checkGltfJson(std::string_view text, std::string_view name, const GltfBuffers& buffers = {});

}  // namespace sao::scenes::detail
