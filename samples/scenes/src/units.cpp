// Scene units: the words, their factors, and the choice between --units, the scene's own unit and
// the bounding box.
#include "sao/scenes/units.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace sao::scenes {

namespace {

constexpr struct {
  LengthUnit unit;
  std::string_view name;
} kUnits[] = {{LengthUnit::Metre, "m"},      {LengthUnit::Centimetre, "cm"}, {LengthUnit::Millimetre, "mm"},
              {LengthUnit::Inch, "in"},      {LengthUnit::Foot, "ft"},       {LengthUnit::Auto, "auto"}};

// The camera's supported range of metersToViewUnits (backends/core/src/camera.cpp).
constexpr double kMinFactor = 1e-6, kMaxFactor = 1e6;

std::string format(const char* pattern, double a, double b = 0) {
  char text[160];
  std::snprintf(text, sizeof text, pattern, a, b);
  return text;
}

double diagonal(const Mesh& mesh) {
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi = -lo;
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  return mesh.positions.empty() ? 0.0 : glm::length(hi - lo);
}

UnitChoice fromBoundingBox(const Mesh& mesh, const std::string& why) {
  const double d = diagonal(mesh);
  UnitChoice c;
  c.unit = "auto";
  double u = d / kAutoDiagonalMetres;
  if (u > 0 && std::isfinite(u)) u = std::stod(format("%.3g", u));  // the printed figure is the one used
  const double unclamped = u;
  if (!(u >= kMinFactor)) u = kMinFactor;  // also for a diagonal of 0 (a mesh that failed validation)
  u = std::min(u, kMaxFactor);
  c.metersToViewUnits = u;
  c.note = "auto (" + why + "): bounding-box diagonal " + format("%.4g", d) + " units taken as " +
           format("%g m, 1 m = %g units", d / u, u) + (u == unclamped ? "" : " (the limit of [1e-6, 1e6])");
  return c;
}

}  // namespace

std::optional<LengthUnit> parseLengthUnit(std::string_view name) {
  for (const auto& u : kUnits)
    if (u.name == name) return u.unit;
  return std::nullopt;
}

std::string_view toString(LengthUnit unit) {
  for (const auto& u : kUnits)
    if (u.unit == unit) return u.name;
  return "?";
}

double metersToViewUnits(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::Centimetre: return 100.0;
    case LengthUnit::Millimetre: return 1000.0;
    case LengthUnit::Inch: return 1.0 / 0.0254;
    case LengthUnit::Foot: return 1.0 / 0.3048;
    default: return 1.0;
  }
}

UnitChoice chooseUnits(const Mesh& mesh, const std::optional<DeclaredUnits>& declared,
                       std::optional<LengthUnit> requested) {
  auto concrete = [](LengthUnit unit, const std::string& why) {
    UnitChoice c;
    c.unit = std::string(toString(unit));
    c.metersToViewUnits = metersToViewUnits(unit);
    c.note = c.unit + " (" + why + ")";
    if (unit != LengthUnit::Metre) c.note += format(": 1 m = %g units", c.metersToViewUnits);
    return c;
  };
  const bool declaredConcrete = declared && declared->unit != LengthUnit::Auto;
  if (requested && *requested != LengthUnit::Auto) return concrete(*requested, "--units");
  if (requested) {  // --units auto
    if (declaredConcrete) return concrete(declared->unit, "--units auto keeps the unit of " + declared->source);
    return fromBoundingBox(mesh, "--units auto");
  }
  if (declaredConcrete) return concrete(declared->unit, declared->source);
  if (declared) return fromBoundingBox(mesh, declared->source);
  return concrete(LengthUnit::Metre, "the default: the file states no unit, see --units");
}

}  // namespace sao::scenes
