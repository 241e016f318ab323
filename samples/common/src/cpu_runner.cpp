// The CPU reference as a sample backend (float mode: what a GPU computes).
#include "runners.h"
#include "sao/cpu/parallel.h"
#include "sao/cpu/reference.h"

namespace sao::samples {
namespace {

class CpuRunner final : public BackendRunner {
 public:
  explicit CpuRunner(cpu::Precision precision) : precision_(precision) {}
  std::string_view name() const override { return precision_ == cpu::Precision::Float ? "cpu" : "cpu-double"; }
  std::string description() const override {
    return std::string("CPU reference (") + cpu::toString(precision_) + ", " +
           std::to_string(cpu::threadCount(0)) + " threads)";  // Options::threads = 0
  }
  Status run(const Settings& settings, const Camera& camera, const RunInputs& in, bool measureTime, bool dumpPasses,
             RunOutputs& out) override {
    cpu::Inputs inputs;
    inputs.depth = in.depth;
    inputs.depth2 = in.depth2;
    inputs.normals = in.normals;
    inputs.frameIndex = in.frameIndex;
    inputs.outputFormat = runnerOutputFormat(settings);
    // Temporal accumulation: the previous run's history, as a GPU effect keeps it (same settings,
    // a camera of the same size; sao/temporal.h).
    const bool reuse = settings.temporal && !in.resetHistory && haveHistory_ && settings == historySettings_ &&
                       previous_.width == camera.width && previous_.height == camera.height &&
                       previous_.guardBand == camera.guardBand && previous_.kind == camera.kind;
    if (reuse) {
      inputs.history = &history_;
      inputs.previousCamera = &previous_;
    }
    cpu::Options options;
    options.precision = precision_;
    options.measureTime = measureTime;
    cpu::Result r;
    if (Status s = cpu::run(settings, camera, inputs, options, r); !s) return s;
    haveHistory_ = settings.temporal;
    if (settings.temporal) {
      history_ = r.images[std::size_t(gen::ResourceId::history)].at(0);
      previous_ = camera;
      historySettings_ = settings;
    }
    out.plan = r.plan;
    splitOutput(std::move(r.ao), out);
    out.timings = r.timings;
    if (dumpPasses) {
      for (std::size_t m = 0; m < r.csz.size(); ++m) out.intermediates.push_back({"csz_level" + std::to_string(m), r.csz[m]});
      for (std::size_t m = 0; m < r.csz2.size(); ++m)
        out.intermediates.push_back({"csz2_level" + std::to_string(m), r.csz2[m]});
      if (!r.aoRaw.data.empty()) out.intermediates.push_back({"ao_raw", r.aoRaw});
      for (std::size_t id = 0; id < r.images.size(); ++id)  // the rest the plan allocates (ao_low)
        for (std::size_t m = 0; m < r.images[id].size(); ++m)
          out.intermediates.push_back({std::string(gen::kResources[id].name) +
                                           (r.images[id].size() > 1 ? "_level" + std::to_string(m) : ""),
                                       r.images[id][m]});
    }
    out.aoRaw = std::move(r.aoRaw);
    return Status::success();
  }

 private:
  cpu::Precision precision_;
  bool haveHistory_ = false;
  FloatImage history_;
  Camera previous_;
  Settings historySettings_;
};

}  // namespace

std::unique_ptr<BackendRunner> makeCpuRunner(bool doublePrecision) {
  return std::make_unique<CpuRunner>(doublePrecision ? cpu::Precision::Double : cpu::Precision::Float);
}

}  // namespace sao::samples
