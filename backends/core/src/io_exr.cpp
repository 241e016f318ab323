// OpenEXR files: depth with its camera, float intermediates. See sao/io.h for the file layout.
#include <ImathBox.h>
#include <ImathMatrix.h>
#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfMatrixAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfStdIO.h>
#include <ImfStringVectorAttribute.h>
#include <ImfTestFile.h>
#include <openexr.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstring>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

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

// ---- paths --------------------------------------------------------------------------------------

Status checkReadable(const std::string& path) {
  if (path.empty()) return Status::error(StatusCode::IoError, "empty path");
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (st.type() == fs::file_type::not_found) return fail(StatusCode::IoError, path, "no such file");
  if (ec) return fail(StatusCode::IoError, path, "cannot access: " + ec.message());
  if (st.type() == fs::file_type::directory) return fail(StatusCode::IoError, path, "is a directory, not a file");
  // A FIFO would block the open until someone writes, a device may never end: regular files only.
  if (st.type() != fs::file_type::regular)
    return fail(StatusCode::IoError, path, "is not a regular file (a FIFO, socket or device)");
  errno = 0;
  if (!std::ifstream(path, std::ios::binary).is_open())
    return fail(StatusCode::IoError, path, std::string("cannot open: ") + (errno ? std::strerror(errno) : "unknown error"));
  return Status::success();
}

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

// An open EXR file with a checked data window.
struct OpenedExr {
  std::unique_ptr<Imf::InputFile> file;
  Imath::Box2i dataWindow;
  Extent extent;
};

// OpenEXR's C++ reader (3.1) sizes its allocations from the header before it checks them against
// the file: an attribute's value at its declared size, the chunk offset table at the chunk count,
// the decompression buffers at the width (or tile size) times the lines of a chunk times the
// channels. A few hundred bytes could make it allocate gigabytes (found by fuzz_exr_depth). So the
// header is parsed first by OpenEXR's own C core library (OpenEXRCore), which checks every
// attribute's size against its type and the file. Any problem it reports rejects the file (it
// reports some and reads on with its own guess, which the C++ reader would not share), and the
// sizes it reads must fit: the data window and tiles in kMaxImageSide, the chunk offset table
// (8 bytes a chunk) in the file, one decoded chunk in 512 MiB.
thread_local std::string tCoreError;

// A data window (as either reader sees it) must be non-empty and at most kMaxImageSide a side.
Status checkDataWindow(const std::string& path, std::int64_t width, std::int64_t height) {
  if (width <= 0 || height <= 0) return fail(StatusCode::IoError, path, "empty data window");
  if (width > kMaxImageSide || height > kMaxImageSide)
    return fail(StatusCode::IoError, path,
                "data window is " + std::to_string(width) + "x" + std::to_string(height) +
                    "; the largest side read is " + std::to_string(kMaxImageSide));
  return Status::success();
}

Status precheckHeader(const std::string& path) {
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = [](exr_const_context_t, exr_result_t, const char* message) {
    if (tCoreError.empty()) tCoreError = message && *message ? message : "unknown error";
  };
  tCoreError.clear();
  exr_context_t ctxt = nullptr;
  const exr_result_t started = exr_start_read(&ctxt, path.c_str(), &init);
  struct Finish {
    exr_context_t& c;
    ~Finish() {
      if (c) exr_finish(&c);
    }
  } finish{ctxt};
  if (started != EXR_ERR_SUCCESS || !tCoreError.empty())
    return fail(StatusCode::IoError, path,
                "corrupt header: " + (tCoreError.empty() ? std::string(exr_get_error_code_as_string(started)) : tCoreError));
  exr_storage_t storage = EXR_STORAGE_LAST_TYPE;
  exr_attr_box2i_t window{};
  int32_t chunks = 0;
  const exr_attr_chlist_t* channels = nullptr;
  if (exr_get_storage(ctxt, 0, &storage) != EXR_ERR_SUCCESS || exr_get_data_window(ctxt, 0, &window) != EXR_ERR_SUCCESS ||
      exr_get_chunk_count(ctxt, 0, &chunks) != EXR_ERR_SUCCESS || exr_get_channels(ctxt, 0, &channels) != EXR_ERR_SUCCESS ||
      !channels)
    return fail(StatusCode::IoError, path, "corrupt header: " + tCoreError);
  if (storage == EXR_STORAGE_DEEP_SCANLINE || storage == EXR_STORAGE_DEEP_TILED)
    return fail(StatusCode::UnsupportedFormat, path, "holds deep data; only flat images are read");
  const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
  const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
  if (Status s = checkDataWindow(path, width, height); !s) return s;
  std::uint64_t chunkCols = std::uint64_t(width), chunkLines = 1;
  if (storage == EXR_STORAGE_TILED) {
    uint32_t tileX = 0, tileY = 0;
    exr_tile_level_mode_t levels{};
    exr_tile_round_mode_t round{};
    if (exr_get_tile_descriptor(ctxt, 0, &tileX, &tileY, &levels, &round) != EXR_ERR_SUCCESS)
      return fail(StatusCode::IoError, path, "corrupt header: " + tCoreError);
    if (tileX == 0 || tileY == 0 || tileX > kMaxImageSide || tileY > kMaxImageSide)
      return fail(StatusCode::IoError, path,
                  "tiles are " + std::to_string(tileX) + "x" + std::to_string(tileY) + "; the largest side read is " +
                      std::to_string(kMaxImageSide));
    chunkCols = tileX;
    chunkLines = tileY;
  } else {
    int32_t lines = 0;
    if (exr_get_scanlines_per_chunk(ctxt, 0, &lines) != EXR_ERR_SUCCESS || lines <= 0)
      return fail(StatusCode::IoError, path, "corrupt header: " + tCoreError);
    chunkLines = std::uint64_t(lines);
  }
  std::error_code ec;
  const std::uintmax_t fileSize = fs::file_size(path, ec);
  if (!ec && std::uint64_t(std::max(chunks, 0)) * 8 > fileSize)
    return fail(StatusCode::IoError, path,
                "is truncated or corrupt: its " + std::to_string(width) + "x" + std::to_string(height) +
                    " data window needs " + std::to_string(chunks) + " chunks, whose offset table alone (" +
                    std::to_string(std::uint64_t(chunks) * 8) + " bytes) exceeds the file's " +
                    std::to_string(fileSize) + " bytes");
  std::uint64_t pixelBytes = 0;  // all channels of one pixel
  for (int c = 0; c < channels->num_channels; ++c) pixelBytes += channels->entries[c].pixel_type == EXR_PIXEL_HALF ? 2 : 4;
  const std::uint64_t chunkBytes = chunkCols * chunkLines * pixelBytes;
  if (chunkBytes > (std::uint64_t(512) << 20))
    return fail(StatusCode::IoError, path,
                "one chunk would decode to " + std::to_string(chunkBytes) + " bytes (" + std::to_string(pixelBytes) +
                    " bytes a pixel); the largest read is 512 MiB");
  return Status::success();
}

// OpenEXRCore and the C++ reader can read a malformed header differently (an attribute whose
// declared size is not its type's: Core skips the declared size, the C++ reader reads the type's
// and goes on from there), so the C++ reader's own view is checked as well before InputFile sizes
// its buffers from it (found by fuzz_exr_depth: a 16,711,426-wide data window that Core never saw
// made InputFile allocate 2 GiB). Throws like OpenEXR does on a header it cannot parse.
Status checkCppHeader(const std::string& path) {
  Imf::StdIFStream in(path.c_str());
  char head[8];
  in.read(head, 8);
  int version = int(std::uint32_t(std::uint8_t(head[4])) | std::uint32_t(std::uint8_t(head[5])) << 8 |
                          std::uint32_t(std::uint8_t(head[6])) << 16 | std::uint32_t(std::uint8_t(head[7])) << 24);
  Imf::Header h;
  h.readFrom(in, version);
  const Imath::Box2i window = h.dataWindow();
  const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
  const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
  if (Status s = checkDataWindow(path, width, height); !s) return s;
  if (h.hasTileDescription()) {
    const Imf::TileDescription& t = h.tileDescription();
    if (t.xSize == 0 || t.ySize == 0 || t.xSize > kMaxImageSide || t.ySize > kMaxImageSide)
      return fail(StatusCode::IoError, path,
                  "tiles are " + std::to_string(t.xSize) + "x" + std::to_string(t.ySize) +
                      "; the largest side read is " + std::to_string(kMaxImageSide));
  }
  if (int(h.compression()) < 0 || int(h.compression()) >= int(Imf::NUM_COMPRESSION_METHODS))
    return fail(StatusCode::IoError, path, "corrupt header: unknown compression " + std::to_string(int(h.compression())));
  return Status::success();
}

Status openExr(const std::string& path, OpenedExr& out) {
  if (Status s = checkReadable(path); !s) return s;
  if (!Imf::isOpenExrFile(path.c_str())) return fail(StatusCode::IoError, path, "not an OpenEXR file (bad magic number)");
  if (Status s = precheckHeader(path); !s) return s;
  if (Status s = checkCppHeader(path); !s) return s;
  out.file = std::make_unique<Imf::InputFile>(path.c_str());
  const Imf::Header& h = out.file->header();
  out.dataWindow = h.dataWindow();
  const std::int64_t w = std::int64_t(out.dataWindow.max.x) - out.dataWindow.min.x + 1;
  const std::int64_t ht = std::int64_t(out.dataWindow.max.y) - out.dataWindow.min.y + 1;
  if (w <= 0 || ht <= 0) return fail(StatusCode::IoError, path, "empty data window");
  if (w > kMaxImageSide || ht > kMaxImageSide)
    return fail(StatusCode::IoError, path,
                "data window is " + std::to_string(w) + "x" + std::to_string(ht) + "; the largest side read is " +
                    std::to_string(kMaxImageSide));
  out.extent = {std::uint32_t(w), std::uint32_t(ht)};
  return Status::success();
}

std::string channelList(const Imf::ChannelList& channels) {
  std::string s;
  for (auto it = channels.begin(); it != channels.end(); ++it) s += std::string(s.empty() ? "" : ", ") + it.name();
  return s.empty() ? "none" : s;
}

Status checkChannel(const std::string& path, const std::string& name, const Imf::Channel& c) {
  if (c.type != Imf::FLOAT && c.type != Imf::HALF)
    return fail(StatusCode::UnsupportedFormat, path,
                "channel \"" + name + "\" is " + (c.type == Imf::UINT ? "UINT" : "of an unknown pixel type") +
                    "; only FLOAT and HALF channels are read");
  if (c.xSampling != 1 || c.ySampling != 1)
    return fail(StatusCode::UnsupportedFormat, path, "channel \"" + name + "\" is subsampled; only full-resolution channels are read");
  return Status::success();
}

// Reads the named channels as float into `data` (interleaved, image row 0 = the file's bottom
// scanline). Channels were checked by the caller.
Status readChannels(const std::string& path, OpenedExr& exr, const std::vector<std::string>& names, std::vector<float>& data) {
  // Before the allocation: a truncated file that declares a large data window fails cheaply.
  if (!exr.file->isComplete()) return fail(StatusCode::IoError, path, "file is incomplete (truncated): some scanlines are missing");
  const std::size_t w = exr.extent.width, h = exr.extent.height, n = names.size();
  // Read in bands of rows, the whole image allocated only once the first band decoded: a corrupt
  // file that declares a large image (up to 16384 x 16384) fails at its first band, not after the
  // image was allocated and cleared (found by fuzz_exr_depth).
  constexpr std::size_t kBandRows = 256;
  std::vector<float> fileOrder;  // top scanline first, as in the file
  std::vector<float> band;
  for (std::size_t y0 = 0; y0 < h; y0 += kBandRows) {
    const std::size_t rows = std::min(kBandRows, h - y0);
    band.assign(w * rows * n, 0.0f);
    const int top = exr.dataWindow.min.y + int(y0), bottom = top + int(rows) - 1;
    const Imath::Box2i window(Imath::V2i(exr.dataWindow.min.x, top), Imath::V2i(exr.dataWindow.max.x, bottom));
    Imf::FrameBuffer fb;
    for (std::size_t c = 0; c < n; ++c)
      fb.insert(names[c], Imf::Slice::Make(Imf::FLOAT, band.data() + c, window, sizeof(float) * n, sizeof(float) * n * w));
    exr.file->setFrameBuffer(fb);
    exr.file->readPixels(top, bottom);
    if (y0 == 0) fileOrder.reserve(w * h * n);  // the first band decoded: the file is plausible
    fileOrder.insert(fileOrder.end(), band.begin(), band.end());
  }
  data.resize(fileOrder.size());
  const std::size_t row = w * n;
  for (std::size_t y = 0; y < h; ++y)
    std::copy_n(fileOrder.data() + (h - 1 - y) * row, row, data.data() + y * row);
  return Status::success();
}

template <class A>
Status attribute(const Imf::Header& h, const std::string& path, const char* name, const char* expected, const A*& out) {
  const auto it = h.find(name);
  if (it == h.end()) return fail(StatusCode::IoError, path, std::string("has sao.version but no ") + name + " attribute");
  out = dynamic_cast<const A*>(&it.attribute());
  if (!out)
    return fail(StatusCode::IoError, path,
                std::string("attribute ") + name + " is of type " + it.attribute().typeName() + ", expected " + expected);
  return Status::success();
}

Status intAttribute(const Imf::Header& h, const std::string& path, const char* name, int lo, int hi, int& out) {
  const Imf::IntAttribute* a = nullptr;
  if (Status s = attribute(h, path, name, "int", a); !s) return s;
  out = a->value();
  if (out < lo || out > hi)
    return fail(StatusCode::IoError, path,
                std::string("attribute ") + name + " is " + std::to_string(out) + "; expected " + std::to_string(lo) +
                    (hi == 1 ? " or " : " to ") + std::to_string(hi));
  return Status::success();
}

Status stringAttribute(const Imf::Header& h, const std::string& path, const char* name, std::string& out) {
  const Imf::StringAttribute* a = nullptr;
  if (Status s = attribute(h, path, name, "string", a); !s) return s;
  out = a->value();
  return Status::success();
}

Status unknownValue(const std::string& path, const char* name, const std::string& value, const char* known) {
  return fail(StatusCode::UnsupportedFormat, path,
              std::string("attribute ") + name + " is \"" + value + "\"; known values: " + known);
}

// The camera and format of a file that has sao.version.
Status readCamera(const Imf::Header& h, const std::string& path, Camera& cam, DepthFormat& format) {
  int version = 0;
  if (Status s = intAttribute(h, path, "sao.version", INT_MIN, INT_MAX, version); !s) return s;
  if (version != kDepthExrVersion)
    return fail(StatusCode::UnsupportedFormat, path,
                "sao.version is " + std::to_string(version) + "; this library reads version " +
                    std::to_string(kDepthExrVersion));

  const Imf::M44dAttribute* proj = nullptr;
  if (Status s = attribute(h, path, "sao.projection", "m44d", proj); !s) return s;
  for (int i = 0; i < 16; ++i) {
    const double v = proj->value()[i / 4][i % 4];
    if (!std::isfinite(v))
      return fail(StatusCode::IoError, path,
                  "sao.projection element " + std::to_string(i) + " (row " + std::to_string(i % 4) + ", column " +
                      std::to_string(i / 4) + ") is not finite");
    cam.projection[std::size_t(i)] = v;
  }

  std::string text;
  if (Status s = stringAttribute(h, path, "sao.kind", text); !s) return s;
  if (text == kindName(ProjectionKind::Perspective)) cam.kind = ProjectionKind::Perspective;
  else if (text == kindName(ProjectionKind::Orthographic)) cam.kind = ProjectionKind::Orthographic;
  else return unknownValue(path, "sao.kind", text, "perspective, orthographic");

  if (Status s = stringAttribute(h, path, "sao.clipDepth", text); !s) return s;
  if (text == clipName(ClipDepth::NegativeOneToOne)) cam.clipDepth = ClipDepth::NegativeOneToOne;
  else if (text == clipName(ClipDepth::ZeroToOne)) cam.clipDepth = ClipDepth::ZeroToOne;
  else return unknownValue(path, "sao.clipDepth", text, "negativeOneToOne, zeroToOne");

  int flag = 0;
  if (Status s = intAttribute(h, path, "sao.reversedZ", 0, 1, flag); !s) return s;
  cam.reversedZ = flag != 0;
  if (Status s = intAttribute(h, path, "sao.infiniteFar", 0, 1, flag); !s) return s;
  cam.infiniteFar = flag != 0;
  if (Status s = intAttribute(h, path, "sao.flipY", 0, 1, flag); !s) return s;
  cam.flipY = flag != 0;

  const Imf::DoubleAttribute* meters = nullptr;
  if (Status s = attribute(h, path, "sao.metersToViewUnits", "double", meters); !s) return s;
  if (!std::isfinite(meters->value())) return fail(StatusCode::IoError, path, "sao.metersToViewUnits is not finite");
  cam.metersToViewUnits = meters->value();

  int width = 0, height = 0, guard = 0;
  if (Status s = intAttribute(h, path, "sao.width", 0, INT_MAX, width); !s) return s;
  if (Status s = intAttribute(h, path, "sao.height", 0, INT_MAX, height); !s) return s;
  if (Status s = intAttribute(h, path, "sao.guardBand", 0, INT_MAX, guard); !s) return s;
  cam.width = std::uint32_t(width);
  cam.height = std::uint32_t(height);
  cam.guardBand = std::uint32_t(guard);

  if (Status s = stringAttribute(h, path, "sao.depthFormat", text); !s) return s;
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
  OpenedExr exr;
  if (Status s = openExr(path, exr); !s) return s;
  const Imf::Header& h = exr.file->header();

  const Imf::ChannelList& channels = h.channels();
  std::string name;
  if (channels.findChannel(kDepthChannel)) {
    name = kDepthChannel;
  } else {
    std::size_t count = 0;
    for (auto it = channels.begin(); it != channels.end(); ++it, ++count) name = it.name();
    if (count != 1)
      return fail(StatusCode::IoError, path,
                  "has " + std::to_string(count) + " channels (" + channelList(channels) +
                      ") and none is named Z; a depth file needs a Z channel or exactly one channel");
  }
  if (Status s = checkChannel(path, name, *channels.findChannel(name)); !s) return s;

  Camera cam;
  DepthFormat format = DepthFormat::D32F;
  const bool sao = h.find("sao.version") != h.end();
  if (sao) {
    if (Status s = readCamera(h, path, cam, format); !s) return s;
    if (!extentMatches(exr.extent, cam.width, cam.height, cam.guardBand))
      return fail(StatusCode::IoError, path, extentMismatch(exr.extent, cam.width, cam.height, cam.guardBand));
  }

  std::vector<float> values;
  if (Status s = readChannels(path, exr, {name}, values); !s) return s;

  DepthImage out;
  out.extent = exr.extent;
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
  OpenedExr exr;
  if (Status s = openExr(path, exr); !s) return s;
  const Imf::Header& h = exr.file->header();
  const Imf::ChannelList& channels = h.channels();

  std::vector<std::string> names;
  for (auto it = channels.begin(); it != channels.end(); ++it) {
    if (Status s = checkChannel(path, it.name(), it.channel()); !s) return s;
    names.push_back(it.name());
  }
  if (names.empty()) return fail(StatusCode::IoError, path, "has no channels");
  if (const auto* order = h.findTypedAttribute<Imf::StringVectorAttribute>("sao.channels")) {
    std::vector<std::string> sortedOrder = order->value(), sortedNames = names;
    std::sort(sortedOrder.begin(), sortedOrder.end());
    std::sort(sortedNames.begin(), sortedNames.end());
    if (sortedOrder == sortedNames) names = order->value();
  }

  FloatImage out;
  out.extent = exr.extent;
  out.channels = std::uint32_t(names.size());
  if (Status s = readChannels(path, exr, names, out.data); !s) return s;
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
