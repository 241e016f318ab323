// The sao.* camera attributes of a depth EXR; see depth_exr_camera.h.
#include "depth_exr_camera.h"

#include <climits>
#include <cmath>
#include <cstdint>
#include <optional>

#include "depth_exr_format.h"
#include "io_checks.h"
#include "sao/io.h"

namespace sao::io::detail {
namespace {

Status missing(const std::string& path, const char* name) {
  return fail(StatusCode::IoError, path, std::string("has sao.version but no ") + name + " attribute");
}

Status intAttribute(const exr::Input& in, const std::string& path, const char* name, int lo, int hi, int& out) {
  bool found = false;
  if (Status s = in.intAttribute(name, found, out); !s) return s;
  if (!found) return missing(path, name);
  if (out < lo || out > hi)
    return fail(StatusCode::IoError, path,
                std::string("attribute ") + name + " is " + std::to_string(out) + "; expected " + std::to_string(lo) +
                    (hi == 1 ? " or " : " to ") + std::to_string(hi));
  return Status::success();
}

Status stringAttribute(const exr::Input& in, const std::string& path, const char* name, std::string& out) {
  bool found = false;
  if (Status s = in.stringAttribute(name, found, out); !s) return s;
  return found ? Status::success() : missing(path, name);
}

Status unknownValue(const std::string& path, const char* name, const std::string& value, const char* known) {
  return fail(StatusCode::UnsupportedFormat, path,
              std::string("attribute ") + name + " is \"" + value + "\"; known values: " + known);
}

}  // namespace

Status readDepthCamera(const exr::Input& in, const std::string& path, Camera& cam, DepthFormat& format) {
  int version = 0;
  if (Status s = intAttribute(in, path, "sao.version", INT_MIN, INT_MAX, version); !s) return s;
  if (version != kDepthExrVersion)
    return fail(StatusCode::UnsupportedFormat, path,
                "sao.version is " + std::to_string(version) + "; this library reads version " +
                    std::to_string(kDepthExrVersion));

  double proj[16] = {};
  bool found = false;
  if (Status s = in.matrixAttribute("sao.projection", found, proj); !s) return s;
  if (!found) return missing(path, "sao.projection");
  for (int i = 0; i < 16; ++i) {
    // Stored as Imath::M44d, m[column][row]: element i is column i / 4, row i % 4.
    if (!std::isfinite(proj[i]))
      return fail(StatusCode::IoError, path,
                  "sao.projection element " + std::to_string(i) + " (row " + std::to_string(i % 4) + ", column " +
                      std::to_string(i / 4) + ") is not finite");
    cam.projection[std::size_t(i)] = proj[i];
  }
  std::string text;
  if (Status s = stringAttribute(in, path, "sao.kind", text); !s) return s;
  if (text == kindName(ProjectionKind::Perspective)) cam.kind = ProjectionKind::Perspective;
  else if (text == kindName(ProjectionKind::Orthographic)) cam.kind = ProjectionKind::Orthographic;
  else return unknownValue(path, "sao.kind", text, "perspective, orthographic");

  if (Status s = stringAttribute(in, path, "sao.clipDepth", text); !s) return s;
  if (text == clipName(ClipDepth::NegativeOneToOne)) cam.clipDepth = ClipDepth::NegativeOneToOne;
  else if (text == clipName(ClipDepth::ZeroToOne)) cam.clipDepth = ClipDepth::ZeroToOne;
  else return unknownValue(path, "sao.clipDepth", text, "negativeOneToOne, zeroToOne");

  int flag = 0;
  if (Status s = intAttribute(in, path, "sao.reversedZ", 0, 1, flag); !s) return s;
  cam.reversedZ = flag != 0;
  if (Status s = intAttribute(in, path, "sao.infiniteFar", 0, 1, flag); !s) return s;
  cam.infiniteFar = flag != 0;
  if (Status s = intAttribute(in, path, "sao.flipY", 0, 1, flag); !s) return s;
  cam.flipY = flag != 0;

  double meters = 0.0;
  if (Status s = in.doubleAttribute("sao.metersToViewUnits", found, meters); !s) return s;
  if (!found) return missing(path, "sao.metersToViewUnits");
  if (!std::isfinite(meters)) return fail(StatusCode::IoError, path, "sao.metersToViewUnits is not finite");
  cam.metersToViewUnits = meters;

  int width = 0, height = 0, guard = 0;
  if (Status s = intAttribute(in, path, "sao.width", 0, INT_MAX, width); !s) return s;
  if (Status s = intAttribute(in, path, "sao.height", 0, INT_MAX, height); !s) return s;
  if (Status s = intAttribute(in, path, "sao.guardBand", 0, INT_MAX, guard); !s) return s;
  cam.width = std::uint32_t(width);
  cam.height = std::uint32_t(height);
  cam.guardBand = std::uint32_t(guard);

  if (Status s = stringAttribute(in, path, "sao.depthFormat", text); !s) return s;
  const std::optional<DepthFormat> f = parseFormat(text);
  if (!f) return unknownValue(path, "sao.depthFormat", text, "D16, D24, D32F, LinearZ");
  format = *f;
  return Status::success();
}

}  // namespace sao::io::detail
