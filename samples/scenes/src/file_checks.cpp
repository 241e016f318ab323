#include "file_checks.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace sao::scenes::detail {

namespace fs = std::filesystem;

Status checkRegularFile(const std::string& path) {
  if (path.empty()) return Status::error(StatusCode::IoError, "empty file name");
  if (path.find('\0') != std::string::npos) return fileError(StatusCode::IoError, path, "the name contains a NUL byte");
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (st.type() == fs::file_type::not_found) return fileError(StatusCode::IoError, path, "no such file");
  if (ec) return fileError(StatusCode::IoError, path, "cannot access: " + ec.message());
  if (st.type() == fs::file_type::directory) return fileError(StatusCode::IoError, path, "is a directory, not a file");
  if (st.type() != fs::file_type::regular)
    return fileError(StatusCode::IoError, path, "is not a regular file (a FIFO, socket or device)");
  return Status::success();
}

std::string lowerExtension(std::string_view path) {
  std::string ext = fs::path(std::string(path)).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

Status readWholeFile(const std::string& path, std::uintmax_t maxBytes, std::string& out) {
  if (Status s = checkRegularFile(path); !s) return s;
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) return fileError(StatusCode::IoError, path, "cannot read its size: " + ec.message());
  if (size > maxBytes)
    return fileError(StatusCode::IoError, path,
                     "is " + std::to_string(size) + " bytes, more than the limit of " + std::to_string(maxBytes));
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in.is_open())
    return fileError(StatusCode::IoError, path, std::string("cannot open: ") + (errno ? std::strerror(errno) : "unknown error"));
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  if (in.gcount() != static_cast<std::streamsize>(size)) return fileError(StatusCode::IoError, path, "cannot read it");
  out = std::move(text);
  return Status::success();
}

}  // namespace sao::scenes::detail
