// plan(): only the passes, variants, MIP levels and images a configuration needs. Backends
// allocate from it and dispatch from its schedule (sao/schedule.h); it is cheap and deterministic,
// so tests assert it.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sao/camera.h"
#include "sao/constants.h"
#include "sao/output.h"
#include "sao/settings.h"

namespace sao {

struct Extent {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  bool operator==(const Extent&) const = default;
};

// A texel position: where a region starts inside a larger image (x counts texels along a row, y
// rows in storage order, so (0, 0) is the image's first texel in memory).
struct Offset {
  std::uint32_t x = 0;
  std::uint32_t y = 0;
  bool operator==(const Offset&) const = default;
};

// Whether an input image of `have` serves an effect that needs `needed` texels: exactly that size
// without a region (so that a depth buffer with an undeclared guard band, or the wrong one, is
// refused rather than read from its corner), or the region from `region` on lying inside it
// (compared in 64 bits: an offset near 2^32 does not wrap around into the image).
bool holdsInput(Extent have, const std::optional<Offset>& region, Extent needed);

// The largest image side the plan accepts (backends also check their device's own limit).
inline constexpr std::uint32_t kMaxImageSide = 16384;

struct PlanInputs {
  DepthEncoding depthEncoding = DepthEncoding::Hardware;
  // Which inputs the user supplies (a select=input: variant reads it); the required ones (no
  // when=, the depth) count as supplied whatever this says.
  gen::InputSet<bool> supplied;
  bool userOutput = false;   // the user supplies the output image (not counted in bytes)
  // The output image's format (sao/output.h: one of outputFormats()); it selects the final pass's
  // variant, and an effect-owned output is allocated in it.
  gen::Format outputFormat = gen::Format::R16F;
  // Samples per texel of the depth input: more than 1 selects the multisampled read (DEPTH_MULTISAMPLE).
  std::uint32_t depthSamples = 1;
  // (The output's channel mask and blend are per frame, not part of the plan: sao/frame.h.)
  bool operator==(const PlanInputs&) const = default;
};

struct PlannedImage {
  gen::ResourceId resource;
  gen::Format format;
  Extent extent;              // level 0
  std::uint32_t mipLevels = 1;
  // 2 for a history (history=true: this frame's image and the previous frame's, which trade places
  // every frame, sao/temporal.h); 1 otherwise. `bytes` counts every copy.
  std::uint32_t copies = 1;
  std::uint64_t bytes = 0;
};

struct PlannedPass {
  gen::PassId pass;
  const gen::PassVariantInfo* variant = nullptr;  // bindings and blobs
  // Bindings whose declared resource is served by another image (a dropped pass's output).
  std::vector<std::pair<gen::ResourceId, gen::ResourceId>> aliases;
};

struct Plan {
  gen::VariantValues variants{};
  Extent inputExtent;  // depth, normals, csz: viewport + 2 * guard band
  Extent aoExtent;     // the output: the viewport
  // Per resource: the value of its divide_by= setting (resolution_divisor for ao_raw, ao_low and
  // history), which divides its extent rounded up; 0 or 1: not divided.
  std::array<std::uint32_t, gen::kResources.size()> extentDivisor{};
  std::uint32_t cszLevels = 1;
  std::vector<PlannedPass> passes;
  std::vector<PlannedImage> images;  // effect-owned images only (and the output unless userOutput)
  std::uint64_t totalBytes = 0;

  const PlannedImage* image(gen::ResourceId id) const;
  // The image that serves `declared` in `pass` (itself unless aliased).
  gen::ResourceId resolve(const PlannedPass& pass, gen::ResourceId declared) const;
  std::string describe() const;  // a few lines for logs and the CLI summary
};

Status plan(const Settings& settings, const Camera& camera, const PlanInputs& inputs, Plan& out);

// Bytes an implementation without a plan would allocate up front: every image the effect declares
// (the second layer's chain and the blur intermediate included, whatever the inputs and settings),
// each csz chain down to 1x1; only a user-supplied output is not counted. For comparison in reports.
std::uint64_t fullAllocationBytes(const Camera& camera, const PlanInputs& inputs);

std::uint32_t bytesPerTexel(gen::Format format);

// Level `level` of an image whose level 0 is `e`: each side halved per level, at least 1.
Extent levelExtent(Extent e, std::uint32_t level);

// Level-0 extent of the image that serves `id` in `plan`: a planned image's own, else what the
// resource declares (the input or AO extent over its scale, then over its divisor rounded up:
// ceil(641 / 2) = 321, so reduced pixel p covers viewport pixels [2p, 2p + 2)), e.g. for a
// caller's output.
Extent resourceExtent(const Plan& plan, gen::ResourceId id);

}  // namespace sao
