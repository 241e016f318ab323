// The length unit of a scene's coordinates, and the Camera::metersToViewUnits it gives. sao's
// settings are in metres; the effect converts them to the scene's (view) units with that factor.
#pragma once
#include <optional>
#include <string>
#include <string_view>

#include "sao/scenes/mesh.h"

namespace sao::scenes {

// m, cm, mm, in, ft, or auto: a scale derived from the mesh's bounding box (autoMetersToViewUnits).
enum class LengthUnit { Metre, Centimetre, Millimetre, Inch, Foot, Auto };

// "m", "cm", "mm", "in", "ft", "auto" (lower case only); nullopt for any other word.
std::optional<LengthUnit> parseLengthUnit(std::string_view name);
std::string_view toString(LengthUnit unit);
// The words parseLengthUnit accepts, for messages: "m, cm, mm, in, ft or auto".
inline constexpr std::string_view kLengthUnitNames = "m, cm, mm, in, ft or auto";

// Scene units per metre: m 1, cm 100, mm 1000, in 1/0.0254, ft 1/0.3048. Not for Auto.
double metersToViewUnits(LengthUnit unit);

// The bounding-box diagonal, in metres, that `auto` gives a mesh: the size at which the default
// settings (radius 1 m) suit a single object. Measured against the ray-traced reference at 3, 5,
// 10 and 20 m on the Stanford bunny and assimp's spider.obj, 5 m gave the best SSIM on both and a
// best-fit occlusion scale of 0.84 / 1.01 (2.0 at 10 m, 6.7 at 20 m: too white; 0.6-0.7 at 3 m).
inline constexpr double kAutoDiagonalMetres = 5.0;

// The unit a scene states for itself, and where it says so ("built-in scene", "glTF: metres by
// its specification", "PATH:LINE").
struct DeclaredUnits {
  LengthUnit unit = LengthUnit::Metre;
  std::string source;
};

// auto: the mesh's bounding-box diagonal (in its own units) divided by kAutoDiagonalMetres,
// rounded to 3 significant digits (so that the printed figure is the one used). Not a claim about
// the file's real unit: OBJ and PLY carry none. The mesh must pass validateMesh (a diagonal > 0);
// the result is clamped to Camera's supported range [1e-6, 1e6] and says so in `note`.
struct UnitChoice {
  double metersToViewUnits = 1.0;
  std::string unit = "m";  // "m", "cm", "mm", "in", "ft", or "auto"
  std::string note;        // how it was chosen, for the summary and (for auto) stderr
};

// The units of a scene: `requested` (a program's --units; nullopt when not given) wins; otherwise
// the scene's declared unit (built-in scenes and glTF: metres; a scene file's `units` line); with
// neither, metres (the default: OBJ and PLY carry no unit). Auto, requested or declared, keeps a
// concrete declared unit (glTF is metres by its specification) and derives the scale of the rest
// from the bounding box.
UnitChoice chooseUnits(const Mesh& mesh, const std::optional<DeclaredUnits>& declared,
                       std::optional<LengthUnit> requested);

}  // namespace sao::scenes
