// What every reader and writer of sao/io.h shares: errors that name the path, the checks on a path
// and an image before anything is written, and the guard that keeps exceptions inside.
#pragma once
#include <cstdint>
#include <exception>
#include <new>
#include <string>

#include "sao/image.h"
#include "sao/status.h"

namespace sao::io::detail {

// An error whose message starts with the path.
Status fail(StatusCode code, const std::string& path, const std::string& problem);

// "(x, y)", for messages that name a pixel.
std::string describe(std::uint32_t x, std::uint32_t y);

// A path a file can be written to: not empty, not a directory.
Status checkWritable(const std::string& path);

// An image that can be written: both sides > 0 and at most kMaxImageSide.
Status checkExtent(const std::string& path, Extent e);

// Runs `body`, turning every exception into an IoError that names the path: no exception leaves
// sao/io.h.
template <class F>
Status guarded(const std::string& path, const char* action, F&& body) {
  try {
    return body();
  } catch (const std::bad_alloc&) {
    return fail(StatusCode::IoError, path, std::string("out of memory while ") + action);
  } catch (const std::exception& ex) {
    return fail(StatusCode::IoError, path, std::string("cannot ") + action + ": " + ex.what());
  } catch (...) {
    return fail(StatusCode::IoError, path, std::string("cannot ") + action + ": unknown error");
  }
}

}  // namespace sao::io::detail
