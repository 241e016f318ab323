// Small OpenGL helpers of the viewer: programs from the shared GLSL sources.
#pragma once
#include <epoxy/gl.h>

#include <string>
#include <string_view>

#include "sao/status.h"

namespace sao::viewer {

// The shared shader sources start with "#version 450" (for glslangValidator); OpenGL gets them
// as GLSL 4.30 core.
std::string glslFor430(std::string_view source);

// Links a program from a vertex and an optional fragment shader; `out` is 0 on failure.
Status linkProgram(std::string_view vertex, std::string_view fragment, const char* name, GLuint& out);

}  // namespace sao::viewer
