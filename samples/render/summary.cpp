#include "summary.h"

#include <cmath>
#include <sstream>

namespace sao::samples {

ErrorMetrics compareToReference(const FloatImage& ao, const FloatImage& ref, const FloatImage& positions,
                                std::uint32_t g) {
  ErrorMetrics m;
  double sq = 0, bias = 0;
  std::size_t over = 0;
  for (std::uint32_t y = 0; y < ao.extent.height; ++y)
    for (std::uint32_t x = 0; x < ao.extent.width; ++x) {
      if (positions.at(x + g, y + g, 3) == 0.0f) continue;
      const double d = double(ao.at(x, y)) - ref.at(x, y);
      sq += d * d;
      bias += d;
      over += std::fabs(d) > 0.1;
      ++m.pixels;
    }
  if (m.pixels) {
    m.rmse = std::sqrt(sq / m.pixels);
    m.meanBias = bias / m.pixels;
    m.fractionOver01 = double(over) / m.pixels;
  }
  return m;
}

std::string Summary::text() const {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(3);
  s << "backend: " << backend << "\ninput: " << input << "\nsize: " << size.width << "x" << size.height
    << " (guard band " << guard << ")\nsettings:";
  for (std::size_t i = 0; i < gen::kSettings.size(); ++i)
    s << " " << gen::kSettings[i].name << "=" << gen::settingValue(settings, static_cast<SettingId>(i));
  s << "\nplan: " << plan.describe();
  s << "timing (" << toString(timings.method) << "):";
  for (const auto& p : timings.passes) s << " " << p.pass << " " << p.milliseconds << " ms;";
  s << " total " << timings.totalMilliseconds() << " ms\n";
  s << "depth preparation: " << prepareSeconds << " s\n";
  if (metrics) {
    s.precision(4);
    s << "vs ray-traced near-field AO (" << referenceRays << " rays/pixel, radius " << settings.radius
      << " m; screen-space AO sees only the first depth layer and nothing off-screen): RMSE " << metrics->rmse
      << ", mean bias " << metrics->meanBias << ", pixels off by > 0.1: " << 100.0 * metrics->fractionOver01
      << " % of " << metrics->pixels << " (raw, no intensity fit)\n";
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
  if (metrics)
    s << ",\n  \"reference\": {\"rays\": " << referenceRays << ", \"pixels\": " << metrics->pixels
      << ", \"rmse\": " << metrics->rmse << ", \"mean_bias\": " << metrics->meanBias
      << ", \"fraction_over_0_1\": " << metrics->fractionOver01 << "}";
  s << "\n}\n";
  return s.str();
}

}  // namespace sao::samples
