#include "measure.h"

#include <algorithm>
#include <chrono>
#include <map>

namespace sao::bench {
namespace {

double unixSeconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

Status measure(samples::BackendRunner& backend, const Settings& settings, const Camera& camera,
               const samples::RunInputs& inputs, int runs, const References& references, Measurement& out,
               double warmupMs, std::uint32_t averagedFrames) {
  out = Measurement{};
  if (!inputs.depth) return Status::error(StatusCode::InvalidInput, "bench::measure needs a depth image");
  if (averagedFrames == 0 || (averagedFrames > 1 && settings.temporal))
    return Status::error(StatusCode::InvalidInput,
                         "bench::measure averages 1 or more independent frames, not frames of the temporal setting");
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> perPass;
  std::vector<double> totals;
  // One warm-up run (pipelines, allocations), then the measured ones.
  for (int r = -1; r < runs; ++r) {
    if (r == 0) {
      if (warmupMs > 0 && !settings.temporal)
        if (Status s = backend.keepBusy(settings, camera, inputs, warmupMs); !s) return s;
      out.startedUnixSeconds = unixSeconds();
    }
    samples::RunOutputs o;
    if (Status s = backend.run(settings, camera, inputs, true, false, o); !s) return s;
    if (r < 0) continue;
    for (const auto& p : o.timings.passes) {
      if (!perPass.count(p.pass)) order.push_back(p.pass);
      perPass[p.pass].push_back(p.milliseconds);
    }
    totals.push_back(o.timings.totalMilliseconds());
    out.method = o.timings.method;
    out.planBytes = o.plan.totalBytes;
    out.cszLevels = o.plan.cszLevels;
    out.shaderVariant.clear();
    for (std::size_t v = 0; v < gen::kVariantCount; ++v) {
      if (v) out.shaderVariant += ' ';
      out.shaderVariant.append(gen::kVariants[v].name).append("=").append(std::to_string(o.plan.variants[v]));
    }
    if (r == runs - 1) out.ao = std::move(o.ao);
  }
  out.endedUnixSeconds = unixSeconds();
  if (averagedFrames > 1) {  // frame 0 is the last timed run's (same inputs): the others added to it
    samples::RunInputs frame = inputs;
    for (std::uint32_t f = 1; f < averagedFrames; ++f) {
      frame.frameIndex = inputs.frameIndex + f;
      samples::RunOutputs o;
      if (Status s = backend.run(settings, camera, frame, false, false, o); !s) return s;
      for (std::size_t i = 0; i < out.ao.data.size(); ++i) out.ao.data[i] += o.ao.data[i];
    }
    for (float& v : out.ao.data) v /= float(averagedFrames);
  }
  for (const auto& name : order) out.passes.push_back({name, median(perPass[name])});
  out.totalMs = median(totals);
  out.runs = runs;
  if (references.screen && references.screenMask)
    out.screenError = samples::compareToReference(out.ao, *references.screen, *references.screenMask);
  if (const auto* mask = references.mask) {
    if (references.nearFieldAo) out.aoError = samples::compareToReference(out.ao, *references.nearFieldAo, *mask);
    if (references.obscurance) out.obscuranceError = samples::compareToReference(out.ao, *references.obscurance, *mask);
    if (const FloatImage* c = references.converged) {
      out.convergedError = samples::compareToReference(out.ao, *c, *mask);
      if (references.silhouette) out.convergedStructure = samples::errorStructure(out.ao, *c, *mask, *references.silhouette);
    }
  }
  return Status::success();
}

}  // namespace sao::bench
