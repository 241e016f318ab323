// The scenes sao-bench measures, prepared once per size: the ray caster, the depth every backend is
// given (rasterised by a prepass or ray-cast), and the three references, each computed on first use
// and cached by the settings it depends on. Shared by the sections and the tuner.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "sao/prepass/prepass.h"
#include "sao/raytrace/raytrace.h"
#include "sao/samples/backend_runner.h"
#include "sao/scenes/scene.h"

namespace sao::bench {

// Prints "sao-bench: <message>" and exits with status 1 (the tool stops at its first failure).
[[noreturn]] void fail(const std::string& message);

// The built-in scenes every section and the tuner measure (--quick: two small ones).
std::vector<std::string> benchScenes(bool quick);

// The two_layer section's second depth layer: the first surface at least this far (metres, in
// camera-space z) behind the first (depth peeling, or raytrace::castSecondLayer).
constexpr double kSecondLayerSeparation = 0.5;

// The settings the obscurance reference depends on: radius, intensity, bias, epsilon, contrast.
using ObscuranceKey = std::tuple<float, float, float, float, float>;
ObscuranceKey obscuranceKey(const Settings& s);

// What the effect is given besides depth; the inputs select the shader variant (NORMALS_SUPPLIED,
// TWO_LAYER), as in every backend.
enum class Extra { None, Normals, SecondLayer };

// Reference (c) depends on the obscurance settings and on the inputs (normals, second layer).
using ConvergedKey = std::tuple<ObscuranceKey, Extra>;

// Reference (c) with its cost and the model error: (c) against (a) and (b), NaN until computed.
struct Converged {
  FloatImage ao;
  double seconds = 0, cpuSeconds = 0;  // wall and CPU (all threads) time
  double rmseVsAo = NAN, rmseVsObscurance = NAN;
  double noise = NAN;  // measured with a second seed: (c)'s own per-pixel noise (RMS over the mask)
  std::string modelMap;  // maps/ PNG of (c) - (a), relative to the output folder
};

// Reference (d) depends on the radius, the thickness, the depth tolerance, the inputs and the
// thickness model (ScreenOptions::thicknessFromWidth, unset: the setting thickness_model).
using ScreenKey = std::tuple<float, float, float, Extra, bool>;
ScreenKey screenKey(const Settings& s, Extra extra, std::optional<bool> thicknessFromWidth);

// Reference (d), converged screen-space visibility, with its cost and the two model errors that
// split (c) - (a): (d) against (a) (what screen space cannot see) and (c) against (d) (the
// estimator's definition), over `mask`; NaN until computed.
struct Screen {
  FloatImage ao;                    // V, NaN on the pixels the stride skips
  std::vector<unsigned char> mask;  // Prepared::mask on the pixels evaluated
  double seconds = 0, cpuSeconds = 0;
  double rmseVsAo = NAN, rmseConvergedVsScreen = NAN;
  std::string map;  // maps/ PNG of (d) - (a) (--maps-against d), relative to the output folder
};

// A scene at one size: its ray caster, primary rays, second layer and references.
struct Prepared {
  scenes::Scene scene;
  std::unique_ptr<raytrace::RayScene> rays;
  Camera camera;
  raytrace::Primary primary;
  std::vector<unsigned char> mask;
  std::map<double, FloatImage> references;  // (a) near-field AO per radius
  std::map<double, std::pair<double, double>> referenceNoise;  // (a)'s noise per radius: nearFieldNoise
  std::map<ObscuranceKey, FloatImage> obscurance;  // (b) per obscurance settings
  std::map<ConvergedKey, Converged> converged;     // (c) per obscurance settings and inputs
  std::map<ScreenKey, Screen> screen;              // (d) per radius, thickness, tolerance and inputs
  std::vector<unsigned char> silhouette;           // samples::silhouetteBand of the primary positions
  std::optional<raytrace::Primary> secondLayer;
};

// Prepared scenes by name and size. `prepass` null: the depth comes from Embree primary rays.
// Otherwise the rasterised depth (and the peeled second layer) of that prepass; the references
// still trace rays from its visible points.
class SceneCache {
 public:
  SceneCache(prepass::Prepass* prepass, std::optional<scenes::LengthUnit> units) : prepass_(prepass), units_(units) {}
  Prepared& prepare(const std::string& name, std::uint32_t width, std::uint32_t height);
  // Every scene's first view made orthographic (scenes::toOrthographic) from then on.
  void setOrthographic(bool on) { orthographic_ = on; }

 private:
  prepass::Prepass* prepass_;
  std::optional<scenes::LengthUnit> units_;
  bool orthographic_ = false;
  std::map<std::string, Prepared> scenes_;
};

// (a) near-field AO at `radius` metres.
const FloatImage& nearFieldReference(Prepared& p, double radius, std::uint32_t rays);
// (a)'s own noise at `radius` (computed with `rays` and a second seed on first use), as (c)'s is
// measured: first the RMS over the mask of the two images' difference / sqrt(2), second the same
// predicted from (a) alone, sqrt(mean V (1 - V) / rays) (its rays are independent: binomial).
std::pair<double, double> nearFieldNoise(Prepared& p, double radius, std::uint32_t rays);
// (b) the obscurance integral with the settings' radius, intensity, bias, epsilon and contrast.
const FloatImage& obscuranceReference(Prepared& p, const Settings& s, std::uint32_t rays);
// The second depth layer (the prepass's peeled one, or ray-cast on first use).
const raytrace::Primary& secondLayer(Prepared& p);

// The inputs the effect is given for `extra`, and a word for them ("depth", "depth+normals", ...).
samples::RunInputs runInputs(Prepared& p, Extra extra);
const char* inputsName(Extra extra);

struct ConvergedOptions {
  std::uint32_t taps = 4096;
  bool measureNoise = false;
  const FloatImage* nearFieldAo = nullptr;  // given: the model error (c) vs (a) is computed
  const FloatImage* obscurance = nullptr;   // given: (c) vs (b)
};
// Reference (c) for the settings and inputs, timed; cached per ConvergedKey (the first call's
// options decide the taps and which model errors are filled in).
Converged& convergedReference(Prepared& p, const Settings& s, Extra extra, const ConvergedOptions& options);

struct ScreenOptions {
  std::uint32_t slices = 64;
  std::uint32_t stride = 1;                 // every stride-th pixel in x and y (raytrace::ScreenVisibilityOptions)
  std::optional<bool> thicknessFromWidth;   // raytrace::ScreenVisibilityOptions's (unset: thickness_model)
  const FloatImage* nearFieldAo = nullptr;  // given: (d) vs (a) is computed
  const FloatImage* converged = nullptr;    // given: (c) vs (d)
};
// Reference (d) for the settings' radius and the inputs, timed; cached per ScreenKey (the first
// call's options decide).
Screen& screenReference(Prepared& p, const Settings& s, Extra extra, const ScreenOptions& options);

}  // namespace sao::bench
