// The GL entry points the effect calls, loaded through the caller's getProcAddress. There are no
// global gl* symbols in the library: every call goes through a GlFunctions table.
#pragma once
#include <GL/glcorearb.h>  // typedefs only (GL_GLEXT_PROTOTYPES is never defined)

#include "sao/gl/effect.h"
#include "sao/status.h"

namespace sao::gl::detail {

// X(type, name): required GL 4.3 core entry points; loaded as "gl" #name.
#define SAO_GL_REQUIRED_FUNCTIONS(X)                                   \
  X(PFNGLGETSTRINGPROC, GetString)                                     \
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
  X(PFNGLTEXTUREVIEWPROC, TextureView)                                 \
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
  X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)                 \
  X(PFNGLOBJECTLABELPROC, ObjectLabel)

// Optional: used when the context has them (GL 4.5 / ARB_direct_state_access).
#define SAO_GL_OPTIONAL_FUNCTIONS(X)                                   \
  X(PFNGLGETTEXTUREPARAMETERIVPROC, GetTextureParameteriv)

struct GlFunctions {
#define SAO_GL_DECLARE(type, name) type name = nullptr;
  SAO_GL_REQUIRED_FUNCTIONS(SAO_GL_DECLARE)
  SAO_GL_OPTIONAL_FUNCTIONS(SAO_GL_DECLARE)
#undef SAO_GL_DECLARE

  int major = 0, minor = 0;  // context version (after load())
  bool hasDsa = false;       // GetTextureParameteriv usable (GL 4.5)
  bool hasQueryBuffer = false;  // GL_QUERY_BUFFER exists (GL 4.4)

  bool atLeast(int maj, int min) const { return major > maj || (major == maj && minor >= min); }

  // Loads every entry point; DriverError naming the first missing one or a context below 4.3.
  Status load(GetProcAddressFn getProcAddress);
};

const char* glEnumName(GLenum e);  // for messages: "GL_DEPTH_COMPONENT24", or hex

}  // namespace sao::gl::detail
