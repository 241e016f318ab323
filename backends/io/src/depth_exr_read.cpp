// readDepthExr: a depth EXR with its camera, or any flat EXR's depth channel as other tools write
// it (any part, any compression, a cropped data window). See sao/io.h.
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

std::string boxText(const exr::Box& b) {
  return "(" + std::to_string(b.minX) + ", " + std::to_string(b.minY) + ")-(" + std::to_string(b.maxX) + ", " +
         std::to_string(b.maxY) + ")";
}

std::uint64_t boxWidth(const exr::Box& b) { return std::uint64_t(std::int64_t(b.maxX) - b.minX + 1); }
std::uint64_t boxHeight(const exr::Box& b) { return std::uint64_t(std::int64_t(b.maxY) - b.minY + 1); }

// Where the data window lies in the image. EXR's image is the display window, and a pixel outside
// the data window holds nothing: for depth, no surface, i.e. sky. So a crop (a data window inside
// a larger display window, as renderers write a region or an auto-cropped frame) is placed where
// it lies and surrounded by sky; reading it alone as the whole view would stretch the camera's
// field of view over the crop (the AO was off by up to 0.37). A data window of the display
// window's size but elsewhere (an offset origin some writers use) is read as the image, as
// before; one that reaches outside the display window otherwise (an overscan) is refused, since
// which part the camera sees is then unknown.
struct Placement {
  Extent image;
  std::uint32_t x = 0, y = 0;  // the data window's lowest image row and first column
  bool crop = false;
};

Status place(const std::string& path, const exr::Input& in, Placement& out) {
  const exr::Box data = in.dataWindow(), display = in.displayWindow();
  const bool sameSize = boxWidth(data) == boxWidth(display) && boxHeight(data) == boxHeight(display);
  if (data == display || sameSize) {
    out = {in.extent(), 0, 0, false};
    return Status::success();
  }
  const bool inside = data.minX >= display.minX && data.minY >= display.minY && data.maxX <= display.maxX &&
                      data.maxY <= display.maxY;
  const std::string windows = "data window " + boxText(data) + " and display window " + boxText(display);
  if (!inside)
    return fail(StatusCode::IoError, path,
                "its " + windows + " differ and the data reaches outside the display window (the image): crop the "
                "data window to the display window (an overscan border is a guard band: make the display window the "
                "data window and declare the band)");
  const std::uint64_t w = boxWidth(display), h = boxHeight(display);
  if (display.maxX < display.minX || display.maxY < display.minY || w > kMaxImageSide || h > kMaxImageSide ||
      w * h > kMaxExrPixels || w * h - std::uint64_t(in.extent().width) * in.extent().height > kMaxCropFillPixels)
    return fail(StatusCode::IoError, path,
                "its " + windows + ": the crop leaves " + std::to_string(w) + "x" + std::to_string(h) +
                    " to fill with sky; the most read is " + std::to_string(kMaxImageSide) + " a side and " +
                    std::to_string(kMaxCropFillPixels) + " texels around the data window");
  // EXR's y grows downwards, image rows upwards (sao/io.h): the data's bottom scanline data.maxY
  // is image row display.maxY - data.maxY.
  out = {Extent{std::uint32_t(w), std::uint32_t(h)}, std::uint32_t(data.minX - display.minX),
         std::uint32_t(display.maxY - data.maxY), true};
  return Status::success();
}

bool isLossy(int compression) {
  return compression == EXR_COMPRESSION_B44 || compression == EXR_COMPRESSION_B44A ||
         compression == EXR_COMPRESSION_DWAA || compression == EXR_COMPRESSION_DWAB ||
         compression == EXR_COMPRESSION_PXR24;
}

Status readDepthImpl(const std::string& path, DepthImage& depth, Camera& camera, DepthFileInfo& info,
                     const DepthReadOptions& options) {
  exr::Input in;
  if (Status s = in.open(path); !s) return s;
  DepthChannel found;
  if (Status s = findDepthChannel(path, in.parts(), found); !s) return s;
  if (found.part != in.part())
    if (Status s = in.selectPart(found.part); !s) return s;
  const std::vector<exr::ChannelInfo>& channels = in.channels();
  const auto channel =
      std::find_if(channels.begin(), channels.end(), [&](const exr::ChannelInfo& c) { return c.name == found.name; });
  if (Status s = checkChannel(path, *channel); !s) return s;

  DepthFileInfo learnt;
  learnt.part = std::uint32_t(found.part);
  learnt.parts = std::uint32_t(in.parts().size());
  learnt.channel = found.name;
  learnt.storedAsHalf = channel->pixelType == EXR_PIXEL_HALF;
  learnt.compression = in.compressionName();
  learnt.lossy = isLossy(in.compression());

  Camera cam;
  DepthFormat format = DepthFormat::D32F;
  const bool sao = in.hasAttribute("sao.version");
  Placement placement;
  if (Status s = place(path, in, placement); !s) return s;
  if (sao) {
    if (Status s = readDepthCamera(in, path, cam, format); !s) return s;
    if (!extentMatches(placement.image, cam.width, cam.height, cam.guardBand))
      return fail(StatusCode::IoError, path, extentMismatch(placement.image, cam.width, cam.height, cam.guardBand));
  } else {
    for (const char* name : kCameraAttributes)
      if (in.hasAttribute(name)) learnt.saoAttributes.emplace_back(name);
  }

  std::vector<float> values;
  if (Status s = in.readChannels({channel->name}, values); !s) return s;

  const std::uint32_t max = integerMax(format);
  const bool hardware = format != DepthFormat::LinearZ;
  std::uint32_t sky = 0;  // the texel around a crop: the clear value
  if (!sao) sky = std::bit_cast<std::uint32_t>(options.skyWithoutCamera);
  else if (format == DepthFormat::LinearZ) sky = std::bit_cast<std::uint32_t>(0.0f);
  else if (max) sky = cam.reversedZ ? 0 : max;
  else sky = std::bit_cast<std::uint32_t>(cam.reversedZ ? 0.0f : 1.0f);

  DepthImage out;
  out.extent = placement.image;
  out.format = format;
  out.texels.assign(std::size_t(out.extent.width) * out.extent.height, sky);
  learnt.cropFillTexels = out.texels.size() - values.size();
  const std::uint32_t dataWidth = in.extent().width;
  float worstExcursion = 0.0f;
  for (std::size_t i = 0; i < values.size(); ++i) {
    float v = values[i];
    const auto x = std::uint32_t(i % dataWidth), y = std::uint32_t(i / dataWidth);
    // Lossy compression moves a texel of 0 or 1 (a sky, a far plane) slightly out of range.
    if (hardware && learnt.lossy && std::isfinite(v) && (v < 0.0f || v > 1.0f) &&
        std::min(std::abs(v), std::abs(v - 1.0f)) <= kLossyDepthNoise) {
      const float excursion = v < 0.0f ? -v : v - 1.0f;
      if (learnt.lossyNoiseTexels == 0 || excursion > worstExcursion) {
        worstExcursion = excursion;
        learnt.lossyNoiseWorst = v;
      }
      ++learnt.lossyNoiseTexels;
      v = v < 0.0f ? 0.0f : 1.0f;
    }
    std::uint32_t texel = 0;
    if (max == 0) {
      texel = std::bit_cast<std::uint32_t>(v);
    } else {
      if (!(v >= 0.0f && v <= 1.0f))
        return fail(StatusCode::IoError, path,
                    "Z at " + describe(x, y) + " is " + std::to_string(v) + ", not a normalised " + formatName(format) +
                        " depth in [0, 1]");
      texel = integerTexel(format, v);
    }
    out.texels[std::size_t(placement.y + y) * out.extent.width + placement.x + x] = texel;
  }

  depth = std::move(out);
  if (sao) camera = cam;
  learnt.hasCamera = sao;
  info = std::move(learnt);
  return Status::success();
}

}  // namespace

Status readDepthExr(const std::string& path, DepthImage& depth, Camera& camera, DepthFileInfo& info,
                    const DepthReadOptions& options) {
  return guarded(path, "read the depth EXR", [&] { return readDepthImpl(path, depth, camera, info, options); });
}

Status readDepthExr(const std::string& path, DepthImage& depth, Camera& camera, bool& hasCamera) {
  DepthFileInfo info;
  const Status s = readDepthExr(path, depth, camera, info);
  if (s) hasCamera = info.hasCamera;
  return s;
}

}  // namespace sao
