// A test that runs GL and Vulkan side by side (GL = Vulkan comparisons): both executors made,
// every GL debug error and Vulkan validation message fails it; skipped, saying why, in a program
// built with one API.
#pragma once
#include <algorithm>
#include <memory>
#include <vector>

#include "harness.h"

namespace sao::exectest {

template <typename Base = ::testing::Test>
class BothApis : public Base {
 protected:
  // Both library APIs built (a program may run the engine-side example too: it is not compared here).
  static bool both() {
    const std::vector<Api> a = apis();
    return std::count(a.begin(), a.end(), Api::Gl) && std::count(a.begin(), a.end(), Api::Vulkan);
  }
  void SetUp() override {
    if (!both()) GTEST_SKIP() << "GL = Vulkan needs both APIs; this program has only " << toString(apis().at(0));
    for (Api a : {Api::Gl, Api::Vulkan}) checkMessagesBefore(a);
    gl = makeExecutor(Api::Gl);
    vk = makeExecutor(Api::Vulkan);
  }
  void TearDown() override {
    gl.reset();
    vk.reset();
    if (both())
      for (Api a : {Api::Gl, Api::Vulkan}) checkMessagesAfter(a);
  }
  std::unique_ptr<Executor> gl, vk;
};

}  // namespace sao::exectest
