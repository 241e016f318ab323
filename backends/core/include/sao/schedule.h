// The schedule: the plan as a flat list of dispatches, each with its work-group counts, every
// binding resolved to (image, MIP levels, read or write) and the hazards that must be resolved
// before it runs. OpenGL, Vulkan and the CPU reference only translate it (docs/adding-a-pass.md):
// none of them decides sizes, bindings or barriers on its own.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "sao/plan.h"

namespace sao {

// One binding of one dispatch. Reads are sampled (texelFetch at explicit levels), writes are
// storage-image stores of one level, or, for a levels=A..B pass, an array of B - A + 1 storage
// images: slot j is level baseLevel + j while j < levelCount, and the last level after that (a
// valid image the shader never stores to: the chain ends there, max_mip).
struct ScheduledBinding {
  std::uint32_t binding = 0;    // Vulkan set-0 binding (GL binds the variant's BindingInfo::glUnit)
  gen::ResourceId resource{};   // the image that serves it, aliases resolved
  bool write = false;
  std::uint32_t baseLevel = 0;  // first level the binding sees
  std::uint32_t levelCount = 1; // levels it sees; a read of a whole MIP chain sees them all
  bool wholeChain = false;      // a read of every level of a multi-level image (a MIP-sampled view)
  // A read of a history (history=true): the copy the previous frame wrote (sao/temporal.h,
  // imageCopy); its write is this frame's copy.
  bool previousFrame = false;

  // The level array element `slot` of a levels= write holds (slot 0 for any other binding).
  std::uint32_t slotLevel(std::uint32_t slot) const { return baseLevel + std::min(slot, levelCount - 1); }
};

// What must happen between an earlier access to (resource, levels) and a later one.
enum class HazardKind : std::uint8_t {
  ReadAfterWrite,   // a storage write, then a sampled read: the write must be visible to fetches
  WriteAfterRead,   // a sampled read, then a storage write: the write waits for the read
  WriteAfterWrite,  // a storage write, then another: ordered, the second lands last
  CallerWrote,      // frame entry: the caller may have written an input the frame reads
  CallerReads,      // frame exit: the caller reads the output next, in any way
};

struct Hazard {
  gen::ResourceId resource{};
  std::uint32_t baseLevel = 0;
  std::uint32_t levelCount = 1;
  HazardKind kind{};
  bool previousFrame = false;  // a history's previous-frame copy (frame entry: written by the frame before)
};

struct ScheduledDispatch {
  std::uint32_t passIndex = 0;  // into Plan::passes
  gen::PassId pass{};
  const gen::PassVariantInfo* variant = nullptr;
  std::uint32_t level = 0;      // the first level a levels= pass writes; else 0
  std::uint32_t groupsX = 1, groupsY = 1;
  std::uint32_t firstBinding = 0, bindingCount = 0;  // into Schedule::bindings
  std::uint32_t firstHazard = 0, hazardCount = 0;    // into Schedule::hazards, resolved before it runs
};

struct Schedule {
  std::vector<ScheduledDispatch> dispatches;
  std::vector<ScheduledBinding> bindings;
  std::vector<Hazard> hazards;
  // Frame entry: inputs the caller may have written (CallerWrote), every image the frame
  // writes, against the previous frame's reads and writes (WriteAfterRead / WriteAfterWrite), and
  // a history's previous-frame copy, which the frame before wrote (ReadAfterWrite, previousFrame).
  std::uint32_t firstEntryHazard = 0, entryHazardCount = 0;
  // Frame exit: the output, read by the caller (CallerReads).
  std::uint32_t firstExitHazard = 0, exitHazardCount = 0;

  std::span<const ScheduledBinding> bindingsOf(const ScheduledDispatch& d) const {
    return {bindings.data() + d.firstBinding, d.bindingCount};
  }
  std::span<const Hazard> hazardsBefore(const ScheduledDispatch& d) const {
    return {hazards.data() + d.firstHazard, d.hazardCount};
  }
  std::span<const Hazard> entryHazards() const { return {hazards.data() + firstEntryHazard, entryHazardCount}; }
  std::span<const Hazard> exitHazards() const { return {hazards.data() + firstExitHazard, exitHazardCount}; }
  std::string describe() const;  // one line per dispatch, for logs and tests
};

// The schedule of a plan: the step right after plan(), which every backend takes. Deterministic.
Schedule makeSchedule(const Plan& plan);

// ---- what a backend checks and keeps across frames

// An input or output image as the caller supplies it this frame.
struct SuppliedImage {
  bool supplied = false;
  Extent extent;  // the whole level 0 the caller supplies
  // Inputs: Inputs::region, the texel of the supplied image that holds the region's first texel
  // (the guard band's corner); the region, plan.inputExtent texels from here, must lie inside
  // `extent`. Unset: `extent` must be plan.inputExtent.
  std::optional<Offset> region{};
};
using SuppliedImages = std::array<SuppliedImage, gen::kResources.size()>;

// The caller's images against the plan: every input a dispatch reads is supplied, large enough to
// hold the input extent at its offset (no 32-bit wrap-around), and no other input is; a supplied
// output has the AO extent, and one is supplied exactly when `outputSupplied` says the plan
// expects it. InvalidInput naming the image (for a region: its offset, the extent and the image's
// size); `who` prefixes the message ("sao::gl", "sao::vk"). Allocates only to build an error.
Status checkSupplied(const Plan& plan, const SuppliedImages& images, bool outputExpected, const char* who);

// Whether an owned image keeps its allocation from `before` to `after` (same format, extent, levels).
bool sameImage(const PlannedImage& before, const PlannedImage& after);
bool sameImages(const Plan& before, const Plan& after);

}  // namespace sao
