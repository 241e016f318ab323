// sao-bench --tune's record, tune.csv: one row per evaluated candidate, appended and flushed as
// it finishes, so that a rerun skips what is there. A row is keyed by everything its figures
// depend on: the candidate (kind, name, inputs, tuned settings), backend, depth source, size and
// the taps of reference (c); the scene set is in the header (per-scene columns), and a file with
// another header is refused rather than mixed. The last column, session, numbers the invocations
// that appended rows (1, 2, ...): times are only comparable within one (tune_time.h), so each
// session keeps its own rows of the time anchors (their key includes it). A file written before
// that column is read as session 1 throughout and gains the column at the first append.
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
  std::uint32_t session = 0;  // the invocation that measured it (column session)

  std::string columns() const;  // the candidate's columns as written: all but runs, the figures and session
  // What a rerun looks a row up by: columns(), and for a time anchor (isTimeAnchor) its session, so
  // that a session's anchors never replace an earlier session's.
  std::string key() const;
  double totalMs() const;
  double meanRmse() const;
  double meanBlotch() const;  // the blotch RMSE (error_structure.h), mean over the scenes
};

class TuneCsv {
 public:
  // Reads `path` if it exists (its header must be the one for `scenes` and the objective: an
  // a_rays column and <scene>_rmse_vs_a columns when objectiveRays > 0), then keeps it open for
  // appending; creates it with the header otherwise. A header without the session column (a file
  // written before it) is accepted: its rows are session 1.
  Status open(const std::string& path, const std::vector<std::string>& scenes, std::uint32_t objectiveRays = 0);
  ~TuneCsv();
  const std::vector<TuneRow>& rows() const { return rows_; }
  // This invocation's session: 1 + the largest in the file (1 for a new or empty file).
  std::uint32_t session() const { return session_; }
  const TuneRow* find(const std::string& key) const;
  // Written and flushed at once, with session(). The first append to a file without the session
  // column first rewrites it with the column (its rows session 1): a file is never of two formats.
  Status append(const TuneRow& row);

 private:
  std::string path_;
  std::vector<std::string> scenes_;
  std::uint32_t objectiveRays_ = 0;
  std::uint32_t session_ = 1;
  std::string header_;
  // The data lines of a file read without the session column, kept verbatim for its rewrite.
  bool withoutSession_ = false;
  std::vector<std::string> linesWithoutSession_;
  std::vector<TuneRow> rows_;
  std::map<std::string, std::size_t> index_;  // key -> rows_
  std::FILE* file_ = nullptr;
  Status addSessionColumn();  // the rewrite before the first append to a file without the column
};

}  // namespace sao::bench
