// Private to sao_scenes: PLY files are read here, not by assimp. Debian's assimp 5.2 reads outside
// its buffer on malformed binary PLY headers (an unknown property type, a property line cut short:
// SEGVs found by tests/fuzz/fuzz_scene_file within a minute); this reader checks every count and
// byte against the data it has.
#pragma once
#include <string_view>

#include "sao/scenes/mesh.h"
#include "sao/status.h"

namespace sao::scenes::detail {

// Reads PLY 1.0 (ascii, binary_little_endian, binary_big_endian): the x, y, z properties of the
// "vertex" element (any numeric type) and the vertex_indices (or vertex_index) list of the "face"
// element; polygons are split into fans, faces of fewer than 3 vertices are left out, other
// elements and properties are skipped. Errors: IoError "NAME: PLY: ..." for a malformed file (a
// UTF-8 byte-order mark before "ply" included),
// InvalidInput for a face that refers to a vertex that does not exist or more than
// kMaxMeshTriangles triangles. out is left untouched on error. Does not call validateMesh.
Status readPly(std::string_view bytes, std::string_view name, Mesh& out);

}  // namespace sao::scenes::detail
