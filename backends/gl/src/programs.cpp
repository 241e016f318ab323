#include "programs.h"

#include <algorithm>
#include <string>

namespace sao::SAO_GL_NS::detail {

Programs::~Programs() {
  for (GLuint p : programs_)
    if (p) gl_.DeleteProgram(p);
}

Status Programs::get(const gen::PassInfo& pass, const gen::PassVariantInfo& variant, GLuint& program,
                     std::uint64_t& compiled) {
  const std::uint32_t blob = sourceBlob(variant);
  if (blob >= programs_.size())
    return Status::error(kEs ? StatusCode::UnsupportedFormat : StatusCode::DriverError,
                         std::string(kApiName) + ": pass '" + std::string(pass.name) + "' (" + std::string(variant.fileStem) +
                             ") has no " + (kEs ? "GLSL ES: a format the effect refuses on OpenGL ES 3.1 (its `target gles` rule)"
                                                : "GLSL blob"));
  if (GLuint p = programs_[blob]) {
    program = p;
    return Status::success();
  }
  const std::string_view source = kEs ? gen::esslSource(blob) : gen::glslSource(blob);
  const std::string what = "pass '" + std::string(pass.name) + "' (" + std::string(variant.fileStem) + ")";
  const GLchar* text = source.data();
  const GLint length = GLint(source.size());

  const GLuint shader = gl_.CreateShader(GL_COMPUTE_SHADER);
  if (!shader) return Status::error(StatusCode::DriverError, std::string(kApiName) + ": glCreateShader failed for " + what);
  gl_.ShaderSource(shader, 1, &text, &length);
  gl_.CompileShader(shader);
  GLint ok = GL_FALSE, logLength = 0;
  gl_.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    gl_.GetShaderiv(shader, GL_INFO_LOG_LENGTH, &logLength);
    std::string log(std::size_t(std::max(logLength, 1)), '\0');
    gl_.GetShaderInfoLog(shader, GLsizei(log.size()), nullptr, log.data());
    gl_.DeleteShader(shader);
    return Status::error(StatusCode::DriverError, std::string(kApiName) + ": the driver rejected the GLSL of " + what + ": " +
                                                      std::string(log.c_str()));
  }
  const GLuint p = gl_.CreateProgram();
  gl_.AttachShader(p, shader);
  gl_.LinkProgram(p);
  gl_.DetachShader(p, shader);
  gl_.DeleteShader(shader);
  gl_.GetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    gl_.GetProgramiv(p, GL_INFO_LOG_LENGTH, &logLength);
    std::string log(std::size_t(std::max(logLength, 1)), '\0');
    gl_.GetProgramInfoLog(p, GLsizei(log.size()), nullptr, log.data());
    gl_.DeleteProgram(p);
    return Status::error(StatusCode::DriverError, std::string(kApiName) + ": linking " + what + " failed: " + std::string(log.c_str()));
  }
  const std::string label = "sao " + std::string(variant.fileStem);
  gl_.label(GL_PROGRAM, p, label);
  programs_[blob] = p;
  ++compiled;
  program = p;
  return Status::success();
}

}  // namespace sao::SAO_GL_NS::detail
