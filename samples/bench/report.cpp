#include "report.h"

#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "sao/samples/shortest_float.h"
#include "svg_plot.h"

namespace sao::bench {
namespace {

using Json = nlohmann::ordered_json;  // keys in the order written

// A CSV field: quoted (with doubled quotes) only when it holds a comma or a quote.
std::string csv(const std::string& s) {
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string o = "\"";
  for (char c : s) o += c == '"' ? std::string("\"\"") : std::string(1, c);
  return o + "\"";
}

const char* kErrorColumns[] = {"rmse_raw", "bias_raw", "ssim_raw", "over_0_1_raw", "fitted_scale",
                               "rmse_fitted", "bias_fitted", "ssim_fitted", "over_0_1_fitted",
                               "flip_raw",  "flip_fitted"};

// A metric as CSV text: "n/a" where it is NaN (samples/metrics.h).
std::string csvMetric(double v) {
  if (!samples::isDefined(v)) return "n/a";
  std::ostringstream s;
  s << v;
  return s.str();
}

void csvErrors(std::ofstream& f, const std::optional<samples::ReferenceComparison>& e) {
  if (!e) {
    for (std::size_t i = 0; i < std::size(kErrorColumns); ++i) f << ",";
    return;
  }
  const auto m = csvMetric;
  f << "," << m(e->raw.rmse) << "," << m(e->raw.meanBias) << "," << m(e->raw.ssim) << "," << m(e->raw.fractionOver01)
    << "," << m(e->fittedIntensity) << "," << m(e->fitted.rmse) << "," << m(e->fitted.meanBias) << ","
    << m(e->fitted.ssim) << "," << m(e->fitted.fractionOver01) << "," << m(e->raw.flip) << "," << m(e->fitted.flip);
}

// (c)'s structure columns, then the model error and the map.
void csvConverged(std::ofstream& f, const Row& r) {
  const auto& st = r.m.convergedStructure;
  if (st)
    f << "," << csvMetric(st->blotchRmse) << "," << csvMetric(st->highFrequencyRmse) << ","
      << csvMetric(st->silhouetteRmse);
  else
    f << ",,,";
  auto optional = [](double v) { return samples::isDefined(v) ? csvMetric(v) : std::string(); };
  f << "," << optional(r.modelRmseVsAo) << "," << optional(r.modelRmseVsObscurance) << "," << csv(r.errorMap);
}

// One reference's error columns; NaN (undefined) serialises as null.
Json jsonErrors(const samples::ReferenceComparison& e) {
  return Json{{"pixels", e.raw.pixels},          {"rmse_raw", e.raw.rmse},
              {"bias_raw", e.raw.meanBias},       {"ssim_raw", e.raw.ssim},
              {"over_0_1_raw", e.raw.fractionOver01}, {"fitted_scale", e.fittedIntensity},
              {"rmse_fitted", e.fitted.rmse},     {"bias_fitted", e.fitted.meanBias},
              {"ssim_fitted", e.fitted.ssim},     {"over_0_1_fitted", e.fitted.fractionOver01},
              {"flip_raw", e.raw.flip},           {"flip_fitted", e.fitted.flip}};
}

}  // namespace

double passMs(const Measurement& m, std::string_view name) {
  for (const auto& p : m.passes)
    if (p.pass == name) return p.milliseconds;
  return 0;
}

void writeCsv(const std::string& path, const std::vector<Row>& rows) {
  std::ofstream f(path);
  f << "section,scene,backend,preset,variant,inputs,shader_variant,width,height,radius_m,samples,use_z_hierarchy,"
       "blur_radius,runs,timing_method,";
  // One column per pass the effect declares, in its order ("<pass>_ms"; 0 where the row's plan has
  // no such pass), so that the columns follow the annotated source.
  for (const gen::PassInfo& pass : gen::passes()) f << pass.name << "_ms,";
  f << "total_ms,ns_per_pixel,plan_bytes,csz_levels";
  for (const char* prefix : {"ao_", "obscurance_", "converged_", "screen_"})
    for (const char* c : kErrorColumns) f << "," << prefix << c;
  f << ",converged_blotch_rmse,converged_highfreq_rmse,converged_silhouette_rmse,model_rmse_vs_ao,"
       "model_rmse_vs_obscurance,error_map,resolution_divisor,started_unix_s,ended_unix_s,screen_model_rmse_vs_ao,model_rmse_converged_vs_screen\n";
  for (const auto& r : rows) {
    const auto& m = r.m;
    f << csv(r.section) << "," << csv(r.scene) << "," << csv(r.backend) << "," << csv(r.preset) << ","
      << csv(r.variant) << "," << csv(r.inputs) << "," << csv(m.shaderVariant) << "," << r.size.width << ","
      << r.size.height << "," << r.settings.radius << "," << r.settings.samples << "," << r.settings.use_z_hierarchy
      << "," << r.settings.blur_radius << "," << m.runs << "," << csv(toString(m.method)) << ",";
    for (const gen::PassInfo& pass : gen::passes()) f << passMs(m, pass.name) << ",";
    f << m.totalMs << ","
      << m.totalMs * 1e6 / (double(r.size.width) * r.size.height) << "," << m.planBytes << "," << m.cszLevels;
    csvErrors(f, m.aoError);
    csvErrors(f, m.obscuranceError);
    csvErrors(f, m.convergedError);
    csvErrors(f, m.screenError);
    csvConverged(f, r);
    f << "," << r.settings.resolution_divisor << "," << std::fixed << std::setprecision(3)
      << m.startedUnixSeconds << "," << m.endedUnixSeconds << std::defaultfloat << std::setprecision(6);
    auto optional = [](double v) { return samples::isDefined(v) ? csvMetric(v) : std::string(); };
    f << "," << optional(r.screenRmseVsAo) << "," << optional(r.convergedRmseVsScreen) << "\n";
  }
}

void writeJson(const std::string& path, const std::vector<Row>& rows, const std::string& machine,
               const std::vector<std::pair<std::string, std::string>>& notes) {
  Json j;
  j["machine"] = machine;
  Json& notesJson = j["notes"] = Json::object();
  for (const auto& [key, text] : notes) notesJson[key] = text;
  Json& rowsJson = j["rows"] = Json::array();
  for (const auto& r : rows) {
    Json row{{"section", r.section},
             {"scene", r.scene},
             {"backend", r.backend},
             {"preset", r.preset},
             {"variant", r.variant},
             {"inputs", r.inputs},
             {"shader_variant", r.m.shaderVariant},
             {"width", r.size.width},
             {"height", r.size.height},
             {"radius_m", samples::shortestDecimal(r.settings.radius)},
             {"samples", r.settings.samples},
             {"use_z_hierarchy", r.settings.use_z_hierarchy},
             {"blur_radius", r.settings.blur_radius},
             {"timing_method", toString(r.m.method)},
             {"runs", r.m.runs},
             {"total_ms", r.m.totalMs}};
    Json& passMs = row["pass_ms"] = Json::object();
    for (const auto& p : r.m.passes) passMs[p.pass] = p.milliseconds;
    if (r.m.aoError) row["error_vs_ao"] = jsonErrors(*r.m.aoError);
    if (r.m.obscuranceError) row["error_vs_obscurance"] = jsonErrors(*r.m.obscuranceError);
    if (r.m.convergedError) {
      Json& c = row["error_vs_converged"] = jsonErrors(*r.m.convergedError);
      if (const auto& st = r.m.convergedStructure) {
        c["blotch_rmse"] = st->blotchRmse;
        c["highfreq_rmse"] = st->highFrequencyRmse;
        c["silhouette_pixels"] = st->silhouettePixels;
        c["silhouette_rmse"] = st->silhouetteRmse;
      }
      row["model_error"] = Json{{"rmse_converged_vs_ao", r.modelRmseVsAo},
                                {"rmse_converged_vs_obscurance", r.modelRmseVsObscurance}};
    }
    if (r.m.screenError) {
      row["error_vs_screen"] = jsonErrors(*r.m.screenError);
      row["screen_model_error"] = Json{{"rmse_screen_vs_ao", r.screenRmseVsAo},
                                       {"rmse_converged_vs_screen", r.convergedRmseVsScreen}};
    }
    if (!r.errorMap.empty()) row["error_map"] = r.errorMap;
    rowsJson.push_back(std::move(row));
  }
  // Invalid UTF-8 (a machine name, a scene path) is replaced, not thrown.
  std::ofstream(path) << j.dump(2, ' ', false, Json::error_handler_t::replace) << "\n";
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
