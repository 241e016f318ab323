// Private to sao_scenes: OBJ files are read here, not by assimp. Debian's assimp 5.2 calls
// atoi/strtol on line buffers that are not NUL-terminated (found by tests/fuzz/fuzz_scene_file
// with ASan's strict string checks, twice within minutes); this reader parses with bounds.
#pragma once
#include <string_view>

#include "sao/scenes/mesh.h"
#include "sao/status.h"

namespace sao::scenes::detail {

// Reads the geometry of a Wavefront OBJ: `v x y z [...]` lines (numbers after the third are
// ignored: w, vertex colours) and `f` lines of references `i`, `i/t`, `i//n` or `i/t/n` (1-based,
// or negative: relative to the vertices so far); polygons are split into fans, faces of fewer
// than 3 vertices are left out, a line ending in a backslash continues on the next, every other
// statement (vt, vn, g, o, s, usemtl, mtllib, l, p, comments, ...) is ignored; a UTF-8
// byte-order mark at the start is skipped. Errors: IoError
// "NAME: OBJ line N: ..." for a malformed line, InvalidInput for a reference to a vertex that
// does not exist or more than kMaxMeshTriangles triangles. out is left untouched on error. Does
// not call validateMesh.
Status readObj(std::string_view text, std::string_view name, Mesh& out);

}  // namespace sao::scenes::detail
