#include "gl_util.h"

#include <vector>

#include "sao/gl/program_build.h"

namespace sao::viewer {

std::string glslFor430(std::string_view source) {
  const auto eol = source.find('\n');
  const std::string_view rest = eol == std::string_view::npos ? std::string_view{} : source.substr(eol + 1);
  return "#version 430 core\n" + std::string(rest);
}

Status linkProgram(std::string_view vertex, std::string_view fragment, const char* name, GLuint& out) {
  std::vector<gl::ShaderStage> stages{{GL_VERTEX_SHADER, glslFor430(vertex), "vertex shader"}};
  if (!fragment.empty()) stages.push_back({GL_FRAGMENT_SHADER, glslFor430(fragment), "fragment shader"});
  return gl::buildProgram(stages, name, out);
}

}  // namespace sao::viewer
