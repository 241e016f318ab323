#include "summary.h"

#include <cmath>
#include <sstream>

namespace sao::samples {

std::string Summary::text() const {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(3);
  s << "backend: " << backend << "\ninput: " << input << "\nsize: " << size.width << "x" << size.height
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
  s << "timing (" << toString(timings.method) << "):";
  for (const auto& p : timings.passes) s << " " << p.pass << " " << p.milliseconds << " ms;";
  s << " total " << timings.totalMilliseconds() << " ms\n";
  s << "depth preparation: " << prepareSeconds << " s\n";
  if (metrics) {
    s.precision(4);
    s << "vs ray-traced near-field AO (" << referenceRays << " rays/pixel, radius " << settings.radius
      << " m; screen-space AO sees only the first depth layer and nothing off-screen), " << metrics->raw.pixels
      << " pixels with geometry:\n";
    auto row = [&](const char* what, const ErrorMetrics& m) {
      s << "  " << what << ": RMSE " << m.rmse << ", mean bias " << m.meanBias << ", SSIM " << m.ssim
        << ", off by > 0.1: " << 100.0 * m.fractionOver01 << " %\n";
    };
    row("raw", metrics->raw);
    s << "  best-fit occlusion scale " << metrics->fittedIntensity << "\n";
    row("fitted", metrics->fitted);
  }
  return s.str();
}

std::string Summary::json() const {
  std::ostringstream s;
  s.precision(9);
  auto quote = [](const std::string& t) {
    std::string o = "\"";
    for (char c : t) {
      if (c == '"' || c == '\\') o += '\\';
      if (c == '\n') {
        o += "\\n";
        continue;
      }
      o += c;
    }
    return o + "\"";
  };
  s << "{\n  \"backend\": " << quote(backend) << ",\n  \"input\": " << quote(input) << ",\n  \"width\": " << size.width
    << ",\n  \"height\": " << size.height << ",\n  \"guard_band\": " << guard << ",\n  \"settings\": {";
  for (std::size_t i = 0; i < gen::kSettings.size(); ++i)
    s << (i ? ", " : "") << quote(std::string(gen::kSettings[i].name)) << ": "
      << gen::settingValue(settings, static_cast<SettingId>(i));
  s << "},\n  \"plan\": {\"csz_levels\": " << plan.cszLevels << ", \"bytes\": " << plan.totalBytes << ", \"passes\": [";
  for (std::size_t i = 0; i < plan.passes.size(); ++i)
    s << (i ? ", " : "") << quote(std::string(gen::pass(plan.passes[i].pass).name));
  s << "]},\n  \"timing_method\": " << quote(toString(timings.method)) << ",\n  \"pass_ms\": {";
  for (std::size_t i = 0; i < timings.passes.size(); ++i)
    s << (i ? ", " : "") << quote(timings.passes[i].pass) << ": " << timings.passes[i].milliseconds;
  s << "},\n  \"total_ms\": " << timings.totalMilliseconds();
  if (metrics) {
    auto obj = [&](const ErrorMetrics& m) {
      std::ostringstream o;
      o.precision(9);
      o << "{\"rmse\": " << m.rmse << ", \"mean_bias\": " << m.meanBias << ", \"ssim\": " << m.ssim
        << ", \"fraction_over_0_1\": " << m.fractionOver01 << "}";
      return o.str();
    };
    s << ",\n  \"reference\": {\"rays\": " << referenceRays << ", \"pixels\": " << metrics->raw.pixels
      << ", \"raw\": " << obj(metrics->raw) << ", \"fitted_intensity\": " << metrics->fittedIntensity
      << ", \"fitted\": " << obj(metrics->fitted) << "}";
  }
  s << "\n}\n";
  return s.str();
}

}  // namespace sao::samples
