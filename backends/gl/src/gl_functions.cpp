#include "gl_functions.h"

#include <cstdio>
#include <string>

namespace sao::gl::detail {

Status GlFunctions::load(GetProcAddressFn getProcAddress) {
  if (!getProcAddress)
    return Status::error(StatusCode::InvalidInput, "sao::gl: getProcAddress is null");
#define SAO_GL_LOAD(type, name)                                                                        \
  name = reinterpret_cast<type>(getProcAddress("gl" #name));                                           \
  if (!name)                                                                                           \
    return Status::error(StatusCode::DriverError, "sao::gl: getProcAddress returned null for gl" #name \
                                                  " (an OpenGL 4.3 core entry point)");
  SAO_GL_REQUIRED_FUNCTIONS(SAO_GL_LOAD)
#undef SAO_GL_LOAD
#define SAO_GL_LOAD_OPTIONAL(type, name) name = reinterpret_cast<type>(getProcAddress("gl" #name));
  SAO_GL_OPTIONAL_FUNCTIONS(SAO_GL_LOAD_OPTIONAL)
#undef SAO_GL_LOAD_OPTIONAL

  // Without a current context the GL returns nothing: the zeros below then fail the check.
  GLint maj = 0, min = 0;
  GetIntegerv(GL_MAJOR_VERSION, &maj);
  GetIntegerv(GL_MINOR_VERSION, &min);
  major = maj;
  minor = min;
  if (!atLeast(4, 3)) {
    const GLubyte* version = GetString(GL_VERSION);
    return Status::error(StatusCode::DriverError,
                         "sao::gl needs OpenGL 4.3 or newer (compute shaders, texture views); the current context "
                         "reports " +
                             std::to_string(maj) + "." + std::to_string(min) +
                             (version ? " (\"" + std::string(reinterpret_cast<const char*>(version)) + "\")"
                                      : std::string(" (is a context current on this thread?)")));
  }
  hasDsa = atLeast(4, 5) && GetTextureParameteriv != nullptr;
  hasQueryBuffer = atLeast(4, 4);
  return Status::success();
}

const char* glEnumName(GLenum e) {
  switch (e) {
    case GL_DEPTH_COMPONENT: return "GL_DEPTH_COMPONENT";
    case GL_DEPTH_STENCIL: return "GL_DEPTH_STENCIL";
    case GL_DEPTH_COMPONENT16: return "GL_DEPTH_COMPONENT16";
    case GL_DEPTH_COMPONENT24: return "GL_DEPTH_COMPONENT24";
    case GL_DEPTH_COMPONENT32: return "GL_DEPTH_COMPONENT32";
    case GL_DEPTH_COMPONENT32F: return "GL_DEPTH_COMPONENT32F";
    case GL_DEPTH24_STENCIL8: return "GL_DEPTH24_STENCIL8";
    case GL_DEPTH32F_STENCIL8: return "GL_DEPTH32F_STENCIL8";
    case GL_R32F: return "GL_R32F";
    case GL_R16F: return "GL_R16F";
    case GL_RG32F: return "GL_RG32F";
    case GL_RG16F: return "GL_RG16F";
    case GL_RG8_SNORM: return "GL_RG8_SNORM";
    case GL_RG16_SNORM: return "GL_RG16_SNORM";
    case GL_RGBA16F: return "GL_RGBA16F";
    case GL_RGBA32F: return "GL_RGBA32F";
    case GL_RGB16F: return "GL_RGB16F";
    case GL_RGB32F: return "GL_RGB32F";
    case GL_RGBA8: return "GL_RGBA8";
    case GL_RGBA8_SNORM: return "GL_RGBA8_SNORM";
    case GL_RGBA16_SNORM: return "GL_RGBA16_SNORM";
    case GL_R8: return "GL_R8";
    case GL_R16: return "GL_R16";
    case GL_R32UI: return "GL_R32UI";
    case GL_TEXTURE_2D: return "GL_TEXTURE_2D";
    case GL_TEXTURE_2D_ARRAY: return "GL_TEXTURE_2D_ARRAY";
    case GL_TEXTURE_3D: return "GL_TEXTURE_3D";
    case GL_TEXTURE_CUBE_MAP: return "GL_TEXTURE_CUBE_MAP";
    case GL_TEXTURE_RECTANGLE: return "GL_TEXTURE_RECTANGLE";
    case GL_TEXTURE_2D_MULTISAMPLE: return "GL_TEXTURE_2D_MULTISAMPLE";
    case GL_TEXTURE_2D_MULTISAMPLE_ARRAY: return "GL_TEXTURE_2D_MULTISAMPLE_ARRAY";
    case GL_STENCIL_INDEX8: return "GL_STENCIL_INDEX8";
    case GL_TEXTURE_1D: return "GL_TEXTURE_1D";
    default: break;
  }
  thread_local char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04X", e);
  return buf;
}

}  // namespace sao::gl::detail
