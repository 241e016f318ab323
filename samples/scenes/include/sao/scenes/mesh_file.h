// Triangle meshes from files: .gltf and .glb (glTF 2.0) through tinygltf (Debian's
// libtinygltf-dev, geometry only: images are neither decoded nor opened), .obj and .ply through
// sao's own readers (src/obj_reader.cpp, src/ply_reader.cpp): fuzzing found assimp 5.2's OBJ and
// PLY readers reading out of bounds on malformed files (docs/ROBUSTNESS.md section 4.8).
//
// The mesh is in world space (the node trees of a glTF's default scene are applied; morph targets
// and skins are not) and triangulated (glTF strips and fans are split, OBJ and PLY polygons become
// fans); only positions and indices are kept, points and lines are left out. A glTF primitive's
// identical positions become one vertex; OBJ and PLY keep the file's vertex list. Units are the
// file's (a glTF is in metres; OBJ and PLY state none: units.h). Before tinygltf sees a glTF, its
// JSON must be valid, its version 2.x (glTF 1.0 is named as unsupported), its members of the
// schema's types (src/gltf_schema.h), a .glb's chunks must fit the file, and the accessors of its
// meshes must have valid strides and bounds (src/gltf_accessors.h); reading the mesh checks every
// index against its vertex count (src/gltf_mesh.h). A UTF-8 byte-order mark is skipped in OBJ and
// .gltf files, refused in PLY and in a .glb's JSON chunk.
//
// No exception escapes these functions: every problem is a Status whose message starts with the
// file's name, and the outputs are left untouched. Files a glTF refers to (its .bin buffers) are opened only when they are regular
// files; from memory, never. An OBJ's material libraries are not opened.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sao/scenes/mesh.h"
#include "sao/scenes/scene.h"
#include "sao/status.h"

namespace sao::scenes {

// The most triangles a mesh (or a scene file's meshes together) may have.
inline constexpr std::size_t kMaxMeshTriangles = 50'000'000;
// The largest .ply, .obj or .gltf file read (they are read into memory first).
inline constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t(2) << 30;

// True for the extensions loadMeshFile reads (case-insensitive): .gltf .glb .obj .ply.
bool isMeshFileExtension(std::string_view path);

// Reads a mesh file. Errors (out is left untouched):
//   IoError            missing file, a directory or another non-regular file, a malformed file
//                      (sao's checks, "glTF: ..."; or tinygltf's own error, "tinygltf: ..."), a
//                      file that cannot be read
//   UnsupportedFormat  an extension other than the four above
//   InvalidInput       a mesh that fails validateMesh
// When `cameras` is given, it receives the views of a glTF's cameras: one for each node of the
// default scene that holds a camera, in node order (src/gltf_cameras.h; docs/scene-format.md, "glTF
// cameras"); a camera whose world matrix leaves it no direction is then an IoError. None for OBJ
// and PLY. A glTF's camera values are checked either way (a camera that is not valid glTF 2.0, or
// not usable by sao, is an IoError).
Status loadMeshFile(const std::string& path, Mesh& out, std::vector<View>* cameras = nullptr);

// The same from bytes in memory; `formatHint` is an extension without the dot ("gltf", "glb",
// "obj", "ply") and `name` names the data in error messages. Files the data refers to are not
// opened (a glTF with an external buffer fails).
Status loadMeshFromMemory(std::span<const std::uint8_t> bytes, std::string_view formatHint, std::string_view name,
                          Mesh& out, std::vector<View>* cameras = nullptr);

// InvalidInput "NAME: PROBLEM" unless the mesh has at least one and at most maxTriangles
// triangles, a whole number of triangles, finite positions, indices below the vertex count and
// triangles that are not all at one point nor all degenerate ("all its N triangles are
// degenerate ...": nothing would be drawn).
Status validateMesh(const Mesh& mesh, std::string_view name, std::size_t maxTriangles = kMaxMeshTriangles);

// A triangle without area: its height on its longest edge is at most 1e-6 of that edge (corners
// repeated or collinear, up to float rounding). It covers no pixel and has no normal.
bool isDegenerateTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c);

// Removes the degenerate triangles of a mesh (indices in range, as after validateMesh) and returns
// how many there were; when there were any, appends "NAME: N of M triangles are degenerate (...)
// and were left out" to `warnings`. loadScene does so for every mesh file (Scene::warnings).
std::size_t removeDegenerateTriangles(Mesh& mesh, std::string_view name, std::vector<std::string>& warnings);

}  // namespace sao::scenes
