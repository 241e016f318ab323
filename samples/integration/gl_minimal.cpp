// The smallest OpenGL integration: SAO on a depth texture in your own GL 4.3+ context. Only the
// installed sao::gl and the system's EGL are used (tests/package builds it against the package);
// the block between the readme markers is quoted in README.md (a test keeps the two identical).
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "sao/gl/effect.h"

// Stand-in for your window system: a surfaceless GL 4.3 core context (Mesa's EGL), made current.
static EGLDisplay makeContextCurrent() {
  EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr) || !eglBindAPI(EGL_OPENGL_API))
    return EGL_NO_DISPLAY;
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 3,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
  if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    eglTerminate(display);
    return EGL_NO_DISPLAY;
  }
  return display;
}

#define SAO_GL_FN(type, name) const auto name = reinterpret_cast<type>(eglGetProcAddress(#name))

int main() {
  // Stand-in for your engine: a context and the depth texture of a floor seen from above it.
  EGLDisplay display = makeContextCurrent();
  if (display == EGL_NO_DISPLAY) return std::fprintf(stderr, "no EGL surfaceless GL 4.3 context\n"), 1;
  SAO_GL_FN(PFNGLGENTEXTURESPROC, glGenTextures);
  SAO_GL_FN(PFNGLBINDTEXTUREPROC, glBindTexture);
  SAO_GL_FN(PFNGLTEXSTORAGE2DPROC, glTexStorage2D);
  SAO_GL_FN(PFNGLTEXSUBIMAGE2DPROC, glTexSubImage2D);
  SAO_GL_FN(PFNGLDELETETEXTURESPROC, glDeleteTextures);
  const std::uint32_t width = 320, height = 180;
  std::vector<float> floor;
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) floor.push_back(0.5f + 0.4f * y / height);
  GLuint depthTexture = 0;
  glGenTextures(1, &depthTexture);
  glBindTexture(GL_TEXTURE_2D, depthTexture);
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, width, height);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, floor.data());
  glBindTexture(GL_TEXTURE_2D, 0);

  // [readme-gl]
  std::unique_ptr<sao::gl::Effect> ao;
  sao::Status status = sao::gl::Effect::create(eglGetProcAddress, ao);  // or glfwGetProcAddress, ...
  sao::Camera camera = sao::perspectiveCamera(std::numbers::pi / 3, width, height, 0.1, 100.0,
                                              sao::ClipDepth::NegativeOneToOne, /*reversedZ=*/false);
  sao::Settings settings = sao::presetSettings(sao::Preset::Medium);
  settings.radius = 0.5f;  // metres
  sao::gl::Inputs inputs;
  inputs.depth = {depthTexture, sao::gl::kDepthComponent32F};
  if (status) status = ao->render(camera, settings, inputs);
  if (!status) std::fprintf(stderr, "sao: %s\n", status.message.c_str());
  const std::uint32_t aoTexture = ao ? ao->aoTexture() : 0;  // R16F, linear visibility in [0, 1]
  // [/readme-gl]

  std::printf("GL: %s, AO texture %u, %.1f MB planned\n", status ? "ok" : "failed", aoTexture,
              ao ? ao->plan().totalBytes / 1e6 : 0.0);
  ao.reset();  // while the context is current: the effect deletes its GL objects
  glDeleteTextures(1, &depthTexture);
  eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglTerminate(display);
  return status ? 0 : 1;
}
