// ao_sample's exact texel reads on one scene, replayed through traffic models (traffic_model.h):
// csz level 0 from the CPU reference (float, as the GPU computes it), the z MIP chain by Table 1,
// and the taps of effect/cpu/tap_trace.h for any settings and variant (and, with thickness_model 1,
// the width passes' reads, effect/cpu/width_trace.h).
#pragma once
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sao/camera.h"
#include "sao/image.h"
#include "sao/settings.h"
#include "sao/status.h"
#include "traffic_model.h"

namespace sao::bench {

// What a curve reads: z through the hierarchy or level 0 only, supplied normals (rgba16f) or
// rebuilt ones, and the bytes of a z texel (4: r32f; 16: AlchemyAO's float4 positions).
struct TrafficVariant {
  std::string label;
  bool zHierarchy = true;
  bool normalsSupplied = false;
  std::uint32_t zTexelBytes = 4;
};

struct ReplayResult {
  std::vector<Traffic> traffic;       // one per machine: every pass replayed
  std::vector<Traffic> widthTraffic;  // the part of it the width passes read (thickness_model 1; else 0)
  std::uint64_t pixels = 0;      // AO pixels sampled: ao_raw's extent (the viewport at resolution_divisor 1)
  int maxMip = 0;                // the run's max_mip (0 without the hierarchy)
};

class TrafficScene {
 public:
  // Runs the CPU reference (float, medium preset) on the depth to get csz level 0; builds the chain.
  static Status create(const DepthImage& depth, const Camera& camera, std::unique_ptr<TrafficScene>& out);
  ~TrafficScene();

  // Every work group of ao_sample for `settings` (use_z_hierarchy taken from the variant), in
  // dispatch order, through one model per machine (machines valid); with thickness_model 1 the
  // width and width_resolve passes before it (effect/cpu/width_trace.h), through the same caches.
  Status replay(const Settings& settings, const TrafficVariant& variant, std::span<const Machine> machines,
                ReplayResult& out) const;

 private:
  struct Impl;
  explicit TrafficScene(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace sao::bench
