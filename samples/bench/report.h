// The bench's outputs: one row per measurement, written as results.csv and results.json, and the
// SVG charts (pareto, radius, resolution).
#pragma once
#include <cmath>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "measure.h"

namespace sao::bench {

struct Row {
  std::string section, scene, backend, preset, variant;
  std::string inputs;  // what the effect was given: "depth", "depth+normals" or "depth+depth2"
  Extent size;
  Settings settings;
  Measurement m;
  // Model error, the same for every row of a scene, settings and inputs: RMSE of (c) against (a)
  // and (b) over the mask; NaN where (c) or that reference was not computed.
  double modelRmseVsAo = NAN, modelRmseVsObscurance = NAN;
  std::string errorMap;  // the error-vs-(c) PNG, relative to the output folder; empty: none
  // The same per scene, radius and inputs for reference (d): RMSE of (d) against (a) (what screen
  // space cannot see) and of (c) against (d) (the estimator's definition); NaN where not computed.
  double screenRmseVsAo = NAN, convergedRmseVsScreen = NAN;
};

// Median time of one pass, 0 when the pass did not run.
double passMs(const Measurement& m, std::string_view pass);

// Error columns come in four groups, named by their reference: ao_* against (a) the near-field AO,
// obscurance_* against (b) the AlchemyAO obscurance, converged_* against (c) the converged
// estimator, screen_* against (d) converged screen-space visibility; then (c)'s blotch,
// high-frequency and silhouette figures, the model error (model_rmse_vs_ao,
// model_rmse_vs_obscurance) and error_map; (d)'s model errors (screen_model_rmse_vs_ao,
// model_rmse_converged_vs_screen) last. Empty where not computed.
void writeCsv(const std::string& path, const std::vector<Row>& rows);

// `notes`: (key, text) pairs written as the "notes" object: what the references, the radius-sweep
// baseline and the second layer are.
void writeJson(const std::string& path, const std::vector<Row>& rows, const std::string& machine,
               const std::vector<std::pair<std::string, std::string>>& notes);

// pareto.svg (error against both references vs time, presets on `mainScene`), radius.svg (ao_sample
// time vs radius, one curve per radius-section variant) and resolution.svg, in `dir`; a chart whose
// section did not run is not written. Returns the names of the files written.
std::vector<std::string> writeCharts(const std::string& dir, const std::vector<Row>& rows,
                                     const std::string& mainScene, const std::string& radiusBackend);

}  // namespace sao::bench
