#include "sao/gl/headless.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

namespace sao::gl {

const char* toString(EglPlatform platform) {
  switch (platform) {
    case EglPlatform::Auto: return "auto";
    case EglPlatform::Surfaceless: return "EGL surfaceless (EGL_MESA_platform_surfaceless)";
    case EglPlatform::Device: return "EGL device (EGL_EXT_platform_device)";
  }
  return "?";
}

struct HeadlessContext::Egl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EGLSurface surface = EGL_NO_SURFACE;  // a 1x1 pbuffer only without EGL_KHR_surfaceless_context
};

namespace {

bool hasExtension(const char* list, std::string_view name) {
  if (!list) return false;
  std::string_view s(list);
  for (std::size_t pos = 0; pos < s.size();) {
    std::size_t end = s.find(' ', pos);
    if (end == std::string_view::npos) end = s.size();
    if (s.substr(pos, end - pos) == name) return true;
    pos = end + 1;
  }
  return false;
}

std::string eglError(const char* what) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s failed (EGL error 0x%04X)", what, unsigned(eglGetError()));
  return buf;
}

ProcAddress loadProc(const char* name) { return reinterpret_cast<ProcAddress>(eglGetProcAddress(name)); }

void GLAPIENTRY debugCallback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                              const GLchar* message, const void* user) {
  std::string text = length >= 0 ? std::string(message, std::size_t(length)) : std::string(message);
  auto* self = static_cast<HeadlessContext*>(const_cast<void*>(user));
  self->record(DebugMessage{source, type, id, severity, std::move(text)});
}

// Tries to create a core `major.minor`+ debug context on an initialised display.
Status makeContext(EGLDisplay display, const HeadlessOptions& o, EGLContext& ctx, EGLSurface& surface) {
  if (!eglBindAPI(o.es ? EGL_OPENGL_ES_API : EGL_OPENGL_API))
    return Status::error(StatusCode::DriverError, eglError(o.es ? "eglBindAPI(EGL_OPENGL_ES_API)" : "eglBindAPI(EGL_OPENGL_API)"));
  const char* ext = eglQueryString(display, EGL_EXTENSIONS);
  const bool surfaceless = hasExtension(ext, "EGL_KHR_surfaceless_context");
  const EGLint renderable = o.es ? EGL_OPENGL_ES3_BIT : EGL_OPENGL_BIT;
  const EGLint withPbuffer[] = {EGL_RENDERABLE_TYPE, renderable, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
  const EGLint anySurface[] = {EGL_RENDERABLE_TYPE, renderable, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (!eglChooseConfig(display, withPbuffer, &config, 1, &count) || count == 0) {
    count = 0;
    if (!surfaceless || !eglChooseConfig(display, anySurface, &config, 1, &count)) count = 0;
  }
  if (count == 0) {
    if (!(surfaceless && hasExtension(ext, "EGL_KHR_no_config_context")))
      return Status::error(StatusCode::DriverError, o.es ? "no EGL config with EGL_OPENGL_ES3_BIT" : "no EGL config with EGL_OPENGL_BIT");
    config = nullptr;  // EGL_NO_CONFIG_KHR
  }
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION_KHR,
                            o.major,
                            EGL_CONTEXT_MINOR_VERSION_KHR,
                            o.minor,
                            EGL_CONTEXT_FLAGS_KHR,
                            o.debug ? EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR : 0,
                            o.es ? EGL_NONE : EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR,  // ES has no profiles
                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT_KHR,
                            EGL_NONE};
  ctx = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs);
  if (ctx == EGL_NO_CONTEXT)
    return Status::error(StatusCode::DriverError, eglError((std::string(o.es ? "eglCreateContext(ES " : "eglCreateContext(core ") +
                                                            std::to_string(o.major) + "." + std::to_string(o.minor) + ", debug)")
                                                               .c_str()));
  surface = EGL_NO_SURFACE;
  if (!surfaceless) {
    const EGLint pb[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    surface = config ? eglCreatePbufferSurface(display, config, pb) : EGL_NO_SURFACE;
    if (surface == EGL_NO_SURFACE) {
      eglDestroyContext(display, ctx);
      ctx = EGL_NO_CONTEXT;
      return Status::error(StatusCode::DriverError, "no EGL_KHR_surfaceless_context and no pbuffer surface");
    }
  }
  if (!eglMakeCurrent(display, surface, surface, ctx)) {
    const std::string e = eglError("eglMakeCurrent");
    if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
    eglDestroyContext(display, ctx);
    ctx = EGL_NO_CONTEXT;
    surface = EGL_NO_SURFACE;
    return Status::error(StatusCode::DriverError, e);
  }
  return Status::success();
}

}  // namespace

void HeadlessContext::record(DebugMessage m) {
  if (m.type == GL_DEBUG_TYPE_ERROR) std::fprintf(stderr, "GL debug: %s\n", format(m).c_str());
  std::lock_guard<std::mutex> lock(mutex_);
  messages_.push_back(std::move(m));
}

Status HeadlessContext::create(std::unique_ptr<HeadlessContext>& out, const HeadlessOptions& options) {
  out.reset();
  std::unique_ptr<HeadlessContext> c(new HeadlessContext());
  c->egl_ = std::make_unique<Egl>();
  EglPlatform want = options.platform;
  if (want == EglPlatform::Auto) {
    if (const char* env = std::getenv("SAO_EGL_PLATFORM")) {
      if (std::strcmp(env, "surfaceless") == 0) want = EglPlatform::Surfaceless;
      else if (std::strcmp(env, "device") == 0) want = EglPlatform::Device;
    }
  }
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  const bool haveSurfaceless = hasExtension(client, "EGL_MESA_platform_surfaceless");
  const bool haveDevice = hasExtension(client, "EGL_EXT_platform_device") &&
                          (hasExtension(client, "EGL_EXT_device_enumeration") ||
                           hasExtension(client, "EGL_EXT_device_base"));
  std::string tried;
  auto attempt = [&](EGLDisplay display, EglPlatform platform, const std::string& what) -> bool {
    if (display == EGL_NO_DISPLAY) {
      tried += "; " + what + ": " + eglError("eglGetPlatformDisplayEXT");
      return false;
    }
    EGLint maj = 0, min = 0;
    if (!eglInitialize(display, &maj, &min)) {
      tried += "; " + what + ": " + eglError("eglInitialize");
      return false;
    }
    Status st = makeContext(display, options, c->egl_->context, c->egl_->surface);
    if (!st) {
      tried += "; " + what + ": " + st.message;
      return false;
    }
    c->egl_->display = display;
    c->platform_ = platform;
    c->description_ = what;
    return true;
  };

  bool ok = false;
  if ((want == EglPlatform::Auto || want == EglPlatform::Surfaceless) && haveSurfaceless)
    ok = attempt(eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                 EglPlatform::Surfaceless, toString(EglPlatform::Surfaceless));
  if (!ok && (want == EglPlatform::Auto || want == EglPlatform::Device) && haveDevice) {
    EGLDeviceEXT devices[16];
    EGLint n = 0;
    if (!eglQueryDevicesEXT(16, devices, &n)) n = 0;
    for (EGLint i = 0; i < n && !ok; ++i) {
      const char* devExt = eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
      std::string what = std::string(toString(EglPlatform::Device)) + " #" + std::to_string(i);
      if (devExt && *devExt) what += " [" + std::string(devExt) + "]";
      ok = attempt(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), EglPlatform::Device, what);
    }
    if (n == 0) tried += "; no EGL devices";
  }
  if (!ok) {
    std::string why = "could not create a headless OpenGL " + std::to_string(options.major) + "." +
                      std::to_string(options.minor) + " core context";
    if (!haveSurfaceless && !haveDevice)
      why += ": EGL has neither EGL_MESA_platform_surfaceless nor EGL_EXT_platform_device";
    return Status::error(StatusCode::DriverError, why + tried);
  }

  GLint maj = 0, min = 0, flags = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &maj);
  glGetIntegerv(GL_MINOR_VERSION, &min);
  if (maj < options.major || (maj == options.major && min < options.minor))
    return Status::error(StatusCode::DriverError, "the EGL context is OpenGL " + std::to_string(maj) + "." +
                                                      std::to_string(min) + ", below the requested " +
                                                      std::to_string(options.major) + "." +
                                                      std::to_string(options.minor));
  c->description_ += std::string(" | ") + reinterpret_cast<const char*>(glGetString(GL_VERSION)) + " | " +
                     reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (options.debug) {
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    if (!(flags & GL_CONTEXT_FLAG_DEBUG_BIT))
      return Status::error(StatusCode::DriverError, "the EGL context is not a debug context");
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debugCallback, c.get());
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
  }
  out = std::move(c);
  return Status::success();
}

HeadlessContext::~HeadlessContext() {
  if (!egl_ || egl_->display == EGL_NO_DISPLAY) return;
  if (eglGetCurrentContext() == egl_->context) {
    glDebugMessageCallback(nullptr, nullptr);
    eglMakeCurrent(egl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  if (egl_->surface != EGL_NO_SURFACE) eglDestroySurface(egl_->display, egl_->surface);
  if (egl_->context != EGL_NO_CONTEXT) eglDestroyContext(egl_->display, egl_->context);
}

Status HeadlessContext::makeCurrent() {
  if (!eglMakeCurrent(egl_->display, egl_->surface, egl_->surface, egl_->context))
    return Status::error(StatusCode::DriverError, eglError("eglMakeCurrent"));
  return Status::success();
}

Status HeadlessContext::finish() {
  if (Status s = makeCurrent(); !s) return s;
  glFinish();
  return Status::success();
}

Status HeadlessContext::releaseCurrent() {
  if (!eglMakeCurrent(egl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT))
    return Status::error(StatusCode::DriverError, eglError("eglMakeCurrent(EGL_NO_CONTEXT)"));
  return Status::success();
}

GetProcAddressFn HeadlessContext::getProcAddress() { return &loadProc; }

std::vector<DebugMessage> HeadlessContext::messages() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return messages_;
}

std::vector<DebugMessage> HeadlessContext::errors() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<DebugMessage> out;
  for (const auto& m : messages_)
    if (m.type == GL_DEBUG_TYPE_ERROR) out.push_back(m);
  return out;
}

void HeadlessContext::clearMessages() {
  std::lock_guard<std::mutex> lock(mutex_);
  messages_.clear();
}

std::string HeadlessContext::format(const DebugMessage& m) {
  auto type = [](std::uint32_t t) -> const char* {
    switch (t) {
      case GL_DEBUG_TYPE_ERROR: return "ERROR";
      case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated";
      case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined behaviour";
      case GL_DEBUG_TYPE_PORTABILITY: return "portability";
      case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
      case GL_DEBUG_TYPE_MARKER: return "marker";
      case GL_DEBUG_TYPE_PUSH_GROUP: return "push group";
      case GL_DEBUG_TYPE_POP_GROUP: return "pop group";
      default: return "other";
    }
  };
  auto severity = [](std::uint32_t s) -> const char* {
    switch (s) {
      case GL_DEBUG_SEVERITY_HIGH: return "high";
      case GL_DEBUG_SEVERITY_MEDIUM: return "medium";
      case GL_DEBUG_SEVERITY_LOW: return "low";
      default: return "notification";
    }
  };
  return std::string(type(m.type)) + " (" + severity(m.severity) + ", id " + std::to_string(m.id) + "): " + m.text;
}

}  // namespace sao::gl
