// Shared checks of the readers and writers; see io_checks.h.
#include "io_checks.h"

#include <filesystem>
#include <system_error>

#include "sao/plan.h"  // kMaxImageSide

namespace sao::io::detail {

Status fail(StatusCode code, const std::string& path, const std::string& problem) {
  return Status::error(code, path + ": " + problem);
}

std::string describe(std::uint32_t x, std::uint32_t y) {
  return "(" + std::to_string(x) + ", " + std::to_string(y) + ")";
}

Status checkWritable(const std::string& path) {
  if (path.empty()) return Status::error(StatusCode::IoError, "empty path");
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return fail(StatusCode::IoError, path, "is a directory, cannot write a file there");
  return Status::success();
}

Status checkExtent(const std::string& path, Extent e) {
  if (e.width == 0 || e.height == 0)
    return fail(StatusCode::InvalidExtent, path,
                "image is " + std::to_string(e.width) + "x" + std::to_string(e.height) + "; both sides must be > 0");
  if (e.width > kMaxImageSide || e.height > kMaxImageSide)
    return fail(StatusCode::InvalidExtent, path,
                "image is " + std::to_string(e.width) + "x" + std::to_string(e.height) + "; the largest side is " +
                    std::to_string(kMaxImageSide));
  return Status::success();
}

}  // namespace sao::io::detail
