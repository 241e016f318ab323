#include "gl_functions.h"

#include <cstdio>
#include <string>
#include <string_view>
#include <type_traits>

namespace sao::SAO_GL_NS::detail {

Status GlFunctions::load(GetProcAddressFn getProcAddress) {
  if (!getProcAddress)
    return Status::error(StatusCode::InvalidInput, std::string(kApiName) + ": getProcAddress is null");
#define SAO_GL_LOAD(type, name)                                                                        \
  name = reinterpret_cast<type>(getProcAddress("gl" #name));                                           \
  if (!name)                                                                                           \
    return Status::error(StatusCode::DriverError, std::string(kApiName) + ": getProcAddress returned null for gl" #name \
                                                  " (an OpenGL 4.3 core entry point)");
  SAO_GL_REQUIRED_FUNCTIONS(SAO_GL_LOAD)
  if constexpr (!kEs) {
    SAO_GL_CORE_ES_OPTIONAL_FUNCTIONS(SAO_GL_LOAD)
  }
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
  const GLubyte* versionText = GetString(GL_VERSION);
  const bool esContext = versionText && std::string(reinterpret_cast<const char*>(versionText)).rfind("OpenGL ES", 0) == 0;
  if constexpr (kEs) {
    if (!esContext || !atLeast(3, 1))
      return Status::error(StatusCode::DriverError,
                           "sao::gles needs an OpenGL ES 3.1 or newer context (compute shaders); the current context "
                           "reports " +
                               std::to_string(maj) + "." + std::to_string(min) +
                               (versionText ? " (\"" + std::string(reinterpret_cast<const char*>(versionText)) + "\")"
                                            : std::string(" (is a context current on this thread?)")) +
                               (versionText && !esContext ? ": use sao::gl on desktop OpenGL" : ""));
    hasDsa = false;  // ES has no direct state access
    hasQueryBuffer = false;
    // Each from the version or extension that has it (eglGetProcAddress answers any known name,
    // so the extension string decides), under that extension's name. No texture views: ES reads
    // no array inputs here (inputs.cpp cannot query a texture's target without DSA).
    GLint count = 0;
    GetIntegerv(GL_NUM_EXTENSIONS, &count);
    auto has = [&](std::string_view name) {
      for (GLint i = 0; i < count; ++i)
        if (const GLubyte* e = GetStringi(GL_EXTENSIONS, GLuint(i)); e && name == reinterpret_cast<const char*>(e))
          return true;
      return false;
    };
    auto load = [&](auto& fn, const char* name) {
      fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(getProcAddress(name));
    };
    if (has("GL_EXT_disjoint_timer_query")) load(GetQueryObjectui64v, "glGetQueryObjectui64vEXT");
    if (atLeast(3, 2)) load(ObjectLabel, "glObjectLabel");
    else if (has("GL_KHR_debug")) load(ObjectLabel, "glObjectLabelKHR");
    return Status::success();
  }
  if (esContext)
    return Status::error(StatusCode::DriverError, "sao::gl needs desktop OpenGL 4.3; the current context is \"" +
                                                      std::string(reinterpret_cast<const char*>(versionText)) +
                                                      "\": use sao::gles on OpenGL ES");
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

}  // namespace sao::SAO_GL_NS::detail
