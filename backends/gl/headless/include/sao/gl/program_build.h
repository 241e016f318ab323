// GL programs from GLSL text, for the code that draws with raw GL beside the effect (the prepass,
// the viewer, sao-bench's per_tap ladder): a compile or link failure comes back as a Status that
// carries the driver's log.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "sao/status.h"

namespace sao::gl {

struct ShaderStage {
  std::uint32_t stage = 0;  // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER, ...
  std::string text;         // complete GLSL, #version line first
  std::string name;         // for messages: "prepass.vert"
};

// Compiles the stages and links them into a program (`out`, 0 on failure); the shader objects are
// deleted either way. Errors read "<what>: <stage name> does not compile: <log>" or
// "<what> does not link: <log>". Needs a current context.
Status buildProgram(const std::vector<ShaderStage>& stages, const std::string& what, std::uint32_t& out);

}  // namespace sao::gl
