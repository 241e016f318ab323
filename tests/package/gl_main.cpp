// sao::gl from a consumer's point of view: a surfaceless EGL context (Mesa), a D32F depth texture
// at the far plane everywhere (sky), one render, the AO read back (1 everywhere), a bad input
// rejected, a header version mismatch reported. Only EGL is linked; GL comes through
// eglGetProcAddress, for the effect and for this program.
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <numbers>
#include <vector>

#include "sao/gl/effect.h"
#include "consumer_check.h"


namespace {

sao::gl::ProcAddress load(const char* name) { return reinterpret_cast<sao::gl::ProcAddress>(eglGetProcAddress(name)); }

template <class F>
F fn(const char* name) {
  return reinterpret_cast<F>(load(name));
}

}  // namespace

int main() {
  auto getPlatformDisplay = fn<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  CHECK(getPlatformDisplay);
  EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  CHECK(display != EGL_NO_DISPLAY);
  EGLint major = 0, minor = 0;
  CHECK(eglInitialize(display, &major, &minor));
  CHECK(eglBindAPI(EGL_OPENGL_API));
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 3,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
  CHECK(context != EGL_NO_CONTEXT);
  CHECK(eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context));

  auto genTextures = fn<PFNGLGENTEXTURESPROC>("glGenTextures");
  auto bindTexture = fn<PFNGLBINDTEXTUREPROC>("glBindTexture");
  auto texStorage2D = fn<PFNGLTEXSTORAGE2DPROC>("glTexStorage2D");
  auto texSubImage2D = fn<PFNGLTEXSUBIMAGE2DPROC>("glTexSubImage2D");
  auto getTexImage = fn<PFNGLGETTEXIMAGEPROC>("glGetTexImage");
  auto deleteTextures = fn<PFNGLDELETETEXTURESPROC>("glDeleteTextures");
  auto pixelStorei = fn<PFNGLPIXELSTOREIPROC>("glPixelStorei");
  auto getString = fn<PFNGLGETSTRINGPROC>("glGetString");
  CHECK(genTextures && bindTexture && texStorage2D && texSubImage2D && getTexImage && deleteTextures && pixelStorei &&
        getString);
  std::printf("GL: %s on %s\n", reinterpret_cast<const char*>(getString(GL_VERSION)),
              reinterpret_cast<const char*>(getString(GL_RENDERER)));

  {
    std::unique_ptr<sao::gl::Effect> wrong;
    const sao::Status st = sao::gl::Effect::create(&load, wrong, SAO_VERSION + 1);
    CHECK(st.code == sao::StatusCode::VersionMismatch && !wrong);
  }

  std::unique_ptr<sao::gl::Effect> effect;
  sao::Status st = sao::gl::Effect::create(&load, effect);
  if (!st) std::fprintf(stderr, "create: %s\n", st.message.c_str());
  CHECK(st.ok());

  sao::Camera camera = sao::perspectiveCamera(std::numbers::pi / 3, 64, 36, 0.1, 100.0,
                                              sao::ClipDepth::NegativeOneToOne, false);
  camera.guardBand = 4;
  const int w = 72, h = 44;
  GLuint depth = 0;
  genTextures(1, &depth);
  bindTexture(GL_TEXTURE_2D, depth);
  texStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, w, h);
  const std::vector<float> far(std::size_t(w) * h, 1.0f);
  pixelStorei(GL_UNPACK_ALIGNMENT, 4);
  texSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, far.data());
  bindTexture(GL_TEXTURE_2D, 0);

  sao::gl::Inputs bad;  // depth texture 0
  st = effect->render(camera, sao::Settings{}, bad);
  CHECK(st.code == sao::StatusCode::InvalidInput && !st.message.empty());

  sao::gl::Inputs in;
  in.depth = {depth, sao::gl::kDepthComponent32F};
  st = effect->render(camera, sao::Settings{}, in);
  if (!st) std::fprintf(stderr, "render: %s\n", st.message.c_str());
  CHECK(st.ok());
  std::vector<float> ao(std::size_t(64) * 36, -1.0f);
  bindTexture(GL_TEXTURE_2D, effect->aoTexture());
  pixelStorei(GL_PACK_ALIGNMENT, 4);
  getTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_FLOAT, ao.data());
  bindTexture(GL_TEXTURE_2D, 0);
  for (float a : ao) CHECK(a == 1.0f);  // nothing occludes the sky

  effect.reset();
  deleteTextures(1, &depth);
  eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display, context);
  eglTerminate(display);
  std::printf("sao::gl: version check, bad input rejected, sky renders A = 1 everywhere: ok\n");
  return 0;
}
