// The camera the depth buffer was rendered with, and the conventions of that depth buffer.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "sao/status.h"

namespace sao {

enum class ClipDepth : std::uint8_t {
  NegativeOneToOne,  // OpenGL default: depth = 0.5 * ndc.z + 0.5
  ZeroToOne,         // Vulkan, D3D, or GL with glClipControl(..., GL_ZERO_TO_ONE): depth = ndc.z
};

enum class ProjectionKind : std::uint8_t { Perspective, Orthographic };

// How a supplied normals texture (the normals input, NORMALS_SUPPLIED) holds each normal; the
// values are the effect's SAO_NORMALS_* constants. Camera space is the one of the projection
// (right-handed, looking down -z). World-space encodings need Camera::viewRotation. Octahedral:
// the unit normal's signed octahedral map in .xy, in [-1, 1]^2 (docs/effect-math.md, section 5.2);
// .zw are ignored. Texture channels, one contract on every backend (checkNormalsChannels): the xyz
// encodings need three or four channels (rgba16f recommended); the octahedral ones two or more
// (e.g. rg16f, rg16_snorm), since a channel the texture lacks would read 0, a silently wrong normal.
enum class NormalsEncoding : std::uint8_t {
  CameraXyz,         // camera-space normal in .xyz (the default)
  WorldXyz,          // world-space normal in .xyz
  CameraOctahedral,  // camera-space normal, octahedral in .xy
  WorldOctahedral,   // world-space normal, octahedral in .xy
};

// Which sample of a multisampled depth texel stands for the texel (the values are the effect's
// SAO_DEPTH_SAMPLE_* constants). The effect reads MSAA depth directly, with no resolve pass;
// single-sample depth has one sample, and both policies read it.
enum class DepthSamplePolicy : std::uint8_t {
  Sample0,  // sample 0 (the default): what a blit of a multisampled depth buffer gives on most drivers
  Nearest,  // the sample nearest to the camera (sky only when every sample is sky): a silhouette
            // texel takes the foreground, as a min/max depth resolve would
};

struct Camera {
  // Column-major like GLM: element (row r, column c) is projection[c * 4 + r]. Right-handed view
  // space looking down -z, as the paper assumes.
  std::array<double, 16> projection{};
  ProjectionKind kind = ProjectionKind::Perspective;
  ClipDepth clipDepth = ClipDepth::NegativeOneToOne;
  bool reversedZ = false;    // the near plane maps to depth 1, the far plane to 0
  bool infiniteFar = false;  // the projection has no far plane
  // Rows of the depth image are in the order the API stores them: row 0 at ndc.y = -1 (GL's bottom
  // row, Vulkan's top row). Set when rendering with a flipped viewport (negative height in Vulkan).
  bool flipY = false;
  double metersToViewUnits = 1.0;  // settings are in metres; view space may use other units
  std::uint32_t width = 0;         // visible viewport, pixels
  std::uint32_t height = 0;
  std::uint32_t guardBand = 0;     // extra pixels rendered on every side of the viewport
  // Optional: the near and far distances (view units; far may be +inf) the matrix was built with.
  // The matrix alone cannot tell GL's [-1,1] clip range from [0,1] (a standard GL matrix is also a
  // valid [0,1] projection whose near plane lies at 2fn/(f+n); a reversed one keeps its near plane
  // and moves its far plane), so a wrong clipDepth would silently shift every z. When > 0,
  // analyze() rejects a camera whose matrix, read with the declared conventions, disagrees.
  double expectedNear = 0;
  double expectedFar = 0;
  // The normals input's encoding (G-buffer convention, like the depth conventions above).
  NormalsEncoding normalsEncoding = NormalsEncoding::CameraXyz;
  // The world -> camera rotation (the view matrix's upper-left 3x3, a pure rotation), column-major
  // like `projection`: element (row r, column c) is viewRotation[c * 3 + r]; n_camera = R n_world.
  // Required by the world-space encodings; whenever set, computeConstants() refuses anything but a
  // rotation (columns of unit length and mutually orthogonal to 1e-4, determinant +1, finite).
  std::optional<std::array<double, 9>> viewRotation;
  // Optional: the world -> camera transform (the view matrix), column-major 4x4 like `projection`,
  // rigid (a rotation and a translation in view units; last row 0 0 0 1). Temporal accumulation
  // (the `temporal` setting) needs it on every frame's camera: the previous frame's history is
  // found by moving each pixel's point from this camera into the previous one. Whenever set,
  // computeConstants() refuses anything but a rigid transform (as for viewRotation, to 1e-4), and
  // one whose rotation differs from viewRotation's when both are set.
  std::optional<std::array<double, 16>> view;
  // A multisampled depth input's sample per texel (the depth buffer's convention, like clipDepth).
  DepthSamplePolicy depthSamplePolicy = DepthSamplePolicy::Sample0;
  bool operator==(const Camera&) const = default;
};

// The normals texture contract above: the channels `encoding` reads (3 for the xyz encodings, 2
// for the octahedral ones; 0 for a value outside the enum, which computeConstants names).
std::uint32_t normalsChannelsRead(NormalsEncoding encoding);

// The contract for a texture of `channels` colour channels: Ok, or UnsupportedFormat "<format> (two channels) but Camera::normalsEncoding is CameraXyz, which reads
// .xyz: use an octahedral encoding or a three- or four-channel <noun>". `format` names the texture
// as the backend does ("sao::gl: the normals texture 7 is GL_RG16F"), `noun` is "texture" or
// "format". An encoding outside the enum passes here. Builds the message only on failure, but the
// caller builds `format`: a per-frame caller tests normalsChannelsRead() first.
Status checkNormalsChannels(NormalsEncoding encoding, std::uint32_t channels, const std::string& format,
                            const char* noun);

// What the projection says about itself, derived in double precision.
struct DepthModel {
  // Perspective: z = c0 / (d * c1 + c2). Orthographic: z = d * c1 + c2. d is the stored depth.
  double c0 = 0, c1 = 0, c2 = 0;
  double nearDistance = 0;    // > 0 for perspective
  double farDistance = 0;     // +inf when infinite
  double depthAtNear = 0;     // stored depth of the near plane (0 or 1)
  double depthAtFar = 1;      // stored depth of the far plane (the clear value)
};

// Checks the camera and derives its depth model. Rejects matrices that are not a perspective or
// orthographic projection of the declared kind, a declared reversed-Z or infinite far plane that
// the matrix contradicts, near/far planes other than expectedNear/expectedFar (when set: a wrong
// clipDepth), near <= 0 for perspective, non-finite entries and bad sizes.
Status analyze(const Camera& camera, DepthModel& out);

// Camera-space z of a stored depth value, in double (the reference the shaders approximate).
double linearZ(const DepthModel& model, ProjectionKind kind, double depth);

// Builders for tests and samples: GLM-style matrices for each convention (expectedNear left 0).
// They do not check their arguments: numbers that come from a user go through
// checkPerspectiveArguments / checkOrthographicArguments first, which name the bad argument
// (near == far would otherwise surface as "a non-finite element", near > far as "set reversedZ").
Camera perspectiveCamera(double fovyRadians, std::uint32_t width, std::uint32_t height, double nearDistance,
                         double farDistance /* inf for infinite */, ClipDepth clip, bool reversedZ);
Camera orthographicCamera(double halfHeight, std::uint32_t width, std::uint32_t height, double nearDistance,
                          double farDistance, ClipDepth clip, bool reversedZ);

// Ok, or InvalidCamera naming the first bad argument of the builder: fovy outside (0, pi) or
// halfHeight <= 0, an empty viewport or a side above kMaxImageSide, near not finite or (perspective) not > 0,
// far not beyond near (perspective: far may be +inf; orthographic: finite).
Status checkPerspectiveArguments(double fovyRadians, std::uint32_t width, std::uint32_t height, double nearDistance,
                                 double farDistance);
Status checkOrthographicArguments(double halfHeight, std::uint32_t width, std::uint32_t height, double nearDistance,
                                  double farDistance);

}  // namespace sao
