#include "programs.h"

#include <algorithm>
#include <string>

namespace sao::gl::detail {

Programs::~Programs() {
  for (GLuint p : programs_)
    if (p) gl_.DeleteProgram(p);
}

Status Programs::get(const gen::PassInfo& pass, const gen::PassVariantInfo& variant, GLuint& program,
                     std::uint64_t& compiled) {
  if (variant.glslBlob >= programs_.size())
    return Status::error(StatusCode::DriverError, "sao::gl: pass '" + std::string(pass.name) + "' has no GLSL blob");
  if (GLuint p = programs_[variant.glslBlob]) {
    program = p;
    return Status::success();
  }
  const std::string_view source = gen::glslSource(variant.glslBlob);
  const std::string what = "pass '" + std::string(pass.name) + "' (" + std::string(variant.fileStem) + ")";
  const GLchar* text = source.data();
  const GLint length = GLint(source.size());

  const GLuint shader = gl_.CreateShader(GL_COMPUTE_SHADER);
  if (!shader) return Status::error(StatusCode::DriverError, "sao::gl: glCreateShader failed for " + what);
  gl_.ShaderSource(shader, 1, &text, &length);
  gl_.CompileShader(shader);
  GLint ok = GL_FALSE, logLength = 0;
  gl_.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    gl_.GetShaderiv(shader, GL_INFO_LOG_LENGTH, &logLength);
    std::string log(std::size_t(std::max(logLength, 1)), '\0');
    gl_.GetShaderInfoLog(shader, GLsizei(log.size()), nullptr, log.data());
    gl_.DeleteShader(shader);
    return Status::error(StatusCode::DriverError, "sao::gl: the driver rejected the GLSL of " + what + ": " +
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
    return Status::error(StatusCode::DriverError, "sao::gl: linking " + what + " failed: " + std::string(log.c_str()));
  }
  const std::string label = "sao " + std::string(variant.fileStem);
  gl_.ObjectLabel(GL_PROGRAM, p, GLsizei(label.size()), label.c_str());
  programs_[variant.glslBlob] = p;
  ++compiled;
  program = p;
  return Status::success();
}

}  // namespace sao::gl::detail
