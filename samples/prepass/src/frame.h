// What both backends derive from one render() call before touching the API: validated inputs, the
// image extent, the clear value and the uniform block (matrices built in double, rounded to float
// once), and the expanded vertex stream.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "sao/prepass/prepass.h"

namespace sao::prepass::detail {

// std140 layout of PrepassBlock in shaders/prepass.{vert,frag}: 160 bytes.
struct Uniforms {
  std::array<float, 16> mvp{};         // column-major, clip from world, guard band included
  std::array<float, 16> modelView{};   // column-major, camera (view units) from world
  std::array<float, 4> clipInfo{};     // c0, c1, c2, perspective ? 1 : 0
  std::array<float, 4> peel{};         // far_dir, far_lim, minimum separation (view units), cull ? 1 : 0
};
static_assert(sizeof(Uniforms) == 160);

struct Frame {
  Extent extent;            // viewport + 2 * guard band
  DepthModel model;         // from sao::analyze
  bool reversedZ = false;   // depth test GREATER, clear 0
  bool zeroToOneClip = false;
  bool flipY = false;       // rows are read back in reverse order
  double clearDepth = 1.0;
  Uniforms uniforms;
};

// Validates everything that does not depend on the API and fills `out`.
Status prepareFrame(const scenes::Mesh& mesh, const scenes::View& view, const Camera& camera,
                    const PrepassOptions& options, Frame& out);
// The same for a view given as its matrix, world -> camera (scenes::viewMatrix), without a mesh.
Status prepareFrame(const glm::dmat4& view, const Camera& camera, const PrepassOptions& options, Frame& out);

// Checks the mesh (at least one triangle, indices a multiple of 3 and in range, finite vertices)
// and returns a 64-bit digest of its contents, the key of the backends' upload cache.
Status checkMesh(const scenes::Mesh& mesh, std::uint64_t& digest);

// Three vertices per triangle, six floats each: world position (as stored) and the triangle's unit
// world-space face normal from the cross product of its float edges in double (0 if degenerate).
std::vector<float> expandMesh(const scenes::Mesh& mesh);
inline constexpr std::uint32_t kVertexFloats = 6;

// Reverses the row order of an image in place (Camera::flipY).
void flipRows(std::vector<std::uint32_t>& texels, Extent extent);
void flipRows(FloatImage& image);

// "D16", ... for messages.
const char* formatName(DepthFormat format);

}  // namespace sao::prepass::detail
