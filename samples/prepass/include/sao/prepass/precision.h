// How well camera-space z and face normals survive the depth buffer (SAO paper, section 2.1 and
// Figures 3 and 4): for each depth format x far plane x convention, the scene is rasterised by a
// prepass, z is reconstructed from the stored depth exactly as the effect's linear_z pass does it
// (the CPU reference in float mode, i.e. the GPU's arithmetic: eq. 2 with the block constants of
// computeConstants), the face normal is reconstructed from that z exactly as ao_sample does it
// (docs/effect-math.md 5.2: cross product of the screen-space differences of reconstructed
// positions), and both are compared with the truth, binned by distance.
#pragma once
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "sao/prepass/prepass.h"

namespace sao::prepass {

struct PrecisionOptions {
  std::uint32_t width = 1280, height = 720;
  std::vector<DepthFormat> formats{DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F};
  // Finite far planes in metres and/or INFINITY (the paper's eq. 2 covers both).
  std::vector<double> farPlanes{1000.0, INFINITY};
  bool standard = true;  // near -> 0: GL's [-1, 1] clip where the backend has it, else [0, 1]
  bool reversed = true;  // near -> 1, [0, 1] clip
  // Bins of true distance along the view axis (-z, metres): bin i is [c_i / sqrt(10), c_i * sqrt(10)).
  std::vector<double> binCentres{1.0, 10.0, 100.0};
};

struct PrecisionRow {
  DepthFormat format = DepthFormat::D32F;
  double farPlane = 0;  // metres, or +inf
  bool reversed = false;
  ClipDepth clip = ClipDepth::ZeroToOne;
  double distanceBin = 0;  // the bin's centre, metres
  double zWorstM = 0, zP99M = 0;              // |z reconstructed - z true|, metres
  double normalWorstDeg = 0, normalP99Deg = 0;  // angle between reconstructed and true face normal
  std::size_t pixels = 0;  // pixels measured: inside a face (the pixel and its 4 neighbours on the same face)
  std::size_t lost = 0;    // of those, pixels whose stored depth reads as sky (clear value or beyond the far plane)
};

// The dedicated scene: three tilted panels (45 degrees to the view axis), one in each third of
// the screen, centred 1, 10 and 100 m away, seen from the origin down -z (fovy 1 rad, near 0.1 m),
// with vertices exactly representable in float so that the analytic truth is the rasterised plane.
struct PrecisionPanel {
  glm::dvec3 corner, edgeU, edgeV;  // the parallelogram corner + s edgeU + t edgeV, s, t in [0, 1]
};
// `aspect` is width / height of the image the scene will be rendered at.
void precisionScene(double aspect, scenes::Mesh& mesh, scenes::View& view, std::vector<PrecisionPanel>& panels);

// Runs the measurement on the dedicated scene with analytic truth. Rows in the order format x far
// plane x convention (standard first) x bin; bins without pixels are left out.
Status measurePrecision(Prepass& prepass, const PrecisionOptions& options, std::vector<PrecisionRow>& rows);

// The same on any mesh and view, with the truth from raytrace::castPrimary (Embree, float hit
// distances: its own z error is about 1e-7 relative, which bounds what can be measured). Pixels
// count as inside a face where the ray-cast normals of the pixel and its 4 neighbours agree to
// 1e-5 rad.
Status measurePrecision(Prepass& prepass, const scenes::Mesh& mesh, const scenes::View& view,
                        const PrecisionOptions& options, std::vector<PrecisionRow>& rows);

// A fixed-width text table of the rows.
std::string formatPrecisionTable(const std::vector<PrecisionRow>& rows);

}  // namespace sao::prepass
