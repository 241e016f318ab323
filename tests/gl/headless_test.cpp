// The headless context helper: a core 4.3+ debug context whose KHR_debug callback collects
// messages, on the EGL surfaceless platform or, failing that, an EGL device.
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdlib>
#include <cstring>

#include "gl_support.h"

namespace sao::gltest {
namespace {

class Headless : public GlTest {};

TEST_F(Headless, IsACore43DebugContext) {
  gl::HeadlessContext& c = context();
  GLint major = 0, minor = 0, flags = 0, profile = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_TRUE(major > 4 || (major == 4 && minor >= 3)) << major << "." << minor;
  EXPECT_TRUE(flags & GL_CONTEXT_FLAG_DEBUG_BIT);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
  EXPECT_TRUE(glIsEnabled(GL_DEBUG_OUTPUT));
  EXPECT_NE(c.platform(), gl::EglPlatform::Auto);
  // SAO_EGL_PLATFORM forces the platform: nothing else may be tried.
  if (const char* env = std::getenv("SAO_EGL_PLATFORM")) {
    if (std::strcmp(env, "device") == 0) {
      EXPECT_EQ(c.platform(), gl::EglPlatform::Device) << c.description();
    }
    if (std::strcmp(env, "surfaceless") == 0) {
      EXPECT_EQ(c.platform(), gl::EglPlatform::Surfaceless) << c.description();
    }
  }
  std::printf("%s\n", c.description().c_str());
}

TEST_F(Headless, CollectsErrorMessages) {
  gl::HeadlessContext& c = context();
  ASSERT_TRUE(c.errors().empty());
  glBindTexture(GL_TEXTURE_2D, 0xBADu);  // core profile: a name never generated -> GL_INVALID_OPERATION
  const auto errors = c.errors();
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].type, std::uint32_t(GL_DEBUG_TYPE_ERROR));
  EXPECT_FALSE(errors[0].text.empty());
  EXPECT_EQ(glGetError(), GLenum(GL_INVALID_OPERATION));
  c.clearMessages();  // expected: do not fail this test in TearDown
  EXPECT_TRUE(c.errors().empty());
}

TEST_F(Headless, ApplicationMessagesAreNotErrors) {
  gl::HeadlessContext& c = context();
  glDebugMessageInsert(GL_DEBUG_SOURCE_APPLICATION, GL_DEBUG_TYPE_MARKER, 42, GL_DEBUG_SEVERITY_NOTIFICATION, -1,
                       "marker");
  const auto all = c.messages();
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(all.back().id, 42u);
  EXPECT_EQ(all.back().text, "marker");
  EXPECT_TRUE(c.errors().empty());
}

TEST_F(Headless, GetProcAddressLoadsTheEffect) {
  std::unique_ptr<gl::Effect> e = makeEffect();
  EXPECT_TRUE(e);
}

// The fallback path: an EGL device display (EGL_EXT_platform_device), as on an NVIDIA machine
// without a display. Mesa offers a software device too (EGL_MESA_device_software), so the same
// code is exercised here. SAO_REQUIRE_EGL_DEVICE=1 (the gl.egl_device.* ctests, where the
// device is known to work) turns a missing device into a failure instead of a skip.
TEST(HeadlessDevice, EglDevicePlatform) {
  const char* require = std::getenv("SAO_REQUIRE_EGL_DEVICE");
  const bool required = require && std::strcmp(require, "1") == 0;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!client || !std::strstr(client, "EGL_EXT_platform_device")) {
    if (required) FAIL() << "SAO_REQUIRE_EGL_DEVICE=1 but EGL has no EGL_EXT_platform_device";
    GTEST_SKIP() << "no EGL_EXT_platform_device";
  }
  gl::HeadlessContext& main = context();  // made current again at the end
  std::unique_ptr<gl::HeadlessContext> c;
  gl::HeadlessOptions o;
  o.platform = gl::EglPlatform::Device;
  const Status st = gl::HeadlessContext::create(c, o);
  if (!st) {
    ASSERT_TRUE(main.makeCurrent().ok());
    if (required) FAIL() << "SAO_REQUIRE_EGL_DEVICE=1 but no EGL device gives a GL 4.3 core context: " << st.message;
    GTEST_SKIP() << "EGL devices present but none gives a GL 4.3 core context: " << st.message;
  }
  EXPECT_EQ(c->platform(), gl::EglPlatform::Device);
  std::printf("%s\n", c->description().c_str());
  std::unique_ptr<gl::Effect> e;
  const Status est = gl::Effect::create(gl::HeadlessContext::getProcAddress(), e);
  EXPECT_TRUE(est.ok()) << est.message;
  e.reset();
  EXPECT_TRUE(c->errors().empty());
  c.reset();
  ASSERT_TRUE(main.makeCurrent().ok());
}

}  // namespace
}  // namespace sao::gltest
