// readDepthExr: a depth EXR with its camera, or any flat EXR's depth channel. See sao/io.h.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "depth_exr_camera.h"
#include "depth_exr_format.h"
#include "exr_channels.h"
#include "exr_reader.h"
#include "io_checks.h"
#include "sao/io.h"

namespace sao {
namespace {

using namespace io::detail;

// The integer texel whose decoded float is exactly `v` (the value writeDepthExr stored), or the
// nearest one for a value that is not exactly such a float.
std::uint32_t integerTexel(DepthFormat format, float v) {
  const std::uint32_t max = integerMax(format);
  const auto nearest = static_cast<std::int64_t>(std::llround(double(v) * double(max)));
  for (std::int64_t t : {nearest, nearest - 1, nearest + 1})
    if (t >= 0 && t <= std::int64_t(max) && static_cast<float>(decodeDepth(format, std::uint32_t(t))) == v)
      return std::uint32_t(t);
  return std::uint32_t(std::clamp<std::int64_t>(nearest, 0, max));
}

Status readDepthImpl(const std::string& path, DepthImage& depth, Camera& camera, bool& hasCamera) {
  exr::Input in;
  if (Status s = in.open(path); !s) return s;
  const std::vector<exr::ChannelInfo>& channels = in.channels();
  auto named = [&](const std::string& n) {
    return std::find_if(channels.begin(), channels.end(), [&](const exr::ChannelInfo& c) { return c.name == n; });
  };
  auto channel = named(kDepthChannel);
  if (channel == channels.end()) {
    if (channels.size() != 1)
      return fail(StatusCode::IoError, path,
                  "has " + std::to_string(channels.size()) + " channels (" + channelList(channels) +
                      ") and none is named Z; a depth file needs a Z channel or exactly one channel");
    channel = channels.begin();
  }
  if (Status s = checkChannel(path, *channel); !s) return s;

  Camera cam;
  DepthFormat format = DepthFormat::D32F;
  const bool sao = in.hasAttribute("sao.version");
  if (sao) {
    if (Status s = readDepthCamera(in, path, cam, format); !s) return s;
    if (!extentMatches(in.extent(), cam.width, cam.height, cam.guardBand))
      return fail(StatusCode::IoError, path, extentMismatch(in.extent(), cam.width, cam.height, cam.guardBand));
  }

  std::vector<float> values;
  if (Status s = in.readChannels({channel->name}, values); !s) return s;

  DepthImage out;
  out.extent = in.extent();
  out.format = format;
  out.texels.resize(values.size());
  const std::uint32_t max = integerMax(format);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const float v = values[i];
    if (max == 0) {
      out.texels[i] = std::bit_cast<std::uint32_t>(v);
      continue;
    }
    if (!(v >= 0.0f && v <= 1.0f))
      return fail(StatusCode::IoError, path,
                  "Z at " + describe(std::uint32_t(i % out.extent.width), std::uint32_t(i / out.extent.width)) + " is " +
                      std::to_string(v) + ", not a normalised " + formatName(format) + " depth in [0, 1]");
    out.texels[i] = integerTexel(format, v);
  }

  depth = std::move(out);
  if (sao) camera = cam;
  hasCamera = sao;
  return Status::success();
}

}  // namespace

Status readDepthExr(const std::string& path, DepthImage& depth, Camera& camera, bool& hasCamera) {
  return guarded(path, "read the depth EXR", [&] { return readDepthImpl(path, depth, camera, hasCamera); });
}

}  // namespace sao
