// The per_tap section's minimal baselines on OpenGL (per_tap_shaders.h): a headless context of
// their own (not the gl backend's, which the section runs in between), the effect's csz chain and
// normals uploaded once, each rung compiled per sample count and timed as the gl backend times a
// pass on llvmpipe: glFinish, steady clock, draw or dispatch, glFinish.
#pragma once
#include <memory>
#include <vector>


#include "per_tap_shaders.h"
#include "sao/constants.h"
#include "sao/image.h"
#include "sao/plan.h"
#include "sao/status.h"

namespace sao::gl {
class HeadlessContext;
}

namespace sao::bench {

class PerTapLadder {
 public:
  // `csz`: the effect's csz levels (level 0 first, r32f, the input extent with the guard band);
  // `normals`: 4-channel camera-space normals of the same extent; `viewport`: the AO size.
  static Status create(const std::vector<FloatImage>& csz, const FloatImage& normals, Extent viewport,
                       std::unique_ptr<PerTapLadder>& out);
  ~PerTapLadder();
  PerTapLadder(const PerTapLadder&) = delete;
  PerTapLadder& operator=(const PerTapLadder&) = delete;

  // One warm-up and `runs` timed runs of `step` with `block`'s values (samples, spiral_turns,
  // radius, ...), milliseconds per run: `clockMs` by a steady clock between two glFinish, `gpuMs` by
  // a GL_TIME_ELAPSED query as the effect's passes are timed (empty when a result is below 100 ns:
  // the query does not see the work, as llvmpipe's around compute). The last run's output is read
  // back into `ao`. Fails on a compile or link error and on any GL error the debug context reported.
  Status measure(const LadderStep& step, const ParamBlock& block, int runs, std::vector<double>& clockMs,
                 std::vector<double>& gpuMs, FloatImage& ao);

  std::string description() const;  // the context: platform, GL version, renderer

 private:
  PerTapLadder() = default;
  Status checkErrors(const char* what);

  std::unique_ptr<gl::HeadlessContext> context_;
  Extent viewport_;
  std::uint32_t cszLevels_ = 1;
  // GL names: csz level 0, the whole chain, normals, the r16f output, its framebuffer, an empty VAO.
  std::uint32_t z0_ = 0, zMips_ = 0, normals_ = 0, output_ = 0, fbo_ = 0, vao_ = 0;
};

}  // namespace sao::bench
