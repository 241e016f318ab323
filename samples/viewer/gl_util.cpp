#include "gl_util.h"

#include <vector>

namespace sao::viewer {
namespace {

std::string infoLog(GLuint object, bool program) {
  GLint length = 0;
  program ? glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length) : glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(std::size_t(length > 0 ? length : 1), '\0');
  program ? glGetProgramInfoLog(object, length, nullptr, log.data())
          : glGetShaderInfoLog(object, length, nullptr, log.data());
  return log.data();
}

Status compile(GLenum stage, std::string_view source, const char* name, GLuint& out) {
  const std::string text = glslFor430(source);
  const char* ptr = text.c_str();
  out = glCreateShader(stage);
  glShaderSource(out, 1, &ptr, nullptr);
  glCompileShader(out);
  GLint ok = 0;
  glGetShaderiv(out, GL_COMPILE_STATUS, &ok);
  if (ok) return Status::success();
  const std::string log = infoLog(out, false);
  glDeleteShader(out);
  out = 0;
  return Status::error(StatusCode::DriverError, std::string(name) + ": shader does not compile: " + log);
}

}  // namespace

std::string glslFor430(std::string_view source) {
  const auto eol = source.find('\n');
  const std::string_view rest = eol == std::string_view::npos ? std::string_view{} : source.substr(eol + 1);
  return "#version 430 core\n" + std::string(rest);
}

Status linkProgram(std::string_view vertex, std::string_view fragment, const char* name, GLuint& out) {
  out = 0;
  GLuint vs = 0, fs = 0;
  if (Status s = compile(GL_VERTEX_SHADER, vertex, name, vs); !s) return s;
  if (!fragment.empty())
    if (Status s = compile(GL_FRAGMENT_SHADER, fragment, name, fs); !s) {
      glDeleteShader(vs);
      return s;
    }
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  if (fs) glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  if (fs) glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = infoLog(program, true);
    glDeleteProgram(program);
    return Status::error(StatusCode::DriverError, std::string(name) + ": program does not link: " + log);
  }
  out = program;
  return Status::success();
}

}  // namespace sao::viewer
