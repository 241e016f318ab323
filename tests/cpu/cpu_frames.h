// The CPU reference's frames of one camera path, run in order with the temporal history carried
// from run to run (cpu::Inputs::history / previousCamera), as a GPU effect keeps it: the oracle of
// the temporal tests on every backend.
#pragma once
#include <gtest/gtest.h>

#include "sao/cpu/reference.h"

namespace sao::test {

class CpuFrames {
 public:
  explicit CpuFrames(const Settings& settings) : settings_(settings) {}
  // One frame: `in` as the caller fills it (depth, motion, frame index, ...); the history and the
  // previous camera are added after the first frame. Fails the running test on an error.
  cpu::Result run(const Camera& camera, cpu::Inputs in) {
    if (hasHistory_) {
      in.history = &history_;
      in.previousCamera = &previous_;
    }
    cpu::Result r;
    const Status st = cpu::run(settings_, camera, in, cpu::Options{cpu::Precision::Float, 2}, r);
    EXPECT_TRUE(st.ok()) << st.message;
    if (st.ok()) {
      history_ = r.images[std::size_t(gen::ResourceId::history)].at(0);
      previous_ = camera;
      hasHistory_ = true;
    }
    return r;
  }
  // The history the last frame wrote (4 channels: sum, key z, frames, 0).
  const FloatImage& history() const { return history_; }

 private:
  Settings settings_;
  FloatImage history_;
  Camera previous_;
  bool hasHistory_ = false;
};

}  // namespace sao::test
