// The CPU passes of effect/sao.glsl, as the CPU reference finds them: effect/CMakeLists.txt names
// this file in sao_generate_effect(... CPU_PASSES), which makes it SAO_CPU_PASSES_HEADER, and
// backends/cpu/src/reference.cpp includes that and calls runEffectPass for every dispatch. An
// extended effect gives its own header with the same function (tests/walkthrough/cpu_passes.h).
#pragma once
#include <span>

#include "sao_passes.h"

namespace sao::cpu {

template <typename T>
Status runEffectPass(PassContext<T>& ctx, const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
  return runSaoPass(ctx, d, bindings);
}

}  // namespace sao::cpu
