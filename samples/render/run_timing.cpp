#include "run_timing.h"

#include <algorithm>
#include <map>

namespace sao::render {
namespace {

Spread spreadOf(std::vector<double> v) {
  Spread s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  s.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  s.min = v.front();
  s.max = v.back();
  return s;
}

}  // namespace

RunTiming summarizeRuns(const std::vector<Timings>& runs) {
  RunTiming out;
  out.runs = std::uint32_t(runs.size());
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> perPass;
  std::vector<double> totals;
  for (const Timings& t : runs) {
    out.method = t.method;
    for (const auto& p : t.passes) {
      if (!perPass.count(p.pass)) order.push_back(p.pass);
      perPass[p.pass].push_back(p.milliseconds);
    }
    totals.push_back(t.totalMilliseconds());
  }
  for (const auto& name : order) out.passes.push_back({name, spreadOf(perPass[name])});
  out.total = spreadOf(totals);
  return out;
}

}  // namespace sao::render
