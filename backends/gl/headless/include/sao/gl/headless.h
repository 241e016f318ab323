// A headless OpenGL context for tests and tools: EGL on Mesa's surfaceless platform (llvmpipe
// without a GPU), falling back to EGL_EXT_platform_device (e.g. NVIDIA without a display). The
// context is a core 4.3+ debug context (or, with HeadlessOptions::es, an ES 3.1+ one); a KHR_debug callback collects every message so that a
// test can fail on GL_DEBUG_TYPE_ERROR.
#pragma once
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "sao/gl/effect.h"
#include "sao/status.h"

namespace sao::gl {

struct DebugMessage {
  std::uint32_t source = 0, type = 0, id = 0, severity = 0;  // GL_DEBUG_SOURCE_*, GL_DEBUG_TYPE_*, ...
  std::string text;
};

enum class EglPlatform {
  Auto,         // surfaceless when the client supports it, otherwise devices
  Surfaceless,  // EGL_MESA_platform_surfaceless
  Device,       // EGL_EXT_platform_device (+ EGL_EXT_device_enumeration)
};

struct HeadlessOptions {
  int major = 4, minor = 3;  // the least version accepted (core profile; with es, the ES version)
  bool es = false;           // an OpenGL ES context (EGL_OPENGL_ES_API) instead: for sao::gles, major.minor >= 3.1
  bool debug = true;         // debug context + KHR_debug callback
  // Auto can be overridden with the environment variable SAO_EGL_PLATFORM=surfaceless|device.
  EglPlatform platform = EglPlatform::Auto;
};

class HeadlessContext {
 public:
  // Creates the context and makes it current on the calling thread.
  static Status create(std::unique_ptr<HeadlessContext>& out, const HeadlessOptions& options = {});
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  Status makeCurrent();
  // glFinish on this context (made current first): every command issued so far has completed.
  Status finish();
  // Leaves no context current on the calling thread (to test callers without one).
  Status releaseCurrent();
  // eglGetProcAddress, for sao::gl::Effect::create.
  static GetProcAddressFn getProcAddress();

  EglPlatform platform() const { return platform_; }
  const std::string& description() const { return description_; }  // platform, GL version, renderer

  std::vector<DebugMessage> messages() const;  // every message since the last clear
  std::vector<DebugMessage> errors() const;    // those of type GL_DEBUG_TYPE_ERROR
  void clearMessages();
  static std::string format(const DebugMessage& m);
  // Adds a message (what the debug callback does; errors are also printed to stderr).
  void record(DebugMessage message);

 private:
  HeadlessContext() = default;
  struct Egl;
  std::unique_ptr<Egl> egl_;
  EglPlatform platform_ = EglPlatform::Auto;
  std::string description_;
  mutable std::mutex mutex_;
  std::vector<DebugMessage> messages_;
};

const char* toString(EglPlatform platform);

}  // namespace sao::gl
