#include "tune_time.h"

#include <algorithm>
#include <iterator>
#include <map>

namespace sao::bench {
namespace {

using SessionAnchors = std::map<std::size_t, const TimedRow*>;  // candidate index -> anchor

double total(const TimedRow& r) {
  double t = 0;
  for (double v : r.ms) t += v;
  return t;
}

Status refuse(const std::string& message) { return Status::error(StatusCode::InvalidInput, message); }

}  // namespace

Status timeUnits(const std::vector<TimedRow>& rows, std::vector<std::vector<double>>& unitMs) {
  unitMs.clear();
  std::map<std::uint32_t, SessionAnchors> anchors;
  for (const TimedRow& r : rows) {
    if (!r.anchor) continue;
    const std::string session = std::to_string(r.session);
    if (r.ms.empty() || !std::all_of(r.ms.begin(), r.ms.end(), [](double v) { return v > 0; }))
      return refuse(r.label + " (a time anchor of session " + session + ") has no time on every scene");
    if (!anchors[r.session].emplace(r.candidate, &r).second)
      return refuse("two time anchors of session " + session + " at candidate " + std::to_string(r.candidate) + ": " +
                    r.label);
  }
  for (const TimedRow& r : rows) {
    const auto own = anchors.find(r.session);
    if (own == anchors.end())
      return refuse(r.label + ": its session " + std::to_string(r.session) +
                    " has no time anchor (a measurement of the untuned medium) to time it against; delete that "
                    "session's rows to measure them again");
    const SessionAnchors& a = own->second;
    // The anchors around the row: both, or the nearest where the session has them on one side only.
    auto after = a.lower_bound(r.candidate);
    auto before = after;
    if (after == a.end()) before = after = std::prev(a.end());
    else if (after->first != r.candidate && after != a.begin()) before = std::prev(after);
    const TimedRow& lo = *before->second;
    const TimedRow& hi = *after->second;
    if (lo.ms.size() != r.ms.size() || hi.ms.size() != r.ms.size())
      return refuse(r.label + " and the time anchors of its session " + std::to_string(r.session) +
                    " have different scene counts");
    const double w = before == after ? 0 : double(r.candidate - before->first) / double(after->first - before->first);
    std::vector<double> unit(r.ms.size());
    for (std::size_t s = 0; s < unit.size(); ++s) unit[s] = (1 - w) * lo.ms[s] + w * hi.ms[s];
    unitMs.push_back(std::move(unit));
  }
  return Status::success();
}

std::vector<SessionDrift> anchorDrift(const std::vector<TimedRow>& rows) {
  std::map<std::uint32_t, SessionAnchors> anchors;
  for (const TimedRow& r : rows)
    if (r.anchor && total(r) > 0) anchors[r.session].emplace(r.candidate, &r);
  std::vector<SessionDrift> out;
  for (const auto& [session, a] : anchors) {
    SessionDrift d{session, a.size(), 1, 1};
    const double first = total(*a.begin()->second);
    for (const auto& entry : a) {
      d.min = std::min(d.min, total(*entry.second) / first);
      d.max = std::max(d.max, total(*entry.second) / first);
    }
    out.push_back(d);
  }
  return out;
}

}  // namespace sao::bench
