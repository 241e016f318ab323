// Loads the entry file with its includes expanded, keeping each line's origin.
#pragma once
#include <set>
#include <string>
#include <vector>

#include "diagnostics.h"

namespace sao::codegen {

struct SourceLine {
  std::string text;
  SourceLoc loc;
};

struct LoadedSource {
  std::vector<SourceLine> lines;
  std::vector<std::string> files;  // every file read, entry first (for the depfile)
};

// Expands `#include "file"` (relative to the including file), rejects cycles and missing files,
// and drops `#version` and `#extension GL_GOOGLE_include_directive` lines.
LoadedSource loadSource(const std::string& entryPath, Diagnostics& diags);

}  // namespace sao::codegen
