// OpenEXR files: depth with its camera, float intermediates. See sao/io.h for the file layout.
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
#include <cstring>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "exr_reader.h"
#include "sao/io.h"

namespace sao {
namespace {

namespace fs = std::filesystem;

constexpr const char* kDepthChannel = "Z";

Status fail(StatusCode code, const std::string& path, const std::string& problem) {
  return Status::error(code, path + ": " + problem);
}

std::string describe(std::uint32_t x, std::uint32_t y) {
  return "(" + std::to_string(x) + ", " + std::to_string(y) + ")";
}

// ---- names of the enums in the file -------------------------------------------------------------

const char* formatName(DepthFormat f) {
  switch (f) {
    case DepthFormat::D16: return "D16";
    case DepthFormat::D24: return "D24";
    case DepthFormat::D32F: return "D32F";
    case DepthFormat::LinearZ: return "LinearZ";
  }
  return nullptr;
}

std::optional<DepthFormat> parseFormat(const std::string& s) {
  for (DepthFormat f : {DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F, DepthFormat::LinearZ})
    if (s == formatName(f)) return f;
  return std::nullopt;
}

const char* kindName(ProjectionKind k) {
  switch (k) {
    case ProjectionKind::Perspective: return "perspective";
    case ProjectionKind::Orthographic: return "orthographic";
  }
  return nullptr;
}

const char* clipName(ClipDepth c) {
  switch (c) {
    case ClipDepth::NegativeOneToOne: return "negativeOneToOne";
    case ClipDepth::ZeroToOne: return "zeroToOne";
  }
  return nullptr;
}

// Largest value of an integer depth format (0 for float formats).
std::uint32_t integerMax(DepthFormat f) {
  switch (f) {
    case DepthFormat::D16: return 0xffffu;
    case DepthFormat::D24: return 0xffffffu;
    default: return 0;
  }
}

// ---- paths ----------------------------------------------------------------------------------------

Status checkWritable(const std::string& path) {
  if (path.empty()) return Status::error(StatusCode::IoError, "empty path");
  std::error_code ec;
  if (fs::is_directory(path, ec)) return fail(StatusCode::IoError, path, "is a directory, cannot write a file there");
  return Status::success();
}

// ---- image checks -------------------------------------------------------------------------------

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

// The depth image holds the viewport plus the guard band on every side.
bool extentMatches(Extent e, std::uint64_t width, std::uint64_t height, std::uint64_t guard) {
  return std::uint64_t(e.width) == width + 2 * guard && std::uint64_t(e.height) == height + 2 * guard;
}

std::string extentMismatch(Extent e, std::uint64_t width, std::uint64_t height, std::uint64_t guard) {
  return "depth image is " + std::to_string(e.width) + "x" + std::to_string(e.height) + ", but the camera's " +
         std::to_string(width) + "x" + std::to_string(height) + " viewport with a guard band of " +
         std::to_string(guard) + " needs " + std::to_string(width + 2 * guard) + "x" + std::to_string(height + 2 * guard);
}

// ---- reading ------------------------------------------------------------------------------------

Status checkChannel(const std::string& path, const exr::ChannelInfo& c) {
  if (c.pixelType != EXR_PIXEL_FLOAT && c.pixelType != EXR_PIXEL_HALF)
    return fail(StatusCode::UnsupportedFormat, path,
                "channel \"" + c.name + "\" is " + (c.pixelType == EXR_PIXEL_UINT ? "UINT" : "of an unknown pixel type") +
                    "; only FLOAT and HALF channels are read");
  if (c.xSampling != 1 || c.ySampling != 1)
    return fail(StatusCode::UnsupportedFormat, path, "channel \"" + c.name + "\" is subsampled; only full-resolution channels are read");
  return Status::success();
}

std::string channelList(const std::vector<exr::ChannelInfo>& channels) {
  std::string s;
  for (const exr::ChannelInfo& c : channels) s += std::string(s.empty() ? "" : ", ") + c.name;
  return s.empty() ? "none" : s;
}

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

// The camera and format of a file that has sao.version.
Status readCamera(const exr::Input& in, const std::string& path, Camera& cam, DepthFormat& format) {
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
    if (Status s = readCamera(in, path, cam, format); !s) return s;
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

Status readFloatImpl(const std::string& path, FloatImage& image, std::vector<std::string>& channelNames) {
  exr::Input in;
  if (Status s = in.open(path); !s) return s;
  std::vector<std::string> names;
  for (const exr::ChannelInfo& c : in.channels()) {
    if (Status s = checkChannel(path, c); !s) return s;
    names.push_back(c.name);
  }
  if (names.empty()) return fail(StatusCode::IoError, path, "has no channels");
  std::vector<std::string> order;
  bool found = false;
  // An order of another type, or one that does not name exactly the file's channels, is ignored.
  if (in.stringVectorAttribute("sao.channels", found, order) && found) {
    std::vector<std::string> sortedOrder = order, sortedNames = names;
    std::sort(sortedOrder.begin(), sortedOrder.end());
    std::sort(sortedNames.begin(), sortedNames.end());
    if (sortedOrder == sortedNames) names = order;
  }

  FloatImage out;
  out.extent = in.extent();
  out.channels = std::uint32_t(names.size());
  if (Status s = in.readChannels(names, out.data); !s) return s;
  image = std::move(out);
  channelNames = std::move(names);
  return Status::success();
}

// ---- writing ------------------------------------------------------------------------------------

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

// Runs `body`, turning every exception into an IoError that names the path.
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

}  // namespace

Status writeDepthExr(const std::string& path, const DepthImage& depth, const Camera& camera) {
  return guarded(path, "write the depth EXR", [&] { return writeDepthImpl(path, depth, camera); });
}

Status readDepthExr(const std::string& path, DepthImage& depth, Camera& camera, bool& hasCamera) {
  return guarded(path, "read the depth EXR", [&] { return readDepthImpl(path, depth, camera, hasCamera); });
}

Status writeFloatExr(const std::string& path, const FloatImage& image, const std::vector<std::string>& channelNames) {
  return guarded(path, "write the EXR", [&] { return writeFloatImpl(path, image, channelNames); });
}

Status readFloatExr(const std::string& path, FloatImage& image, std::vector<std::string>& channelNames) {
  return guarded(path, "read the EXR", [&] { return readFloatImpl(path, image, channelNames); });
}

}  // namespace sao
