// OpenEXR input through OpenEXRCore only; see exr_reader.h for why.
#include "exr_reader.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>

#include "sao/io.h"
#include "sao/plan.h"

namespace sao::exr {
namespace {

namespace fs = std::filesystem;

// The core library reports errors through a callback and allocates through plain function
// pointers without user data, so both are routed through per-thread state of the read in progress.
struct CoreState {
  std::string firstError;
  std::uint64_t liveBytes = 0;
  bool overBudget = false;
};
thread_local CoreState tCore;

// Each block carries its size in front, so the free function can account for it.
constexpr std::size_t kHeader = 16;

void* budgetedAlloc(size_t bytes) {
  if (tCore.liveBytes + bytes > kCoreMemoryBudget) {
    tCore.overBudget = true;
    return nullptr;
  }
  auto* block = static_cast<unsigned char*>(::operator new(bytes + kHeader, std::nothrow));
  if (!block) return nullptr;
  std::memcpy(block, &bytes, sizeof bytes);
  tCore.liveBytes += bytes;
  return block + kHeader;
}

void budgetedFree(void* p) {
  if (!p) return;
  unsigned char* block = static_cast<unsigned char*>(p) - kHeader;
  size_t bytes = 0;
  std::memcpy(&bytes, block, sizeof bytes);
  tCore.liveBytes -= std::min<std::uint64_t>(bytes, tCore.liveBytes);
  ::operator delete(block);
}

void recordError(exr_const_context_t, exr_result_t, const char* message) {
  if (tCore.firstError.empty()) tCore.firstError = message && *message ? message : "unknown error";
}

// The core library's words for a failed call: its first reported message, or the code's name.
std::string coreProblem(exr_result_t code) {
  if (tCore.overBudget)
    return "it would need more than " + std::to_string(kCoreMemoryBudget >> 20) +
           " MiB of buffers (the header declares more than a file of this size can hold)";
  if (!tCore.firstError.empty()) return tCore.firstError;
  return exr_get_error_code_as_string(code);
}

const char* attributeTypeName(const exr_attribute_t& a) { return a.type_name ? a.type_name : "unknown"; }

Status checkRegularFile(const std::string& path) {
  auto fail = [&](const std::string& problem) { return Status::error(StatusCode::IoError, path + ": " + problem); };
  if (path.empty()) return Status::error(StatusCode::IoError, "empty path");
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (st.type() == fs::file_type::not_found) return fail("no such file");
  if (ec) return fail("cannot access: " + ec.message());
  if (st.type() == fs::file_type::directory) return fail("is a directory, not a file");
  // A FIFO would block the open until someone writes, a device may never end: regular files only.
  if (st.type() != fs::file_type::regular) return fail("is not a regular file (a FIFO, socket or device)");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in.is_open()) return fail(std::string("cannot open: ") + (errno ? std::strerror(errno) : "unknown error"));
  const unsigned char magic[4] = {0x76, 0x2f, 0x31, 0x01};
  unsigned char head[4] = {};
  in.read(reinterpret_cast<char*>(head), 4);
  if (in.gcount() != 4 || std::memcmp(head, magic, 4) != 0) return fail("not an OpenEXR file (bad magic number)");
  return Status::success();
}

}  // namespace

Input::Input() = default;

Input::~Input() {
  if (context_) {
    exr_finish(&context_);
    context_ = nullptr;
  }
}

Status Input::fail(const std::string& problem) const {
  return Status::error(StatusCode::IoError, path_ + ": " + problem);
}

Status Input::open(const std::string& path) {
  path_ = path;
  if (Status s = checkRegularFile(path); !s) return s;
  tCore.firstError.clear();
  tCore.overBudget = false;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = recordError;
  init.alloc_fn = budgetedAlloc;
  init.free_fn = budgetedFree;
  const exr_result_t started = exr_start_read(&context_, path.c_str(), &init);
  // The core library reports some problems and reads on with a guess of its own: any report fails.
  if (started != EXR_ERR_SUCCESS || !tCore.firstError.empty()) return fail("corrupt header: " + coreProblem(started));

  int parts = 0;
  exr_storage_t storage = EXR_STORAGE_LAST_TYPE;
  exr_attr_box2i_t window{};
  int32_t chunks = 0;
  const exr_attr_chlist_t* list = nullptr;
  if (exr_get_count(context_, &parts) != EXR_ERR_SUCCESS || parts < 1 ||
      exr_get_storage(context_, 0, &storage) != EXR_ERR_SUCCESS ||
      exr_get_data_window(context_, 0, &window) != EXR_ERR_SUCCESS ||
      exr_get_chunk_count(context_, 0, &chunks) != EXR_ERR_SUCCESS ||
      exr_get_channels(context_, 0, &list) != EXR_ERR_SUCCESS || !list)
    return fail("corrupt header: " + coreProblem(EXR_ERR_MISSING_REQ_ATTR));
  if (storage == EXR_STORAGE_DEEP_SCANLINE || storage == EXR_STORAGE_DEEP_TILED)
    return Status::error(StatusCode::UnsupportedFormat, path + ": holds deep data; only flat images are read");

  const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
  const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
  if (width <= 0 || height <= 0) return fail("empty data window");
  if (width > kMaxImageSide || height > kMaxImageSide)
    return fail("data window is " + std::to_string(width) + "x" + std::to_string(height) +
                "; the largest side read is " + std::to_string(kMaxImageSide));
  if (storage == EXR_STORAGE_TILED) {
    uint32_t tileX = 0, tileY = 0;
    exr_tile_level_mode_t levels{};
    exr_tile_round_mode_t round{};
    if (exr_get_tile_descriptor(context_, 0, &tileX, &tileY, &levels, &round) != EXR_ERR_SUCCESS)
      return fail("corrupt header: " + coreProblem(EXR_ERR_MISSING_REQ_ATTR));
    if (tileX == 0 || tileY == 0 || tileX > kMaxImageSide || tileY > kMaxImageSide)
      return fail("tiles are " + std::to_string(tileX) + "x" + std::to_string(tileY) + "; the largest side read is " +
                  std::to_string(kMaxImageSide));
    tiled_ = true;
    chunkWidth_ = std::min<std::uint32_t>(tileX, std::uint32_t(width));
    chunkLines_ = std::min<std::uint32_t>(tileY, std::uint32_t(height));
  } else {
    int32_t lines = 0;
    if (exr_get_scanlines_per_chunk(context_, 0, &lines) != EXR_ERR_SUCCESS || lines <= 0)
      return fail("corrupt header: " + coreProblem(EXR_ERR_MISSING_REQ_ATTR));
    chunkWidth_ = std::uint32_t(width);
    chunkLines_ = std::uint32_t(std::min<std::int64_t>(lines, height));
  }

  // Every chunk has an 8-byte entry in the offset table, so the file must hold chunks * 8 bytes:
  // a small file cannot declare a large image (checked before the table is read).
  std::error_code ec;
  const std::uintmax_t fileSize = fs::file_size(path, ec);
  if (ec) return fail("cannot read its size: " + ec.message());
  if (chunks <= 0 || std::uint64_t(chunks) * 8 > fileSize)
    return fail("is truncated or corrupt: its " + std::to_string(width) + "x" + std::to_string(height) +
                " data window needs " + std::to_string(chunks) + " chunks, whose offset table alone (" +
                std::to_string(std::uint64_t(std::max(chunks, 0)) * 8) + " bytes) exceeds the file's " +
                std::to_string(fileSize) + " bytes");

  if (std::uint64_t(width) * std::uint64_t(height) > kMaxExrPixels)
    return fail("data window is " + std::to_string(width) + "x" + std::to_string(height) + " = " +
                std::to_string(width * height) + " pixels; the most read is " + std::to_string(kMaxExrPixels));

  std::uint64_t pixelBytes = 0;  // all channels of one pixel, as stored
  channels_.clear();
  for (int c = 0; c < list->num_channels; ++c) {
    const exr_attr_chlist_entry_t& e = list->entries[c];
    pixelBytes += e.pixel_type == EXR_PIXEL_HALF ? 2 : 4;
    channels_.push_back({std::string(e.name.str, std::size_t(std::max(e.name.length, 0))), int(e.pixel_type),
                         e.x_sampling, e.y_sampling});
  }
  const std::uint64_t chunkBytes = std::uint64_t(chunkWidth_) * chunkLines_ * pixelBytes;
  if (chunkBytes > kMaxChunkBytes)
    return fail("one chunk would decode to " + std::to_string(chunkBytes) + " bytes (" + std::to_string(pixelBytes) +
                " bytes a pixel); the largest read is " + std::to_string(kMaxChunkBytes >> 20) + " MiB");

  minX_ = window.min.x;
  minY_ = window.min.y;
  extent_ = {std::uint32_t(width), std::uint32_t(height)};
  return Status::success();
}

bool Input::hasAttribute(const char* name) const {
  const exr_attribute_t* a = nullptr;
  return exr_get_attribute_by_name(context_, 0, name, &a) == EXR_ERR_SUCCESS && a;
}

Status Input::lookup(const char* name, int type, const char* typeName, bool& found, const exr_attribute_t*& out) const {
  out = nullptr;
  found = exr_get_attribute_by_name(context_, 0, name, &out) == EXR_ERR_SUCCESS && out;
  if (!found) return Status::success();
  if (out->type != type)
    return fail(std::string("attribute ") + name + " is of type " + attributeTypeName(*out) + ", expected " + typeName);
  return Status::success();
}

Status Input::intAttribute(const char* name, bool& found, int& value) const {
  const exr_attribute_t* a = nullptr;
  if (Status s = lookup(name, EXR_ATTR_INT, "int", found, a); !s || !found) return s;
  value = a->i;
  return Status::success();
}

Status Input::doubleAttribute(const char* name, bool& found, double& value) const {
  const exr_attribute_t* a = nullptr;
  if (Status s = lookup(name, EXR_ATTR_DOUBLE, "double", found, a); !s || !found) return s;
  value = a->d;
  return Status::success();
}

Status Input::stringAttribute(const char* name, bool& found, std::string& value) const {
  const exr_attribute_t* a = nullptr;
  if (Status s = lookup(name, EXR_ATTR_STRING, "string", found, a); !s || !found) return s;
  value.assign(a->string->str ? a->string->str : "", std::size_t(std::max(a->string->length, 0)));
  return Status::success();
}

Status Input::matrixAttribute(const char* name, bool& found, double (&value)[16]) const {
  const exr_attribute_t* a = nullptr;
  if (Status s = lookup(name, EXR_ATTR_M44D, "m44d", found, a); !s || !found) return s;
  std::copy_n(a->m44d->m, 16, value);
  return Status::success();
}

Status Input::stringVectorAttribute(const char* name, bool& found, std::vector<std::string>& value) const {
  const exr_attribute_t* a = nullptr;
  if (Status s = lookup(name, EXR_ATTR_STRING_VECTOR, "stringvector", found, a); !s || !found) return s;
  value.clear();
  for (int i = 0; i < a->stringvector->n_strings; ++i) {
    const exr_attr_string_t& s = a->stringvector->strings[i];
    value.emplace_back(s.str ? s.str : "", std::size_t(std::max(s.length, 0)));
  }
  return Status::success();
}

Status Input::readChannels(const std::vector<std::string>& names, std::vector<float>& data) const {
  const std::size_t w = extent_.width, h = extent_.height, n = names.size();
  std::vector<int> fileIndex;  // per requested channel, its index among the file's channels
  for (const std::string& name : names) {
    const auto it = std::find_if(channels_.begin(), channels_.end(), [&](const ChannelInfo& c) { return c.name == name; });
    if (it == channels_.end()) return fail("has no channel \"" + name + "\"");
    fileIndex.push_back(int(it - channels_.begin()));
  }

  exr_decode_pipeline_t decoder = EXR_DECODE_PIPELINE_INITIALIZER;
  bool decoderReady = false;
  struct Cleanup {
    exr_context_t ctxt;
    exr_decode_pipeline_t& d;
    bool& ready;
    ~Cleanup() {
      if (ready) exr_decoding_destroy(ctxt, &d);
    }
  } cleanup{context_, decoder, decoderReady};

  // Bands of chunkLines_ rows, decoded chunk by chunk (one chunk, or a row of tiles) and kept
  // apart: the image grows only as the file proves it holds the data, and is assembled at the end.
  std::vector<std::vector<float>> bands;  // top band first, as in the file
  std::vector<float> planar;              // one chunk, channel after channel
  for (std::size_t y0 = 0; y0 < h; y0 += chunkLines_) {
    const std::size_t rows = std::min<std::size_t>(chunkLines_, h - y0);
    std::vector<float> band(w * rows * n);
    for (std::size_t x0 = 0; x0 < w; x0 += chunkWidth_) {
      tCore.firstError.clear();
      exr_chunk_info_t chunk{};
      const exr_result_t found =
          tiled_ ? exr_read_tile_chunk_info(context_, 0, int(x0 / chunkWidth_), int(y0 / chunkLines_), 0, 0, &chunk)
                 : exr_read_scanline_chunk_info(context_, 0, minY_ + int(y0), &chunk);
      if (found != EXR_ERR_SUCCESS)
        return fail("is truncated or corrupt: the chunk of rows " + std::to_string(y0) + ".." +
                    std::to_string(y0 + rows - 1) + " cannot be located: " + coreProblem(found));
      const std::size_t cw = std::min<std::size_t>(chunkWidth_, w - x0);
      if (chunk.width != int(cw) || chunk.height != int(rows))
        return fail("is corrupt: the chunk of rows " + std::to_string(y0) + ".." + std::to_string(y0 + rows - 1) +
                    " is " + std::to_string(chunk.width) + "x" + std::to_string(chunk.height) + ", expected " +
                    std::to_string(cw) + "x" + std::to_string(rows));
      const exr_result_t initialised = decoderReady ? exr_decoding_update(context_, 0, &chunk, &decoder)
                                                    : exr_decoding_initialize(context_, 0, &chunk, &decoder);
      decoderReady = true;  // destroyed even after a failed initialisation, which may have allocated
      if (initialised != EXR_ERR_SUCCESS) return fail("cannot decode: " + coreProblem(initialised));
      planar.assign(cw * rows * n, 0.0f);
      for (int c = 0; c < decoder.channel_count; ++c) decoder.channels[c].decode_to_ptr = nullptr;
      for (std::size_t k = 0; k < n; ++k) {
        exr_coding_channel_info_t& ch = decoder.channels[fileIndex[k]];
        ch.decode_to_ptr = reinterpret_cast<uint8_t*>(planar.data() + k * cw * rows);
        ch.user_data_type = EXR_PIXEL_FLOAT;
        ch.user_bytes_per_element = 4;
        ch.user_pixel_stride = 4;
        ch.user_line_stride = int32_t(4 * cw);
      }
      exr_result_t r = exr_decoding_choose_default_routines(context_, 0, &decoder);
      if (r == EXR_ERR_SUCCESS) r = exr_decoding_run(context_, 0, &decoder);
      if (r != EXR_ERR_SUCCESS)
        return fail("is truncated or corrupt: the chunk of rows " + std::to_string(y0) + ".." +
                    std::to_string(y0 + rows - 1) + " does not decode: " + coreProblem(r));
      for (std::size_t k = 0; k < n; ++k)
        for (std::size_t y = 0; y < rows; ++y)
          for (std::size_t x = 0; x < cw; ++x)
            band[(y * w + x0 + x) * n + k] = planar[k * cw * rows + y * cw + x];
    }
    bands.push_back(std::move(band));
  }
  // Bottom row first; each band is freed once copied, so the peak is about twice the image.
  const std::size_t row = w * n;
  std::vector<float> image(h * row);
  std::size_t fileRow = 0;
  for (std::vector<float>& band : bands) {
    for (std::size_t r = 0; r < band.size() / row; ++r, ++fileRow)
      std::copy_n(band.data() + r * row, row, image.data() + (h - 1 - fileRow) * row);
    std::vector<float>().swap(band);
  }
  data = std::move(image);
  return Status::success();
}

}  // namespace sao::exr
