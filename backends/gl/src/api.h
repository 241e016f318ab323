// Which API these sources build: sao::gl (OpenGL 4.3) or, with SAO_GL_ES=1, sao::gles (OpenGL ES
// 3.1, library sao_gles). SAO_GL_NS names the namespace; kEs tells the few places that differ.
#pragma once
#ifndef SAO_GL_ES
#define SAO_GL_ES 0
#endif
#if SAO_GL_ES
#include "sao/gles/effect.h"
#define SAO_GL_NS gles
#else
#include "sao/gl/effect.h"
#define SAO_GL_NS gl
#endif

namespace sao::SAO_GL_NS::detail {
inline constexpr bool kEs = SAO_GL_ES != 0;
inline constexpr const char* kApiName = SAO_GL_ES ? "sao::gles" : "sao::gl";
}  // namespace sao::SAO_GL_NS::detail
