// Private to sao_scenes: the checks every file reader here makes before opening a file.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

#include "sao/status.h"

namespace sao::scenes::detail {

// IoError "PATH: no such file", "PATH: is a directory, not a file", "PATH: is not a regular file
// (a FIFO, socket or device)" or "PATH: cannot access: ..."; success for a regular file (a FIFO
// would block the open, a device may never end).
Status checkRegularFile(const std::string& path);

// The extension of the path's file name, lower case, with its dot (".glb"), or "" for none.
std::string lowerExtension(std::string_view path);

// Reads a whole regular file of at most maxBytes bytes (IoError naming the path otherwise).
Status readWholeFile(const std::string& path, std::uintmax_t maxBytes, std::string& out);

// The UTF-8 byte-order mark some editors write at the start of a text file.
inline constexpr std::string_view kUtf8ByteOrderMark = "\xEF\xBB\xBF";

// "PATH: PROBLEM" as a Status.
inline Status fileError(StatusCode code, std::string_view path, const std::string& problem) {
  return Status::error(code, std::string(path) + ": " + problem);
}

}  // namespace sao::scenes::detail
