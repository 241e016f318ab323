// sao-bench --tune's record, tune.csv: one row per evaluated candidate, appended and flushed as
// it finishes, so that a rerun skips what is there. A row is keyed by everything its figures
// depend on: the candidate (kind, name, inputs, tuned settings), backend, depth source, size and
// the taps of reference (c); the scene set is in the header (per-scene columns), and a file with
// another header is refused rather than mixed.
#pragma once
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "sao/plan.h"
#include "sao/settings.h"
#include "sao/status.h"

namespace sao::bench {

struct SceneFigures {
  double ms = 0;  // median total time of the runs
  double rmse = 0;  // vs the objective: (c), or (a) when the row's objectiveRays > 0
  // vs (c), or the visibility estimator's own converged value; silhouette NaN: no band
  double blotch = 0, highFrequency = 0, silhouette = 0;
};

struct TuneRow {
  std::string kind, name, backend, depth, inputs;
  Extent size{0, 0};
  std::uint32_t convergedTaps = 0;
  std::uint32_t objectiveRays = 0;  // 0: rmse is vs (c); else vs (a) with this many rays (column a_rays)
  // Estimator 1: the frames of its own converged value (visibility_converged.h, its samples and
  // slices since 2026-12-05's third tune; column own_converged_frames), the reference of its
  // blotch, high-frequency and silhouette figures and of its rmse vs (c); 0 for estimator 0.
  std::uint32_t ownConvergedFrames = 0;
  Settings settings;
  std::uint32_t runs = 0;
  std::vector<SceneFigures> scenes;  // in the header's scene order

  std::string key() const;  // every column but runs and the figures
  double totalMs() const;
  double meanRmse() const;
  double meanBlotch() const;  // the blotch RMSE (error_structure.h), mean over the scenes
};

class TuneCsv {
 public:
  // Reads `path` if it exists (its header must be the one for `scenes` and the objective: an
  // a_rays column and <scene>_rmse_vs_a columns when objectiveRays > 0), then keeps it open for
  // appending; creates it with the header otherwise.
  Status open(const std::string& path, const std::vector<std::string>& scenes, std::uint32_t objectiveRays = 0);
  ~TuneCsv();
  const std::vector<TuneRow>& rows() const { return rows_; }
  const TuneRow* find(const std::string& key) const;
  Status append(const TuneRow& row);  // written and flushed at once

 private:
  std::string path_;
  std::vector<std::string> scenes_;
  std::uint32_t objectiveRays_ = 0;
  std::vector<TuneRow> rows_;
  std::map<std::string, std::size_t> index_;  // key -> rows_
  std::FILE* file_ = nullptr;
};

}  // namespace sao::bench
