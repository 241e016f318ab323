// The view a mesh file gets (it has none of its own), and the default near plane of scene files.
#pragma once
#include "sao/scenes/scene.h"

namespace sao::scenes {

// A view that sees the whole mesh: from the (+x, +y, +z) diagonal of its bounding box towards its
// centre, 60 degrees vertical field of view, at the distance where the bounding sphere just fits
// the field of view (and the horizontal one, for an aspect of 1 or wider), near plane at a
// hundredth of the bounding-box diagonal. Named "default". The mesh must pass validateMesh.
View defaultView(const Mesh& mesh);

// A hundredth of the diagonal of the bounding box of the mesh's vertices.
double defaultNearDistance(const Mesh& mesh);

}  // namespace sao::scenes
