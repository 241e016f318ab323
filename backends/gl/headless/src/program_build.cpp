#include "sao/gl/program_build.h"

#include <epoxy/gl.h>

namespace sao::gl {
namespace {

std::string infoLog(GLuint object, bool program) {
  GLint length = 0;
  program ? glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length) : glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(std::size_t(length > 0 ? length : 1), '\0');
  program ? glGetProgramInfoLog(object, GLsizei(log.size()), nullptr, log.data())
          : glGetShaderInfoLog(object, GLsizei(log.size()), nullptr, log.data());
  return log.c_str();  // up to the terminating zero
}

}  // namespace

Status buildProgram(const std::vector<ShaderStage>& stages, const std::string& what, std::uint32_t& out) {
  out = 0;
  std::vector<GLuint> shaders;
  auto release = [&shaders] {
    for (GLuint s : shaders) glDeleteShader(s);
  };
  for (const ShaderStage& st : stages) {
    const GLuint s = glCreateShader(st.stage);
    shaders.push_back(s);
    const char* text = st.text.c_str();
    glShaderSource(s, 1, &text, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      const std::string log = infoLog(s, false);
      release();
      return Status::error(StatusCode::DriverError, what + ": " + st.name + " does not compile: " + log);
    }
  }
  const GLuint program = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(program, s);
  glLinkProgram(program);
  release();  // flagged for deletion, freed with the program
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = infoLog(program, true);
    glDeleteProgram(program);
    return Status::error(StatusCode::DriverError, what + " does not link: " + log);
  }
  out = program;
  return Status::success();
}

}  // namespace sao::gl
