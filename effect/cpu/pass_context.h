// What the CPU reference's executor (backends/cpu/src/reference.cpp) hands an effect's C++ pass:
// the inputs, the plan, the parameter block as T, the thread count, the variant values and one
// image per planned effect image and level (the output included). A pass finds its images through
// the dispatch's resolved bindings (binding(), image()), the way a shader finds them through its
// units, so the executor names no pass and no image. It lives beside the passes, not in
// backends/cpu/include: it holds Image<T> of sao_math.h, and the kernels stay out of public headers.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "sao/cpu/reference.h"
#include "sao/plan.h"
#include "sao/schedule.h"
#include "sao_math.h"

namespace sao::cpu {

template <typename T>
class PassContext {
 public:
  using Image = detail::Image<T>;
  using Levels = std::vector<Image>;  // one image per MIP level, level 0 first

  PassContext(const Inputs& inputs, const Plan& planned, const gen::SaoParams& params, unsigned threadCount)
      : in(inputs), plan(planned), P(params), threads(threadCount) {}

  const Inputs& in;
  const Plan& plan;
  const detail::Block<T> P;
  const unsigned threads;

  bool variant(gen::VariantId id) const { return plan.variants[static_cast<std::size_t>(id)] != 0; }

  // The levels of an image; empty when the plan has no such image (or it is an input).
  Levels& levels(gen::ResourceId id) { return images_[static_cast<std::size_t>(id)]; }
  const Levels& levels(gen::ResourceId id) const { return images_[static_cast<std::size_t>(id)]; }

  // Whether (id, levels [base, base + count)) is held; the executor checks every binding with it
  // before a dispatch runs, so image() below never indexes past the store.
  bool holds(gen::ResourceId id, std::uint32_t base, std::uint32_t count) const {
    return std::size_t(base) + count <= levels(id).size() && count > 0;
  }

  Image& image(gen::ResourceId id, std::uint32_t level) { return levels(id)[level]; }
  const Image& image(gen::ResourceId id, std::uint32_t level) const { return levels(id)[level]; }
  // The level a binding sees first: the one a write stores to, level A - 1 of a levels=A..B read; for a
  // history's read (previousFrame), the previous frame's image.
  Image& image(const ScheduledBinding& b) {
    return b.previousFrame ? previousFrame(b.resource) : image(b.resource, b.baseLevel);
  }
  // The previous frame's image of a history (history=true): Inputs::history, or all zeros.
  Image& previousFrame(gen::ResourceId id) { return previous_[static_cast<std::size_t>(id)]; }

 private:
  std::array<Levels, gen::kResources.size()> images_;
  std::array<Image, gen::kResources.size()> previous_;
};

// The binding through which dispatch `d` reads (write = false) or writes `declared`, the resource
// as the pass declares it, resolved to the image that serves it (an alias, a level); nullptr when
// the dispatch's variant does not bind it. Schedule bindings follow the variant's list one to one.
inline const ScheduledBinding* binding(const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings,
                                       gen::ResourceId declared, bool write) {
  if (d.variant == nullptr || d.variant->bindings.size() != bindings.size()) return nullptr;
  for (std::size_t i = 0; i < bindings.size(); ++i)
    if (d.variant->bindings[i].resource == declared && d.variant->bindings[i].write == write) return &bindings[i];
  return nullptr;
}

// The n-th read (write = false) or write binding of a dispatch, in declaration order; nullptr past
// the last. For passes whose one read may be served by different images (an aliased blur input).
inline const ScheduledBinding* nthBinding(std::span<const ScheduledBinding> bindings, bool write, std::size_t n) {
  for (const ScheduledBinding& b : bindings)
    if (b.write == write && n-- == 0) return &b;
  return nullptr;
}

}  // namespace sao::cpu
