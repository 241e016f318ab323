// sao-bench --tune's time unit. Every candidate's time is divided by the untuned medium's
// (tune_grid.h), measured again as time anchors between the candidates because the machine's clock
// drifts within a run (0.60x to 1.26x of the first anchor in one run) and more between runs. So a
// row is divided only by anchors of its own session (the invocation that measured it: tune.csv's
// session column), interpolated by candidate index.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sao/status.h"

namespace sao::bench {

// One row of tune.csv as the time unit sees it.
struct TimedRow {
  std::string label;          // names the row in errors
  std::size_t candidate = 0;  // its place in candidate order (the order rows are evaluated in)
  std::uint32_t session = 0;
  bool anchor = false;        // a measurement of the untuned medium (the time unit itself)
  std::vector<double> ms;     // per scene
};

// unitMs[r][s]: the untuned medium's time on scene s for rows[r], from anchors of rows[r]'s session
// only: linear in the candidate index between the two around it, the nearest one where they lie on
// one side only (an anchor is its own unit). InvalidInput naming the row when its session has no
// anchor; naming the anchor when one has no positive time on every scene, another scene count, or
// shares its session and candidate index with another.
Status timeUnits(const std::vector<TimedRow>& rows, std::vector<std::vector<double>>& unitMs);

// A session's anchors: their totals over the session's first anchor's (in candidate order), the
// machine's drift over that run.
struct SessionDrift {
  std::uint32_t session = 0;
  std::size_t anchors = 0;
  double min = 1, max = 1;
};
// One per session that has anchors, by session; anchors without a positive total are left out
// (timeUnits refuses them).
std::vector<SessionDrift> anchorDrift(const std::vector<TimedRow>& rows);

}  // namespace sao::bench
