// The walkthrough effect's CPU passes (docs/adding-a-pass.md, section 3): sao.glsl's, plus the
// oracle of ao_halve. CMakeLists.txt names this file in sao_generate_effect(... CPU_PASSES), so the
// CPU reference compiled unchanged against the extended effect runs the new pass too.
#pragma once
#include <span>
#include <type_traits>

#include "../../effect/cpu/sao_passes.h"

namespace sao::cpu {

namespace walkthrough {

// Pass ao_halve: the A of the dispatch's read image (ao_low, or ao_raw through the alias), rounded
// like sao_round_to_half in Float precision, times 0.5 (times the ao_scale input where given),
// into ao_half.
template <typename T>
Status aoHalvePass(PassContext<T>& ctx, const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
  const ScheduledBinding* in = nthBinding(bindings, false, 0);
  const ScheduledBinding* out = nthBinding(bindings, true, 0);
  if (in == nullptr || out == nullptr) return detail::passError(d, "needs a read and a write binding");
  const detail::Image<T>& src = ctx.image(*in);
  detail::Image<T>& half = ctx.image(*out);
  if (src.w != half.w || src.h != half.h) return detail::passError(d, "needs images of one extent");
  // The new input (AO_SCALED): read where the shader's texelFetch reads, p + guard + input_offset.
  const FloatImage* scale = colourInput(ctx.in, gen::ResourceId::ao_scale);
  for (int y = 0; y < half.h; ++y)
    for (int x = 0; x < half.w; ++x) {
      T a = src.at(x, y, 0);
      if constexpr (std::is_same_v<T, float>) a = detail::roundToHalf(a);
      a *= T(0.5);
      if (scale != nullptr) {
        const std::size_t sx = std::size_t(x + ctx.P.guard.x + ctx.P.input_offset.x);
        const std::size_t sy = std::size_t(y + ctx.P.guard.y + ctx.P.input_offset.y);
        a *= T(scale->data[(sy * scale->extent.width + sx) * scale->channels]);
      }
      half.at(x, y, 0) = a;
    }
  return Status::success();
}

}  // namespace walkthrough

template <typename T>
Status runEffectPass(PassContext<T>& ctx, const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
  if (d.pass == gen::PassId::ao_halve) return walkthrough::aoHalvePass(ctx, d, bindings);
  return runSaoPass(ctx, d, bindings);
}

}  // namespace sao::cpu
