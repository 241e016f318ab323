// Private to sao_scenes: the triangles of a parsed glTF 2.0 model, in world space.
#pragma once
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "sao/scenes/mesh.h"
#include "sao/status.h"
#include "tinygltf.h"

namespace sao::scenes::detail {

// The triangles (modes 4, 5 and 6; points and lines are left out) of every mesh of the default
// scene ("scene", else the first), each transformed by its node's world matrix; identical
// positions within a primitive become one vertex. Morph targets and skins are not applied. Every
// access is bounds-checked; IoError "NAME: glTF: ..." for a node hierarchy that is not a set of
// trees (a cycle, a node with two parents, a scene node that is not a root), a reference to
// something that does not exist, data outside its buffer, positions that are not VEC3 floats or
// indices that are not unsigned integers, and an index out of range ("glTF: mesh M primitive P:
// index I (element K of accessor A) is out of range: its POSITION, accessor B, has N vertices").
// InvalidInput for more triangles than kMaxMeshTriangles. `out` is not checked with validateMesh.
// A node's camera must exist ("glTF: nodes[N].camera is C, which does not exist"); when `cameras`
// is given, it receives the default scene's camera nodes in node order.
struct GltfCameraNode {
  int node;          // index into model.nodes
  int camera;        // index into model.cameras
  glm::dmat4 world;  // the node's world matrix
};
Status gltfTriangles(const tinygltf::Model& model, std::string_view name, Mesh& out,
                     std::vector<GltfCameraNode>* cameras = nullptr);

}  // namespace sao::scenes::detail
