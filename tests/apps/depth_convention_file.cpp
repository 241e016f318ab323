// Turns a depth EXR that sao-render --save-depth wrote (its camera in sao.* attributes) into depth
// files as other tools write them, for depth_convention_warnings.sh. For the camera-less ones it
// prints the sao-render flags of the camera (--fovy/--ortho, --near, --far; [0,1] clip).
// Usage: depth_convention_file IN.exr OUT.exr MODE, MODE one of
//   as-is      camera-less "Z": the window depth as stored (reversed-Z for a scene's depth)
//   flipped    camera-less: 1 - d (the other Z convention of the same camera)
//   linear01   camera-less: the distance along the view axis over the largest one, sky 1
//   distances  with its camera, as LinearZ holding positive distances (sky 0)
//   sky        camera-less: every texel 1
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "sao/io.h"

using namespace sao;

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: depth_convention_file IN.exr OUT.exr as-is|flipped|linear01|distances|sky\n");
    return 2;
  }
  const std::string mode = argv[3];
  DepthImage depth;
  Camera camera;
  bool hasCamera = false;
  DepthModel model;
  if (Status s = readDepthExr(argv[1], depth, camera, hasCamera); !s || !hasCamera || !analyze(camera, model)) {
    std::fprintf(stderr, "depth_convention_file: '%s' is not a depth EXR with a camera\n", argv[1]);
    return 1;
  }
  const bool clear = camera.reversedZ;  // the clear value is 0 reversed, 1 standard
  FloatImage out(depth.extent, 1);
  double farthest = 0;
  for (std::uint32_t y = 0; y < depth.extent.height; ++y)
    for (std::uint32_t x = 0; x < depth.extent.width; ++x) {
      const double d = depth.value(x, y);
      const bool sky = clear ? d <= 0 : d >= 1;
      if (!sky) farthest = std::max(farthest, -linearZ(model, camera.kind, d));
    }
  for (std::uint32_t y = 0; y < depth.extent.height; ++y)
    for (std::uint32_t x = 0; x < depth.extent.width; ++x) {
      const double d = depth.value(x, y);
      const bool sky = clear ? d <= 0 : d >= 1;
      const double distance = sky ? 0 : -linearZ(model, camera.kind, d);
      double v = d;
      if (mode == "flipped") v = 1 - d;
      else if (mode == "linear01") v = sky ? 1 : distance / farthest;
      else if (mode == "distances") v = distance;
      else if (mode == "sky") v = 1;
      else if (mode != "as-is") return std::fprintf(stderr, "depth_convention_file: unknown mode '%s'\n", argv[3]), 2;
      out.at(x, y) = float(v);
    }
  Status s;
  if (mode == "distances") {
    DepthImage linear;
    linear.extent = depth.extent;
    linear.format = DepthFormat::LinearZ;
    for (std::uint32_t y = 0; y < depth.extent.height; ++y)
      for (std::uint32_t x = 0; x < depth.extent.width; ++x)
        linear.texels.push_back(encodeDepth(DepthFormat::LinearZ, out.at(x, y)));
    s = writeDepthExr(argv[2], linear, camera);
  } else {
    s = writeFloatExr(argv[2], out, {"Z"});
  }
  if (!s) {
    std::fprintf(stderr, "depth_convention_file: %s\n", s.message.c_str());
    return 1;
  }
  if (camera.kind == ProjectionKind::Orthographic)
    std::printf("--ortho %.17g --near %.17g --far %.17g\n", 2.0 / camera.projection[5], model.nearDistance,
                model.farDistance);
  else
    std::printf("--fovy %.17g --near %.17g%s\n", 2.0 * std::atan(1.0 / camera.projection[5]) * 180.0 / std::numbers::pi,
                model.nearDistance,
                std::isfinite(model.farDistance) ? (" --far " + std::to_string(model.farDistance)).c_str() : "");
  return 0;
}
