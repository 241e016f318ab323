// Private to sao_scenes: a glTF's cameras (glTF 2.0 section 3.10) as sao views: their values
// checked in the JSON, before tinygltf (which checks none of them and cannot tell an absent zfar
// from 0), and the camera nodes of the default scene turned into Views.
#pragma once
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "gltf_mesh.h"
#include "sao/scenes/scene.h"
#include "sao/status.h"
#include "tinygltf.h"

namespace sao::scenes::detail {

// Every entry of "cameras" (used by a node or not, as every mesh primitive is checked): IoError
// "NAME: glTF: cameras[C]..." for a type other than "perspective" or "orthographic", a missing
// object of that type or a missing required member, and for values sao cannot use:
//   perspective   yfov in (0, pi), znear > 0, zfar (optional) > znear, aspectRatio (optional) > 0
//   orthographic  xmag > 0, ymag > 0 (glTF 2.0 allows negative values, a mirrored image, but
//                 advises against them) with 2 ymag finite, znear >= 0, zfar > znear
// The members' types are checked before (gltf_schema.h); JSON has no infinity or NaN, and a
// number beyond a double is not valid JSON (gltf_checks.h).
Status checkGltfCameras(const nlohmann::json& doc, std::string_view name);

// The views of the camera nodes (as gltfTriangles gives them, in node order), one each: the eye at
// the node's origin, looking down its -z with its +y up, both through its world matrix and
// normalised (a scale moves the eye, never the projection). Perspective: fovyRadians = yfov,
// nearDistance = znear (zfar and aspectRatio are not used: the programs keep an infinite far plane
// and their image's aspect). Orthographic: orthoHeight = 2 ymag, nearDistance = znear, orthoFar =
// zfar (xmag is not used). The target lies along the view direction at the depth of the centre of
// the mesh's bounding box, or half its diagonal away when that centre is not in front of the eye.
// Names: the camera's name, else the node's, else "camera C"; control characters become spaces,
// and a name already taken, or "default" (loadScene's first view), gets " (2)", " (3)", ...
// IoError "NAME: glTF: nodes[N] (camera C): ..." for a world matrix that is not finite or leaves no
// view direction (a zero scale, or -z and +y made parallel). `mesh` must pass validateMesh; `out`
// is left untouched on error.
Status gltfCameraViews(const tinygltf::Model& model, const std::vector<GltfCameraNode>& nodes, const Mesh& mesh,
                       std::string_view name, std::vector<View>& out);

}  // namespace sao::scenes::detail
