// The vocabulary of a depth EXR (sao/io.h), shared by its reader and its writer: the channel name,
// the strings that name the depth format, projection kind and clip-depth convention, and the rule
// that ties the image extent to the camera's viewport and guard band.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "sao/camera.h"
#include "sao/image.h"

namespace sao::io::detail {

inline constexpr const char* kDepthChannel = "Z";

// nullptr for a value outside the enum.
const char* formatName(DepthFormat f);
const char* kindName(ProjectionKind k);
const char* clipName(ClipDepth c);
std::optional<DepthFormat> parseFormat(const std::string& s);

// Largest value of an integer depth format (0 for float formats).
std::uint32_t integerMax(DepthFormat f);

// The depth image holds the viewport plus the guard band on every side.
bool extentMatches(Extent e, std::uint64_t width, std::uint64_t height, std::uint64_t guard);
std::string extentMismatch(Extent e, std::uint64_t width, std::uint64_t height, std::uint64_t guard);

}  // namespace sao::io::detail
