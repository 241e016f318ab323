#include "summary.h"

#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "sao/samples/shortest_float.h"

namespace sao::samples {
namespace {

// A metric to 4 decimals, or "n/a" where it is undefined (NaN: sao/samples/metrics.h).
std::string metric(double v, double scale = 1.0) {
  if (!isDefined(v)) return "n/a";
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(4);
  s << v * scale;
  return s.str();
}

}  // namespace

std::string Summary::text() const {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(3);
  s << "backend: " << backend << "\ninput: " << input << "\nprojection: " << projection << "\nsize: " << size.width << "x" << size.height
    << " (guard band " << guard << ")\nsettings:";
  for (std::size_t i = 0; i < gen::kSettings.size(); ++i) {
    // As the metadata types them: ints and bools as integers, floats to 6 significant digits
    // (epsilon 0.0001 must not read as 0.000).
    const double v = gen::settingValue(settings, static_cast<SettingId>(i));
    std::ostringstream value;
    if (gen::kSettings[i].type == gen::SettingType::Float) value << v;
    else value << static_cast<long long>(v);
    s << " " << gen::kSettings[i].name << "=" << value.str();
  }
  s << "\nplan: " << plan.describe();
  s << "timing (" << toString(timing.method) << ", median of " << timing.runs << " run" << (timing.runs == 1 ? "" : "s")
    << " after 1 warm-up run):";
  for (const auto& p : timing.passes) s << " " << p.pass << " " << p.ms.median << " ms;";
  s << " total " << timing.total.median << " ms\n";
  s << "timing spread (fastest..slowest of " << timing.runs << "):";
  for (const auto& p : timing.passes) s << " " << p.pass << " " << p.ms.min << ".." << p.ms.max << " ms;";
  s << " total " << timing.total.min << ".." << timing.total.max << " ms\n";
  s << "depth preparation: " << prepareSeconds << " s\n";
  if (!units.empty()) s << "units: " << units << "\n";
  for (const std::string& w : inputWarnings) s << "warning: " << w << "\n";
  if (frames) s << frames->text();
  if (scale) {
    std::ostringstream g;
    g << "geometry: " << scale->geometryPixels << " pixels; AO min " << scale->aoMin << ", mean " << scale->aoMean
      << "; radius " << settings.radius << " m = " << settings.radius * metersToViewUnits << " scene units, projected "
      << scale->radiusPxMedian << " px (median), below 1 px on " << 100.0 * scale->fractionBelowOnePx
      << " %, beyond the image on " << 100.0 * scale->fractionAboveImage << " %\n";
    s << g.str();  // default float format: 6 significant digits
    for (const std::string& w : scale->warnings) s << "warning: " << w << "\n";
  }
  if (metrics) {
    s.precision(4);
    s << "vs ray-traced near-field AO (" << referenceRays << " rays/pixel, radius " << settings.radius
      << " m; screen-space AO sees only the first depth layer and nothing off-screen), " << metrics->raw.pixels
      << " pixels with geometry:\n";
    auto row = [&](const char* what, const ErrorMetrics& m) {
      s << "  " << what << ": RMSE " << metric(m.rmse) << ", mean bias " << metric(m.meanBias) << ", SSIM "
        << metric(m.ssim) << ", off by > 0.1: " << metric(m.fractionOver01, 100.0) << " %; where the reference is 1 ("
        << m.openPixels << " pixels): mean darkening " << metric(m.openDarkening) << ", below 0.9 "
        << metric(m.openShareUnder09, 100.0) << " %\n";
    };
    row("raw", metrics->raw);
    s << "  best-fit occlusion scale " << metric(metrics->fittedIntensity)
      << (isDefined(metrics->fittedIntensity) ? "" : " (the AO shows no occlusion: every scale fits alike)") << "\n";
    row("fitted", metrics->fitted);
  }
  return s.str();
}

std::string Summary::json() const {
  using Json = nlohmann::ordered_json;
  Json j;
  j["backend"] = backend;
  j["input"] = input;
  j["projection"] = projection;
  if (frames)
    j["frames"] = {{"count", frames->frames}, {"path", frames->path}, {"flicker", frames->meanFlicker},
                   {"compared_fraction", frames->comparedFraction}, {"effect_ms_median", frames->medianEffectMs}};
  j["width"] = size.width;
  j["height"] = size.height;
  j["guard_band"] = guard;
  Json& values = j["settings"] = Json::object();
  for (std::size_t i = 0; i < gen::kSettings.size(); ++i) {
    const double v = gen::settingValue(settings, static_cast<SettingId>(i));
    const std::string name(gen::kSettings[i].name);
    if (gen::kSettings[i].type == gen::SettingType::Float) values[name] = shortestDecimal(float(v));
    else values[name] = static_cast<long long>(v);
  }
  Json passes = Json::array();
  for (const auto& p : plan.passes) passes.push_back(std::string(gen::pass(p.pass).name));
  j["plan"] = {{"csz_levels", plan.cszLevels}, {"bytes", plan.totalBytes}, {"passes", passes}};
  j["timing_method"] = toString(timing.method);
  j["runs"] = timing.runs;  // measured, after one warm-up run
  Json median = Json::object(), fastest = Json::object(), slowest = Json::object();
  for (const auto& p : timing.passes) {
    median[p.pass] = p.ms.median;
    fastest[p.pass] = p.ms.min;
    slowest[p.pass] = p.ms.max;
  }
  j["pass_ms"] = median;
  j["pass_ms_min"] = fastest;
  j["pass_ms_max"] = slowest;
  j["total_ms"] = timing.total.median;
  j["total_ms_min"] = timing.total.min;
  j["total_ms_max"] = timing.total.max;
  j["units"] = {{"how", units}, {"meters_to_view_units", metersToViewUnits}};
  if (scale) {
    j["geometry"] = {{"pixels", scale->geometryPixels},
                     {"ao_min", scale->aoMin},
                     {"ao_mean", scale->aoMean},
                     {"radius_px_median", scale->radiusPxMedian},
                     {"fraction_radius_below_1px", scale->fractionBelowOnePx},
                     {"fraction_radius_beyond_image", scale->fractionAboveImage}};
  }
  std::vector<std::string> warnings = inputWarnings;
  if (scale) warnings.insert(warnings.end(), scale->warnings.begin(), scale->warnings.end());
  j["warnings"] = warnings;
  if (metrics) {
    // NaN (undefined) serialises as null.
    auto obj = [](const ErrorMetrics& m) {
      return Json{
          {"rmse", m.rmse}, {"mean_bias", m.meanBias}, {"ssim", m.ssim}, {"fraction_over_0_1", m.fractionOver01},
          {"open_pixels", m.openPixels}, {"open_darkening", m.openDarkening}, {"open_share_under_0_9", m.openShareUnder09}};
    };
    j["reference"] = {{"rays", referenceRays},        {"pixels", metrics->raw.pixels},
                      {"raw", obj(metrics->raw)},      {"fitted_intensity", metrics->fittedIntensity},
                      {"fitted", obj(metrics->fitted)}};
  }
  // Invalid UTF-8 in a path (any byte sequence is a valid Linux file name) is replaced, not thrown.
  return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace sao::samples
