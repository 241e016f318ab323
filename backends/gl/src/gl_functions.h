// The GL entry points the effect calls, loaded through the caller's getProcAddress. There are no
// global gl* symbols in the library: every call goes through a GlFunctions table.
#pragma once
#include <GL/glcorearb.h>  // typedefs only (GL_GLEXT_PROTOTYPES is never defined)

#include <string_view>

#include "api.h"
#include "sao/status.h"

namespace sao::SAO_GL_NS::detail {

// X(type, name): required GL 4.3 core (and ES 3.1) entry points; loaded as "gl" #name.
#define SAO_GL_REQUIRED_FUNCTIONS(X)                                   \
  X(PFNGLGETSTRINGPROC, GetString)                                     \
  X(PFNGLGETSTRINGIPROC, GetStringi)                                   \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                 \
  X(PFNGLGETINTEGERI_VPROC, GetIntegeri_v)                             \
  X(PFNGLGETINTEGER64I_VPROC, GetInteger64i_v)                         \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                             \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                 \
  X(PFNGLISTEXTUREPROC, IsTexture)                                     \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                 \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                           \
  X(PFNGLTEXSTORAGE2DPROC, TexStorage2D)                               \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                             \
  X(PFNGLGETTEXPARAMETERIVPROC, GetTexParameteriv)                     \
  X(PFNGLGETTEXLEVELPARAMETERIVPROC, GetTexLevelParameteriv)           \
  X(PFNGLGENSAMPLERSPROC, GenSamplers)                                 \
  X(PFNGLDELETESAMPLERSPROC, DeleteSamplers)                           \
  X(PFNGLSAMPLERPARAMETERIPROC, SamplerParameteri)                     \
  X(PFNGLBINDSAMPLERPROC, BindSampler)                                 \
  X(PFNGLBINDIMAGETEXTUREPROC, BindImageTexture)                       \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                   \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                             \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                   \
  X(PFNGLBUFFERDATAPROC, BufferData)                                   \
  X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                             \
  X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                           \
  X(PFNGLBINDBUFFERRANGEPROC, BindBufferRange)                         \
  X(PFNGLCREATESHADERPROC, CreateShader)                               \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                               \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                             \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                 \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                       \
  X(PFNGLDELETESHADERPROC, DeleteShader)                               \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                             \
  X(PFNGLATTACHSHADERPROC, AttachShader)                               \
  X(PFNGLDETACHSHADERPROC, DetachShader)                               \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                 \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                               \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                     \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                             \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                   \
  X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                         \
  X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                             \
  X(PFNGLFINISHPROC, Finish)                                           \
  X(PFNGLGENQUERIESPROC, GenQueries)                                   \
  X(PFNGLDELETEQUERIESPROC, DeleteQueries)                             \
  X(PFNGLBEGINQUERYPROC, BeginQuery)                                   \
  X(PFNGLENDQUERYPROC, EndQuery)                                       \
  X(PFNGLGETQUERYIVPROC, GetQueryiv)                                   \

// Required on OpenGL 4.3; on ES optional, loaded under the extensions' names (labels: ES 3.2 or
// KHR_debug; 64-bit query results: EXT_disjoint_timer_query; texture views never: ES reads no
// array inputs). Null where an ES context has none: the call sites check.
#define SAO_GL_CORE_ES_OPTIONAL_FUNCTIONS(X)                           \
  X(PFNGLTEXTUREVIEWPROC, TextureView)                                 \
  X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)                 \
  X(PFNGLOBJECTLABELPROC, ObjectLabel)

// Optional: used when the context has them (GL 4.5 / ARB_direct_state_access).
#define SAO_GL_OPTIONAL_FUNCTIONS(X)                                   \
  X(PFNGLGETTEXTUREPARAMETERIVPROC, GetTextureParameteriv)

struct GlFunctions {
#define SAO_GL_DECLARE(type, name) type name = nullptr;
  SAO_GL_REQUIRED_FUNCTIONS(SAO_GL_DECLARE)
  SAO_GL_CORE_ES_OPTIONAL_FUNCTIONS(SAO_GL_DECLARE)
  SAO_GL_OPTIONAL_FUNCTIONS(SAO_GL_DECLARE)
#undef SAO_GL_DECLARE

  int major = 0, minor = 0;  // context version (after load())
  bool hasDsa = false;       // GetTextureParameteriv usable (GL 4.5)
  bool hasQueryBuffer = false;  // GL_QUERY_BUFFER exists (GL 4.4)

  bool atLeast(int maj, int min) const { return major > maj || (major == maj && minor >= min); }
  // glObjectLabel where the context has it (every GL 4.3; ES 3.2 or KHR_debug).
  void label(GLenum type, GLuint name, std::string_view text) const {
    if (ObjectLabel) ObjectLabel(type, name, GLsizei(text.size()), text.data());
  }

  // Loads every entry point; DriverError naming the first missing one or a context below 4.3 (ES:
  // below 3.1, or not an ES context).
  Status load(GetProcAddressFn getProcAddress);
};

const char* glEnumName(GLenum e);  // for messages: "GL_DEPTH_COMPONENT24", or hex

}  // namespace sao::SAO_GL_NS::detail
