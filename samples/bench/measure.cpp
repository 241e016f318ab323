#include "measure.h"

#include <algorithm>
#include <map>

namespace sao::bench {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

Status measure(samples::BackendRunner& backend, const Settings& settings, const Camera& camera,
               const DepthImage& depth, int runs, const FloatImage* reference,
               const std::vector<unsigned char>* mask, Measurement& out) {
  out = Measurement{};
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> perPass;
  std::vector<double> totals;
  // One warm-up run (pipelines, allocations), then the measured ones.
  for (int r = -1; r < runs; ++r) {
    samples::RunOutputs o;
    if (Status s = backend.run(settings, camera, {&depth, nullptr, nullptr}, true, false, o); !s) return s;
    if (r < 0) continue;
    for (const auto& p : o.timings.passes) {
      if (!perPass.count(p.pass)) order.push_back(p.pass);
      perPass[p.pass].push_back(p.milliseconds);
    }
    totals.push_back(o.timings.totalMilliseconds());
    out.method = o.timings.method;
    out.planBytes = o.plan.totalBytes;
    out.cszLevels = o.plan.cszLevels;
    if (r == runs - 1) out.ao = std::move(o.ao);
  }
  for (const auto& name : order) out.passes.push_back({name, median(perPass[name])});
  out.totalMs = median(totals);
  out.runs = runs;
  if (reference && mask) out.error = samples::compareToReference(out.ao, *reference, *mask);
  return Status::success();
}

}  // namespace sao::bench
