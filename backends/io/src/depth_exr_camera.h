// The camera and depth format of a depth EXR, read from its sao.* header attributes (sao/io.h
// lists them with their types).
#pragma once
#include <string>

#include "exr_reader.h"
#include "sao/camera.h"
#include "sao/image.h"
#include "sao/status.h"

namespace sao::io::detail {

// The camera's attributes besides sao.version (sao/io.h), in sorted order.
inline constexpr const char* kCameraAttributes[] = {
    "sao.clipDepth", "sao.depthFormat", "sao.flipY", "sao.guardBand", "sao.height", "sao.infiniteFar",
    "sao.kind", "sao.metersToViewUnits", "sao.projection", "sao.reversedZ", "sao.width"};

// For a file that has sao.version: every attribute present, of the right type, finite and in range.
// IoError for a missing, mistyped or out-of-range attribute; UnsupportedFormat for an unknown
// version, kind, clip-depth or format string. `camera` and `format` may be partly written on error.
Status readDepthCamera(const exr::Input& in, const std::string& path, Camera& camera, DepthFormat& format);

}  // namespace sao::io::detail
