#include "report.h"

#include <fstream>
#include <map>
#include <sstream>

#include "svg_plot.h"

namespace sao::bench {
namespace {

// A CSV field: quoted (with doubled quotes) only when it holds a comma or a quote.
std::string csv(const std::string& s) {
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string o = "\"";
  for (char c : s) o += c == '"' ? std::string("\"\"") : std::string(1, c);
  return o + "\"";
}

std::string json(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) o += c;
  }
  return o + "\"";
}

const char* kErrorColumns[] = {"rmse_raw", "bias_raw", "ssim_raw", "over_0_1_raw", "fitted_scale",
                               "rmse_fitted", "bias_fitted", "ssim_fitted", "over_0_1_fitted"};

// A metric as text: `undefined` ("n/a" in CSV, null in JSON) where it is NaN (samples/metrics.h).
std::string metric(double v, const char* undefined) {
  if (!samples::isDefined(v)) return undefined;
  std::ostringstream s;
  s << v;
  return s.str();
}

void csvErrors(std::ofstream& f, const std::optional<samples::ReferenceComparison>& e) {
  if (!e) {
    for (std::size_t i = 0; i < std::size(kErrorColumns); ++i) f << ",";
    return;
  }
  auto m = [](double v) { return metric(v, "n/a"); };
  f << "," << m(e->raw.rmse) << "," << m(e->raw.meanBias) << "," << m(e->raw.ssim) << "," << m(e->raw.fractionOver01)
    << "," << m(e->fittedIntensity) << "," << m(e->fitted.rmse) << "," << m(e->fitted.meanBias) << ","
    << m(e->fitted.ssim) << "," << m(e->fitted.fractionOver01);
}

void jsonErrors(std::ofstream& f, const char* key, const std::optional<samples::ReferenceComparison>& e) {
  if (!e) return;
  auto m = [](double v) { return metric(v, "null"); };
  f << ", \"" << key << "\": {\"pixels\": " << e->raw.pixels << ", \"rmse_raw\": " << m(e->raw.rmse)
    << ", \"bias_raw\": " << m(e->raw.meanBias) << ", \"ssim_raw\": " << m(e->raw.ssim)
    << ", \"over_0_1_raw\": " << m(e->raw.fractionOver01) << ", \"fitted_scale\": " << m(e->fittedIntensity)
    << ", \"rmse_fitted\": " << m(e->fitted.rmse) << ", \"bias_fitted\": " << m(e->fitted.meanBias)
    << ", \"ssim_fitted\": " << m(e->fitted.ssim) << ", \"over_0_1_fitted\": " << m(e->fitted.fractionOver01) << "}";
}

}  // namespace

double passMs(const Measurement& m, const char* name) {
  for (const auto& p : m.passes)
    if (p.pass == name) return p.milliseconds;
  return 0;
}

void writeCsv(const std::string& path, const std::vector<Row>& rows) {
  std::ofstream f(path);
  f << "section,scene,backend,preset,variant,inputs,shader_variant,width,height,radius_m,samples,use_z_hierarchy,"
       "blur_radius,runs,timing_method,linear_z_ms,mips_ms,ao_sample_ms,blur_h_ms,blur_v_ms,total_ms,ns_per_pixel,"
       "plan_bytes,csz_levels";
  for (const char* prefix : {"ao_", "obscurance_"})
    for (const char* c : kErrorColumns) f << "," << prefix << c;
  f << "\n";
  for (const auto& r : rows) {
    const auto& m = r.m;
    f << csv(r.section) << "," << csv(r.scene) << "," << csv(r.backend) << "," << csv(r.preset) << ","
      << csv(r.variant) << "," << csv(r.inputs) << "," << csv(m.shaderVariant) << "," << r.size.width << ","
      << r.size.height << "," << r.settings.radius << "," << r.settings.samples << "," << r.settings.use_z_hierarchy
      << "," << r.settings.blur_radius << "," << m.runs << "," << csv(toString(m.method)) << ","
      << passMs(m, "linear_z") << "," << passMs(m, "mips") << "," << passMs(m, "ao_sample") << ","
      << passMs(m, "blur_h") << "," << passMs(m, "blur_v") << "," << m.totalMs << ","
      << m.totalMs * 1e6 / (double(r.size.width) * r.size.height) << "," << m.planBytes << "," << m.cszLevels;
    csvErrors(f, m.aoError);
    csvErrors(f, m.obscuranceError);
    f << "\n";
  }
}

void writeJson(const std::string& path, const std::vector<Row>& rows, const std::string& machine,
               const std::vector<std::pair<std::string, std::string>>& notes) {
  std::ofstream f(path);
  f << "{\n  \"machine\": " << json(machine) << ",\n  \"notes\": {\n";
  for (std::size_t i = 0; i < notes.size(); ++i)
    f << "    " << json(notes[i].first) << ": " << json(notes[i].second) << (i + 1 < notes.size() ? "," : "") << "\n";
  f << "  },\n  \"rows\": [\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    f << "    {\"section\": " << json(r.section) << ", \"scene\": " << json(r.scene) << ", \"backend\": "
      << json(r.backend) << ", \"preset\": " << json(r.preset) << ", \"variant\": " << json(r.variant)
      << ", \"inputs\": " << json(r.inputs) << ", \"shader_variant\": " << json(r.m.shaderVariant)
      << ", \"width\": " << r.size.width << ", \"height\": " << r.size.height
      << ", \"radius_m\": " << r.settings.radius << ", \"samples\": " << r.settings.samples
      << ", \"use_z_hierarchy\": " << (r.settings.use_z_hierarchy ? "true" : "false")
      << ", \"blur_radius\": " << r.settings.blur_radius << ", \"timing_method\": " << json(toString(r.m.method))
      << ", \"runs\": " << r.m.runs << ", \"total_ms\": " << r.m.totalMs << ", \"pass_ms\": {";
    for (std::size_t k = 0; k < r.m.passes.size(); ++k)
      f << (k ? ", " : "") << json(r.m.passes[k].pass) << ": " << r.m.passes[k].milliseconds;
    f << "}";
    jsonErrors(f, "error_vs_ao", r.m.aoError);
    jsonErrors(f, "error_vs_obscurance", r.m.obscuranceError);
    f << "}" << (i + 1 < rows.size() ? "," : "") << "\n";
  }
  f << "  ]\n}\n";
}

std::vector<std::string> writeCharts(const std::string& dir, const std::vector<Row>& rows,
                                     const std::string& mainScene, const std::string& radiusBackend) {
  Chart pareto{"Error vs time per preset (" + mainScene + ")", "total time, ms", "RMSE (raw)", true, false, {}};
  Chart radius{"ao_sample time vs radius (" + mainScene + ", " + radiusBackend + ")", "radius, m",
               "ao_sample time, ms", false, false, {}};
  Chart resolution{"Time vs resolution (" + mainScene + ", medium)", "pixels", "total time, ms", true, false, {}};
  std::map<std::string, Series> paretoSeries, resolutionSeries;
  std::vector<std::string> radiusOrder;  // curves in the order the section ran them
  std::map<std::string, Series> radiusSeries;
  auto point = [](Series& s, const std::string& label, double x, double y) {
    s.label = label;
    s.x.push_back(x);
    s.y.push_back(y);
  };
  for (const auto& r : rows) {
    if (r.section == "presets" && r.scene == mainScene) {
      if (r.m.aoError) {
        auto& s = paretoSeries[r.backend + " vs AO"];
        point(s, r.backend + " vs near-field AO", r.m.totalMs, r.m.aoError->raw.rmse);
        s.pointLabels.push_back(r.preset);
      }
      if (r.m.obscuranceError) {
        auto& s = paretoSeries[r.backend + " vs obscurance"];
        point(s, r.backend + " vs obscurance", r.m.totalMs, r.m.obscuranceError->raw.rmse);
        s.pointLabels.push_back(r.preset);
      }
    } else if (r.section == "radius") {
      if (!radiusSeries.count(r.variant)) radiusOrder.push_back(r.variant);
      point(radiusSeries[r.variant], r.variant, r.settings.radius, passMs(r.m, "ao_sample"));
    } else if (r.section == "resolution") {
      point(resolutionSeries[r.backend], r.backend, double(r.size.width) * r.size.height, r.m.totalMs);
    }
  }
  for (auto& [k, s] : paretoSeries) pareto.series.push_back(s);
  for (const auto& k : radiusOrder) radius.series.push_back(radiusSeries[k]);
  for (auto& [k, s] : resolutionSeries) resolution.series.push_back(s);
  std::vector<std::string> written;
  for (const auto& [name, chart] : {std::pair{"pareto.svg", &pareto}, std::pair{"radius.svg", &radius},
                                    std::pair{"resolution.svg", &resolution}}) {
    if (chart->series.empty()) continue;  // its section did not run
    std::ofstream(dir + "/" + name) << renderSvg(*chart);
    written.push_back(name);
  }
  return written;
}

}  // namespace sao::bench
