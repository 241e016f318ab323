#include "visibility_converged.h"

namespace sao::bench {

Settings convergedVisibilitySettings(const Settings& candidate) {
  Settings s = candidate;
  s.estimator = 1;
  // samples and slices stay the candidate's: the estimator's value moves with the taps on a slice
  // side (its joins bridge what the taps skip), a difference of definition that rmse vs (a)
  // measures; the frames average what one frame lacks, more slice directions.
  s.use_z_hierarchy = false;
  s.resolution_divisor = 1;
  s.blur_radius = 0;
  s.temporal = false;
  return s;
}

Status convergedVisibility(samples::BackendRunner& backend, const Settings& candidate, const Camera& camera,
                           const samples::RunInputs& inputs, std::uint32_t frames, FloatImage& out) {
  if (frames == 0) return Status::error(StatusCode::InvalidInput, "converged visibility: 0 frames");
  const Settings s = convergedVisibilitySettings(candidate);
  std::vector<double> sum;
  for (std::uint32_t f = 0; f < frames; ++f) {
    samples::RunInputs in = inputs;
    in.frameIndex = f;
    samples::RunOutputs run;
    if (Status st = backend.run(s, camera, in, false, false, run); !st) return st;
    if (f == 0) {
      out = run.ao;
      sum.assign(run.ao.data.size(), 0.0);
    }
    if (run.ao.data.size() != sum.size())
      return Status::error(StatusCode::DriverError, "converged visibility: frames of different sizes");
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += run.ao.data[i];
  }
  for (std::size_t i = 0; i < sum.size(); ++i) out.data[i] = float(sum[i] / double(frames));
  return Status::success();
}

}  // namespace sao::bench
