// A Vulkan test that also drives OpenGL in the same process (the GL = Vulkan comparisons): the
// headless GL context made current before each test, and any GL debug message fails the test, as
// VkTest fails on a validation message. Header only; the target links gl_test_support.
#pragma once
#include "gl_support.h"
#include "sao/gl/headless.h"
#include "vk_support.h"

namespace sao::vktest {

class VkWithGl : public VkTest {
 protected:
  void SetUp() override {
    VkTest::SetUp();
    ASSERT_TRUE(gltest::context().makeCurrent().ok());
    gltest::context().clearMessages();
  }
  void TearDown() override {
    for (const auto& m : gltest::context().errors()) ADD_FAILURE() << "GL debug message: " << gl::HeadlessContext::format(m);
    VkTest::TearDown();
  }
};

}  // namespace sao::vktest
