// The walkthrough effect's CPU passes (docs/adding-a-pass.md, section 3): sao.glsl's, plus the
// oracle of ao_halve. CMakeLists.txt names this file in sao_generate_effect(... CPU_PASSES), so the
// CPU reference compiled unchanged against the extended effect runs the new pass too.
#pragma once
#include <span>

#include "../../effect/cpu/sao_passes.h"

namespace sao::cpu {

namespace walkthrough {

// Pass ao_halve: blur_v's A again from the dispatch's read image (ao_blur_h, or ao_raw through the
// alias), rounded like sao_round_to_half in Float precision, times 0.5, into ao_half.
template <typename T>
Status aoHalvePass(PassContext<T>& ctx, const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
  if (Status st = detail::blurPass(ctx, d, bindings, 0, 1, true); !st) return st;
  detail::Image<T>& half = ctx.image(*nthBinding(bindings, true, 0));  // blurPass found it
  for (T& a : half.v) a = a * T(0.5);
  return Status::success();
}

}  // namespace walkthrough

template <typename T>
Status runEffectPass(PassContext<T>& ctx, const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
  if (d.pass == gen::PassId::ao_halve) return walkthrough::aoHalvePass(ctx, d, bindings);
  return runSaoPass(ctx, d, bindings);
}

}  // namespace sao::cpu
