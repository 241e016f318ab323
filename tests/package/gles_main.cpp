// sao::gles from a consumer's point of view, the component taken alone: a surfaceless EGL OpenGL
// ES 3.1 context (Mesa), a D32F depth texture at the far plane everywhere (sky), one render, the AO
// read back through a framebuffer (ES has no glGetTexImage: A = 1 everywhere), a bad input and a
// GL_R16F output refused (ES stores no r16f image), a header version mismatch reported. Only EGL
// is linked; GLES comes through eglGetProcAddress, for the effect and for this program.
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <numbers>
#include <vector>

#include "consumer_check.h"
#include "sao/gles/effect.h"

namespace {

sao::gles::ProcAddress load(const char* name) {
  return reinterpret_cast<sao::gles::ProcAddress>(eglGetProcAddress(name));
}

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
  CHECK(eglBindAPI(EGL_OPENGL_ES_API));
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 1, EGL_NONE};
  EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
  CHECK(context != EGL_NO_CONTEXT);
  CHECK(eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context));

  auto genTextures = fn<PFNGLGENTEXTURESPROC>("glGenTextures");
  auto bindTexture = fn<PFNGLBINDTEXTUREPROC>("glBindTexture");
  auto texStorage2D = fn<PFNGLTEXSTORAGE2DPROC>("glTexStorage2D");
  auto texSubImage2D = fn<PFNGLTEXSUBIMAGE2DPROC>("glTexSubImage2D");
  auto deleteTextures = fn<PFNGLDELETETEXTURESPROC>("glDeleteTextures");
  auto pixelStorei = fn<PFNGLPIXELSTOREIPROC>("glPixelStorei");
  auto getString = fn<PFNGLGETSTRINGPROC>("glGetString");
  auto genFramebuffers = fn<PFNGLGENFRAMEBUFFERSPROC>("glGenFramebuffers");
  auto bindFramebuffer = fn<PFNGLBINDFRAMEBUFFERPROC>("glBindFramebuffer");
  auto framebufferTexture2D = fn<PFNGLFRAMEBUFFERTEXTURE2DPROC>("glFramebufferTexture2D");
  auto checkFramebufferStatus = fn<PFNGLCHECKFRAMEBUFFERSTATUSPROC>("glCheckFramebufferStatus");
  auto readPixels = fn<PFNGLREADPIXELSPROC>("glReadPixels");
  auto deleteFramebuffers = fn<PFNGLDELETEFRAMEBUFFERSPROC>("glDeleteFramebuffers");
  CHECK(genTextures && bindTexture && texStorage2D && texSubImage2D && deleteTextures && pixelStorei && getString &&
        genFramebuffers && bindFramebuffer && framebufferTexture2D && checkFramebufferStatus && readPixels &&
        deleteFramebuffers);
  std::printf("GLES: %s on %s\n", reinterpret_cast<const char*>(getString(GL_VERSION)),
              reinterpret_cast<const char*>(getString(GL_RENDERER)));

  {
    std::unique_ptr<sao::gles::Effect> wrong;
    const sao::Status st = sao::gles::Effect::create(&load, wrong, SAO_VERSION + 1);
    CHECK(st.code == sao::StatusCode::VersionMismatch && !wrong);
  }

  std::unique_ptr<sao::gles::Effect> effect;
  sao::Status st = sao::gles::Effect::create(&load, effect);
  if (!st) std::fprintf(stderr, "create: %s\n", st.message.c_str());
  CHECK(st.ok());

  sao::Camera camera = sao::perspectiveCamera(std::numbers::pi / 3, 64, 36, 0.1, 100.0,
                                              sao::ClipDepth::NegativeOneToOne, false);
  camera.guardBand = 4;
  const int w = 72, h = 44;
  GLuint depth = 0, r16f = 0;
  genTextures(1, &depth);
  bindTexture(GL_TEXTURE_2D, depth);
  texStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, w, h);
  const std::vector<float> far(std::size_t(w) * h, 1.0f);
  pixelStorei(GL_UNPACK_ALIGNMENT, 4);
  texSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, far.data());
  genTextures(1, &r16f);
  bindTexture(GL_TEXTURE_2D, r16f);
  texStorage2D(GL_TEXTURE_2D, 1, GL_R16F, 64, 36);
  bindTexture(GL_TEXTURE_2D, 0);

  sao::gles::Inputs bad;  // depth texture 0
  st = effect->render(camera, sao::Settings{}, bad);
  CHECK(st.code == sao::StatusCode::InvalidInput && !st.message.empty());

  sao::gles::Inputs in;
  in.depth = {depth, sao::gles::kDepthComponent32F};
  in.output = r16f;  // ES stores no r16f image: refused, naming the formats ES takes
  st = effect->render(camera, sao::Settings{}, in);
  CHECK(st.code == sao::StatusCode::UnsupportedFormat && std::strstr(st.message.c_str(), "GL_R32F"));

  in.output = 0;
  st = effect->render(camera, sao::Settings{}, in);
  if (!st) std::fprintf(stderr, "render: %s\n", st.message.c_str());
  CHECK(st.ok());
  // The owned output is GL_R32F on ES: read through a framebuffer as RGBA floats.
  GLuint fbo = 0;
  genFramebuffers(1, &fbo);
  bindFramebuffer(GL_FRAMEBUFFER, fbo);
  framebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, effect->aoTexture(), 0);
  CHECK(checkFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
  std::vector<float> ao(std::size_t(64) * 36 * 4, -1.0f);
  pixelStorei(GL_PACK_ALIGNMENT, 4);
  readPixels(0, 0, 64, 36, GL_RGBA, GL_FLOAT, ao.data());
  bindFramebuffer(GL_FRAMEBUFFER, 0);
  deleteFramebuffers(1, &fbo);
  for (std::size_t i = 0; i < ao.size(); i += 4) CHECK(ao[i] == 1.0f);  // nothing occludes the sky

  effect.reset();
  deleteTextures(1, &depth);
  deleteTextures(1, &r16f);
  eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display, context);
  eglTerminate(display);
  std::printf("sao::gles: version check, bad input and an r16f output refused, sky renders A = 1 everywhere: ok\n");
  return 0;
}
