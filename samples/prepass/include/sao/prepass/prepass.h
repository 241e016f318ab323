// A rasterising depth prepass (SAO paper, section 2.1): the scene mesh drawn into a hardware depth
// buffer of the chosen format, with camera-space positions and face normals written in the same
// pass, and optionally a second depth layer by depth peeling with a minimum separation (the deep
// G-buffer input of the effect's TWO_LAYER variant). Everything is read back to the CPU in the
// exact form raytrace::castPrimary produces, so the CPU, OpenGL and Vulkan runners consume the
// rasterised depth exactly as they consume the ray-cast one.
//
// Conventions (the same as raytrace::castPrimary):
//  * The image is the depth input of the effect: (width + 2 g) x (height + 2 g) texels for the
//    camera's guard band g. The camera's projection covers the viewport; the prepass widens the
//    frustum by g pixels on every side at the same pixel scale, so texel (x, y) is sampled at its
//    centre, ndc = 2 (x - g + 0.5) / width - 1 (and likewise for y).
//  * Row 0 is at ndc y = -1 (GL's bottom row, Vulkan's top row with a positive viewport height);
//    with Camera::flipY, row 0 is at ndc y = +1 (the rows are read back in that order).
//  * Texels nothing covers hold the clear value: 1 for standard depth, 0 for reversed-Z (the
//    effect's sky), position and normal (0, 0, 0, 0).
//  * Camera space is right-handed, looking down -z, in view units: the world-space mesh (metres)
//    times Camera::metersToViewUnits.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "sao/camera.h"
#include "sao/image.h"
#include "sao/scenes/mesh.h"
#include "sao/scenes/scene.h"
#include "sao/status.h"

namespace sao::prepass {

struct PrepassOptions {
  DepthFormat format = DepthFormat::D32F;  // D16, D24 or D32F (LinearZ: UnsupportedFormat)
  bool secondLayer = false;                // render depth2 / position2 / normal2 by depth peeling
  // The second layer keeps, per pixel, the nearest surface more than this many metres behind the
  // first layer (in camera-space z). Must be finite and > 0: at 0 the first surface itself would
  // pass wherever float rounding puts its fragment a hair behind its own stored depth.
  double minSeparation = 0.1;
  // The second layer takes only triangles that face the camera as wound (counter-clockwise seen
  // from outside, scenes::MeshBuilder's convention), so that behind a closed object it holds the
  // next surface (the floor behind a sphere) rather than the object's own far side. The first
  // layer never culls (thin panels are seen from both sides).
  bool cullBackFacesInSecondLayer = true;
};

struct PrepassResult {
  DepthImage depth;     // the format's exact bits: D16 / D24 integers, D32F float bits
  FloatImage position;  // RGBA: camera-space x, y, z, 1 where covered; 0 where nothing is
  FloatImage normal;    // RGBA: camera-space unit face normal facing the camera, w = 0 (as castPrimary)
  // Only with PrepassOptions::secondLayer (otherwise empty): the peeled layer, same conventions.
  DepthImage depth2;
  FloatImage position2;
  FloatImage normal2;
};

// The work both backends share: a mesh, a view and a camera in, a PrepassResult out. Objects are
// reusable across calls (the mesh upload is kept while the same mesh object with the same sizes
// comes back; images are kept while the extent and format stay) and free everything they made.
class Prepass {
 public:
  virtual ~Prepass() = default;
  virtual std::string_view name() const = 0;       // "gl" or "vulkan"
  virtual std::string description() const = 0;     // device and driver in words
  // Whether the backend renders depth with this clip-space convention (Vulkan: ZeroToOne only).
  virtual bool supportsClip(ClipDepth clip) const = 0;
  // On failure `out` is empty and the Status says why:
  // InvalidInput: empty mesh, indices not a multiple of 3 or out of range, non-finite vertex, bad
  //   minSeparation (with secondLayer).
  // InvalidExtent: a zero viewport, or an image (viewport + 2 x guard band) beyond the device's limits.
  // InvalidCamera: from sao::analyze, a degenerate view, or a clip convention the backend does not
  //   have (supportsClip).
  // UnsupportedFormat: LinearZ, or a depth format the device cannot render (sample, copy).
  // DriverError: the API failed.
  virtual Status render(const scenes::Mesh& mesh, const scenes::View& view, const Camera& camera,
                        const PrepassOptions& options, PrepassResult& out) = 0;
};

// "gl", "vulkan" or "auto" (the first of gl, vulkan that starts): a prepass on its own headless
// context or device. DriverError when the API is missing or not built into this program.
Status createPrepass(std::string_view name, std::unique_ptr<Prepass>& out);

}  // namespace sao::prepass
