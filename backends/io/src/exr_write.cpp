// writeDepthExr and writeFloatExr, through OpenEXR's C++ library (it only ever writes here; input
// goes through exr_reader.h). See sao/io.h for the file layout and the row order.
#include <ImathMatrix.h>
#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfMatrixAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfStringVectorAttribute.h>

#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "depth_exr_format.h"
#include "io_checks.h"
#include "sao/io.h"

namespace sao {
namespace {

using namespace io::detail;

// Image rows flipped into file order (top scanline first).
std::vector<float> toFileOrder(const std::vector<float>& rows, std::size_t rowLength, std::size_t height) {
  std::vector<float> out(rows.size());
  for (std::size_t y = 0; y < height; ++y)
    std::copy_n(rows.data() + (height - 1 - y) * rowLength, rowLength, out.data() + y * rowLength);
  return out;
}

void writeFile(const std::string& path, Imf::Header& header, const std::vector<std::string>& names,
               const std::vector<float>& fileOrder, Extent e) {
  const std::size_t n = names.size();
  header.compression() = Imf::ZIP_COMPRESSION;  // lossless
  header.lineOrder() = Imf::INCREASING_Y;
  for (const std::string& name : names) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
  Imf::OutputFile file(path.c_str(), header);
  Imf::FrameBuffer fb;
  for (std::size_t c = 0; c < n; ++c)
    fb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(fileOrder.data() + c)),
                                   sizeof(float) * n, sizeof(float) * n * e.width));
  file.setFrameBuffer(fb);
  file.writePixels(int(e.height));
}

Status writeDepthImpl(const std::string& path, const DepthImage& depth, const Camera& camera) {
  if (Status s = checkWritable(path); !s) return s;
  if (Status s = checkExtent(path, depth.extent); !s) return s;
  const Extent e = depth.extent;
  const std::size_t count = std::size_t(e.width) * e.height;
  if (depth.texels.size() != count)
    return fail(StatusCode::InvalidInput, path,
                "depth image has " + std::to_string(depth.texels.size()) + " texels, its extent needs " + std::to_string(count));
  if (!formatName(depth.format)) return fail(StatusCode::InvalidInput, path, "depth image has an unknown format");
  for (std::size_t i = 0; i < 16; ++i)
    if (!std::isfinite(camera.projection[i]))
      return fail(StatusCode::InvalidInput, path, "camera projection element " + std::to_string(i) + " is not finite");
  if (!std::isfinite(camera.metersToViewUnits))
    return fail(StatusCode::InvalidInput, path, "camera metersToViewUnits is not finite");
  if (!kindName(camera.kind) || !clipName(camera.clipDepth))
    return fail(StatusCode::InvalidInput, path, "camera has an unknown projection kind or clip-depth convention");
  if (camera.width > INT_MAX || camera.height > INT_MAX || camera.guardBand > INT_MAX)
    return fail(StatusCode::InvalidInput, path, "camera width, height or guard band does not fit an EXR int attribute");
  if (!extentMatches(e, camera.width, camera.height, camera.guardBand))
    return fail(StatusCode::InvalidInput, path, extentMismatch(e, camera.width, camera.height, camera.guardBand));

  std::vector<float> values(count);
  const std::uint32_t max = integerMax(depth.format);
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t t = depth.texels[i];
    if (max != 0 && t > max)
      return fail(StatusCode::InvalidInput, path,
                  "texel " + describe(std::uint32_t(i % e.width), std::uint32_t(i / e.width)) + " is " + std::to_string(t) +
                      ", above the largest " + formatName(depth.format) + " value " + std::to_string(max));
    values[i] = max != 0 ? static_cast<float>(decodeDepth(depth.format, t)) : std::bit_cast<float>(t);
  }

  Imf::Header header(int(e.width), int(e.height));
  Imath::M44d m;
  for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = camera.projection[std::size_t(i)];
  header.insert("sao.version", Imf::IntAttribute(kDepthExrVersion));
  header.insert("sao.projection", Imf::M44dAttribute(m));
  header.insert("sao.kind", Imf::StringAttribute(kindName(camera.kind)));
  header.insert("sao.clipDepth", Imf::StringAttribute(clipName(camera.clipDepth)));
  header.insert("sao.reversedZ", Imf::IntAttribute(camera.reversedZ ? 1 : 0));
  header.insert("sao.infiniteFar", Imf::IntAttribute(camera.infiniteFar ? 1 : 0));
  header.insert("sao.flipY", Imf::IntAttribute(camera.flipY ? 1 : 0));
  header.insert("sao.metersToViewUnits", Imf::DoubleAttribute(camera.metersToViewUnits));
  header.insert("sao.width", Imf::IntAttribute(int(camera.width)));
  header.insert("sao.height", Imf::IntAttribute(int(camera.height)));
  header.insert("sao.guardBand", Imf::IntAttribute(int(camera.guardBand)));
  header.insert("sao.depthFormat", Imf::StringAttribute(formatName(depth.format)));
  writeFile(path, header, {kDepthChannel}, toFileOrder(values, e.width, e.height), e);
  return Status::success();
}

Status writeFloatImpl(const std::string& path, const FloatImage& image, const std::vector<std::string>& names) {
  if (Status s = checkWritable(path); !s) return s;
  if (Status s = checkExtent(path, image.extent); !s) return s;
  const Extent e = image.extent;
  if (image.channels == 0) return fail(StatusCode::InvalidInput, path, "image has no channels");
  const std::size_t count = std::size_t(e.width) * e.height * image.channels;
  if (image.data.size() != count)
    return fail(StatusCode::InvalidInput, path,
                "image has " + std::to_string(image.data.size()) + " floats, its extent and channels need " +
                    std::to_string(count));
  if (names.size() != image.channels)
    return fail(StatusCode::InvalidInput, path,
                std::to_string(names.size()) + " channel names for an image with " + std::to_string(image.channels) +
                    " channels");
  std::set<std::string> seen;
  for (const std::string& n : names) {
    if (n.empty()) return fail(StatusCode::InvalidInput, path, "empty channel name");
    if (n.size() > 255) return fail(StatusCode::InvalidInput, path, "channel name longer than 255 bytes");
    if (!seen.insert(n).second) return fail(StatusCode::InvalidInput, path, "channel name \"" + n + "\" used twice");
  }
  Imf::Header header(int(e.width), int(e.height));
  header.insert("sao.channels", Imf::StringVectorAttribute(names));
  writeFile(path, header, names, toFileOrder(image.data, std::size_t(e.width) * image.channels, e.height), e);
  return Status::success();
}

}  // namespace

Status writeDepthExr(const std::string& path, const DepthImage& depth, const Camera& camera) {
  return guarded(path, "write the depth EXR", [&] { return writeDepthImpl(path, depth, camera); });
}

Status writeFloatExr(const std::string& path, const FloatImage& image, const std::vector<std::string>& channelNames) {
  return guarded(path, "write the EXR", [&] { return writeFloatImpl(path, image, channelNames); });
}

}  // namespace sao
