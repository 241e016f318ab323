// A test that runs GL and Vulkan side by side (GL = Vulkan comparisons): both executors made,
// every GL debug error and Vulkan validation message fails it; skipped, saying why, in a program
// built with one API.
#pragma once
#include <memory>

#include "harness.h"

namespace sao::exectest {

template <typename Base = ::testing::Test>
class BothApis : public Base {
 protected:
  void SetUp() override {
    if (apis().size() < 2) GTEST_SKIP() << "GL = Vulkan needs both APIs; this program has only " << toString(apis().at(0));
    for (Api a : apis()) checkMessagesBefore(a);
    gl = makeExecutor(Api::Gl);
    vk = makeExecutor(Api::Vulkan);
  }
  void TearDown() override {
    gl.reset();
    vk.reset();
    if (apis().size() == 2)
      for (Api a : apis()) checkMessagesAfter(a);
  }
  std::unique_ptr<Executor> gl, vk;
};

}  // namespace sao::exectest
