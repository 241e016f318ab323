// One interface over the three backends for the samples: run the effect on a depth image that
// lives on the CPU, get the AO and the intermediates back.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "sao/camera.h"
#include "sao/image.h"
#include "sao/plan.h"
#include "sao/settings.h"
#include "sao/timing.h"

namespace sao::samples {

struct RunInputs {
  const DepthImage* depth = nullptr;
  const FloatImage* normals = nullptr;  // optional, 4 channels, camera space
  const DepthImage* depth2 = nullptr;   // optional second layer
  std::uint32_t frameIndex = 0;         // the backend's Inputs::frameIndex (sao::frameSpiral)
  // With the temporal setting: start the history again from this run (the backend's
  // Inputs::resetHistory); otherwise a runner keeps the history of its previous run, as an effect does.
  bool resetHistory = false;
};

struct RunOutputs {
  Plan plan;
  FloatImage ao;      // 1 channel: A
  // With settings.bent_normals: the bent normal (3 channels, camera space, unit length; 0 for sky),
  // from an RGBA16F output the runner chooses then (an r16f output cannot hold it: plan() refuses
  // it); empty otherwise.
  FloatImage bentNormals;
  FloatImage aoRaw;   // 2 channels (A, key z), when the backend can read it back
  Timings timings;
  std::vector<std::pair<std::string, FloatImage>> intermediates;  // with dumpPasses
};

class BackendRunner {
 public:
  virtual ~BackendRunner() = default;
  virtual std::string_view name() const = 0;
  virtual std::string description() const = 0;  // device / driver in words
  virtual Status run(const Settings& settings, const Camera& camera, const RunInputs& inputs, bool measureTime,
                     bool dumpPasses, RunOutputs& out) = 0;
  // Renders the inputs back to back, reading nothing back, for about `milliseconds` of wall time
  // (at least once): a GPU lowers its clocks under the light, bursty load of single runs and their
  // read-backs, and raises them under sustained work, so timed runs after this see the clocks a
  // frame loop gets. With the temporal setting each render is a frame of the history. The CPU
  // backends have no clocks to raise: the default does nothing.
  virtual Status keepBusy(const Settings& settings, const Camera& camera, const RunInputs& inputs, double milliseconds) {
    (void)settings, (void)camera, (void)inputs, (void)milliseconds;
    return Status::success();
  }
};

// The output format a runner asks of its backend: RGBA16F with settings.bent_normals (the bent
// normal in R, G, B and A in A), else the effect's own output format (R16F).
gen::Format runnerOutputFormat(const Settings& settings);
// Splits a runner's read-back output into RunOutputs::ao (A) and, for a 4-channel output,
// RunOutputs::bentNormals (R, G, B); a 1-channel output is moved into ao as it is.
void splitOutput(FloatImage output, RunOutputs& out);

// "cpu" (float, as a GPU computes), "cpu-double", "gl", "vulkan" or "auto" (the first of gl, vulkan, cpu that starts). Backends not built
// into this program give a clear error.
Status createBackend(std::string_view name, std::unique_ptr<BackendRunner>& out);

// InvalidInput for a name createBackend does not know (the message lists the ones it does), so a
// typo in a list of backends is refused with the options, not skipped at run time.
Status checkBackendName(std::string_view name);

// Whether `name` is compiled into this program ("cpu" and "cpu-double" always are; "gl" and
// "vulkan" only when their backend was built). Lets a caller tell "not built" from "failed to
// start", which createBackend reports alike (DriverError).
bool isBackendBuiltIn(std::string_view name);

}  // namespace sao::samples
