// OpenEXR input through OpenEXRCore only; see exr_reader.h for why.
#include "exr_reader.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>

#include "exr_dwa.h"
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

  int count = 0;
  if (exr_get_count(context_, &count) != EXR_ERR_SUCCESS || count < 1)
    return fail("corrupt header: " + coreProblem(EXR_ERR_MISSING_REQ_ATTR));
  std::error_code ec;
  fileSize_ = fs::file_size(path, ec);
  if (ec) return fail("cannot read its size: " + ec.message());
  // Every chunk has an 8-byte entry in an offset table, so the file must hold 8 bytes a chunk of
  // every part: a small file cannot declare a large image (checked before any table is read).
  std::uint64_t tableBytes = 0;
  parts_.clear();
  for (int p = 0; p < count; ++p) {
    int32_t chunks = 0;
    const exr_attr_chlist_t* list = nullptr;
    exr_attr_box2i_t window{};
    if (exr_get_chunk_count(context_, p, &chunks) != EXR_ERR_SUCCESS ||
        exr_get_data_window(context_, p, &window) != EXR_ERR_SUCCESS ||
        exr_get_channels(context_, p, &list) != EXR_ERR_SUCCESS || !list)
      return fail("corrupt header: " + coreProblem(EXR_ERR_MISSING_REQ_ATTR));
    const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
    const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
    if (width > kMaxImageSide || height > kMaxImageSide)
      return fail((count > 1 ? "part " + std::to_string(p) + "'s " : std::string()) + "data window is " +
                  std::to_string(width) + "x" + std::to_string(height) + "; the largest side read is " +
                  std::to_string(kMaxImageSide));
    tableBytes += std::uint64_t(std::max(chunks, 0)) * 8;
    if (chunks <= 0 || tableBytes > fileSize_) {
      return fail("is truncated or corrupt: " + std::string(count > 1 ? "part " + std::to_string(p) + "'s " : "its ") +
                  std::to_string(width) + "x" + std::to_string(height) + " data window needs " +
                  std::to_string(chunks) + " chunks, whose offset table alone (" +
                  std::to_string(std::uint64_t(std::max(chunks, 0)) * 8) + " bytes" +
                  (count > 1 ? ", with the other parts' " + std::to_string(tableBytes) : std::string()) +
                  ") exceeds the file's " + std::to_string(fileSize_) + " bytes");
    }
    PartInfo info;
    const char* name = nullptr;
    if (exr_get_name(context_, p, &name) == EXR_ERR_SUCCESS && name) info.name = name;
    for (int c = 0; c < list->num_channels; ++c) {
      const exr_attr_chlist_entry_t& e = list->entries[c];
      info.channels.push_back({std::string(e.name.str, std::size_t(std::max(e.name.length, 0))), int(e.pixel_type),
                               e.x_sampling, e.y_sampling, e.p_linear != 0});
    }
    parts_.push_back(std::move(info));
  }
  // The first part that can be read (a multi-part file may start with a deep one); the reader of
  // a depth file selects the part of its depth channel.
  Status first = selectPart(0);
  for (int p = 1; !first && p < count; ++p)
    if (selectPart(p)) return Status::success();
  return first;
}

Status Input::selectPart(int part) {
  if (part < 0 || part >= int(parts_.size())) return fail("has no part " + std::to_string(part));
  const std::string which = parts_.size() > 1 ? "part " + std::to_string(part) + "'s " : "";
  exr_storage_t storage = EXR_STORAGE_LAST_TYPE;
  exr_attr_box2i_t window{}, display{};
  exr_compression_t compression = EXR_COMPRESSION_NONE;
  if (exr_get_storage(context_, part, &storage) != EXR_ERR_SUCCESS ||
      exr_get_data_window(context_, part, &window) != EXR_ERR_SUCCESS ||
      exr_get_display_window(context_, part, &display) != EXR_ERR_SUCCESS ||
      exr_get_compression(context_, part, &compression) != EXR_ERR_SUCCESS)
    return fail("corrupt header: " + coreProblem(EXR_ERR_MISSING_REQ_ATTR));
  if (storage == EXR_STORAGE_DEEP_SCANLINE || storage == EXR_STORAGE_DEEP_TILED)
    return Status::error(StatusCode::UnsupportedFormat,
                         path_ + ": " + (parts_.size() > 1 ? "part " + std::to_string(part) + " holds" : "holds") +
                             " deep data; only flat images are read");

  const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
  const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
  if (width <= 0 || height <= 0) return fail(which.empty() ? "empty data window" : which + "data window is empty");
  if (width > kMaxImageSide || height > kMaxImageSide)
    return fail(which + "data window is " + std::to_string(width) + "x" + std::to_string(height) +
                "; the largest side read is " + std::to_string(kMaxImageSide));
  std::uint32_t chunkWidth = 0, chunkLines = 0;
  const bool tiled = storage == EXR_STORAGE_TILED;
  if (tiled) {
    uint32_t tileX = 0, tileY = 0;
    exr_tile_level_mode_t levels{};
    exr_tile_round_mode_t round{};
    if (exr_get_tile_descriptor(context_, part, &tileX, &tileY, &levels, &round) != EXR_ERR_SUCCESS)
      return fail("corrupt header: " + coreProblem(EXR_ERR_MISSING_REQ_ATTR));
    if (tileX == 0 || tileY == 0 || tileX > kMaxImageSide || tileY > kMaxImageSide)
      return fail("tiles are " + std::to_string(tileX) + "x" + std::to_string(tileY) + "; the largest side read is " +
                  std::to_string(kMaxImageSide));
    chunkWidth = std::min<std::uint32_t>(tileX, std::uint32_t(width));
    chunkLines = std::min<std::uint32_t>(tileY, std::uint32_t(height));
  } else {
    int32_t lines = 0;
    if (exr_get_scanlines_per_chunk(context_, part, &lines) != EXR_ERR_SUCCESS || lines <= 0)
      return fail("corrupt header: " + coreProblem(EXR_ERR_MISSING_REQ_ATTR));
    chunkWidth = std::uint32_t(width);
    chunkLines = std::uint32_t(std::min<std::int64_t>(lines, height));
  }

  if (std::uint64_t(width) * std::uint64_t(height) > kMaxExrPixels)
    return fail(which + "data window is " + std::to_string(width) + "x" + std::to_string(height) + " = " +
                std::to_string(width * height) + " pixels; the most read is " + std::to_string(kMaxExrPixels));

  std::uint64_t pixelBytes = 0;  // all channels of one pixel, as stored
  for (const ChannelInfo& c : parts_[std::size_t(part)].channels) pixelBytes += c.pixelType == EXR_PIXEL_HALF ? 2 : 4;
  const std::uint64_t chunkBytes = std::uint64_t(chunkWidth) * chunkLines * pixelBytes;
  if (chunkBytes > kMaxChunkBytes)
    return fail("one chunk would decode to " + std::to_string(chunkBytes) + " bytes (" + std::to_string(pixelBytes) +
                " bytes a pixel); the largest read is " + std::to_string(kMaxChunkBytes >> 20) + " MiB");

  part_ = part;
  tiled_ = tiled;
  chunkWidth_ = chunkWidth;
  chunkLines_ = chunkLines;
  compression_ = int(compression);
  minX_ = window.min.x;
  minY_ = window.min.y;
  dataWindow_ = {window.min.x, window.min.y, window.max.x, window.max.y};
  displayWindow_ = {display.min.x, display.min.y, display.max.x, display.max.y};
  extent_ = {std::uint32_t(width), std::uint32_t(height)};
  return Status::success();
}

const char* Input::compressionName() const {
  switch (compression_) {
    case EXR_COMPRESSION_NONE: return "NONE";
    case EXR_COMPRESSION_RLE: return "RLE";
    case EXR_COMPRESSION_ZIPS: return "ZIPS";
    case EXR_COMPRESSION_ZIP: return "ZIP";
    case EXR_COMPRESSION_PIZ: return "PIZ";
    case EXR_COMPRESSION_PXR24: return "PXR24";
    case EXR_COMPRESSION_B44: return "B44";
    case EXR_COMPRESSION_B44A: return "B44A";
    case EXR_COMPRESSION_DWAA: return "DWAA";
    case EXR_COMPRESSION_DWAB: return "DWAB";
    default: return "unknown";
  }
}

bool Input::isDwa() const { return compression_ == EXR_COMPRESSION_DWAA || compression_ == EXR_COMPRESSION_DWAB; }

bool Input::hasAttribute(const char* name) const {
  const exr_attribute_t* a = nullptr;
  return exr_get_attribute_by_name(context_, part_, name, &a) == EXR_ERR_SUCCESS && a;
}

Status Input::lookup(const char* name, int type, const char* typeName, bool& found, const exr_attribute_t*& out) const {
  out = nullptr;
  found = exr_get_attribute_by_name(context_, part_, name, &out) == EXR_ERR_SUCCESS && out;
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
  found = exr_get_attribute_by_name(context_, part_, name, &a) == EXR_ERR_SUCCESS && a;
  if (!found) return Status::success();
  // m44f is what OpenImageIO and Python's OpenEXR write for a matrix; each float widens exactly.
  if (a->type == EXR_ATTR_M44F) {
    std::copy_n(a->m44f->m, 16, value);
    return Status::success();
  }
  if (a->type != EXR_ATTR_M44D)
    return fail(std::string("attribute ") + name + " is of type " + attributeTypeName(*a) + ", expected m44d or m44f");
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

Status Input::decodeDwa(const exr_chunk_info_t& chunk, const std::vector<int>& fileIndex, std::vector<float>& planar,
                        std::size_t y0, std::size_t rows) const {
  const std::string where = "the chunk of rows " + std::to_string(y0) + ".." + std::to_string(y0 + rows - 1);
  if (tiled_)
    return Status::error(StatusCode::UnsupportedFormat,
                         path_ + ": is tiled and " + compressionName() +
                             "-compressed, which is not read; save it as scanlines (or with ZIP or PIZ)");
  // The core library located the chunk inside the file; its size is checked here before the
  // buffer is made, as the core library's decoder would.
  if (chunk.packed_size > kMaxChunkBytes || chunk.packed_size > fileSize_ || chunk.unpacked_size > kMaxChunkBytes)
    return fail("is corrupt: " + where + " declares " + std::to_string(chunk.packed_size) + " bytes");
  DwaChunk dwa;
  dwa.compression = compression_;
  dwa.channels = channels();
  dwa.minX = dataWindow_.minX;
  dwa.maxX = dataWindow_.maxX;
  dwa.minY = chunk.start_y;
  dwa.lines = chunk.height;
  dwa.packed.resize(chunk.packed_size);
  tCore.firstError.clear();
  if (const exr_result_t r = exr_read_chunk(context_, part_, &chunk, dwa.packed.data()); r != EXR_ERR_SUCCESS)
    return fail("is truncated or corrupt: " + where + " cannot be read: " + coreProblem(r));
  std::string problem;
  if (!decodeDwaChunk(dwa, fileIndex, planar, problem))
    return fail("is truncated or corrupt: " + where + " does not decode (" + compressionName() + "): " + problem);
  return Status::success();
}

Status Input::readChannels(const std::vector<std::string>& names, std::vector<float>& data) const {
  const std::size_t w = extent_.width, h = extent_.height, n = names.size();
  std::vector<int> fileIndex;  // per requested channel, its index among the file's channels
  for (const std::string& name : names) {
    const std::vector<ChannelInfo>& list = channels();
    const auto it = std::find_if(list.begin(), list.end(), [&](const ChannelInfo& c) { return c.name == name; });
    if (it == list.end()) return fail("has no channel \"" + name + "\"");
    fileIndex.push_back(int(it - list.begin()));
  }

  exr_decode_pipeline_t decoder{};  // EXR_DECODE_PIPELINE_INITIALIZER's all-zero state; its {0} warns under clang's -Wextra
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
          tiled_ ? exr_read_tile_chunk_info(context_, part_, int(x0 / chunkWidth_), int(y0 / chunkLines_), 0, 0, &chunk)
                 : exr_read_scanline_chunk_info(context_, part_, minY_ + int(y0), &chunk);
      if (found != EXR_ERR_SUCCESS)
        return fail("is truncated or corrupt: the chunk of rows " + std::to_string(y0) + ".." +
                    std::to_string(y0 + rows - 1) + " cannot be located: " + coreProblem(found));
      const std::size_t cw = std::min<std::size_t>(chunkWidth_, w - x0);
      if (chunk.width != int(cw) || chunk.height != int(rows))
        return fail("is corrupt: the chunk of rows " + std::to_string(y0) + ".." + std::to_string(y0 + rows - 1) +
                    " is " + std::to_string(chunk.width) + "x" + std::to_string(chunk.height) + ", expected " +
                    std::to_string(cw) + "x" + std::to_string(rows));
      if (isDwa()) {
        if (Status s = decodeDwa(chunk, fileIndex, planar, y0, rows); !s) return s;
        for (std::size_t k = 0; k < n; ++k)
          for (std::size_t y = 0; y < rows; ++y)
            for (std::size_t x = 0; x < cw; ++x)
              band[(y * w + x0 + x) * n + k] = planar[k * cw * rows + y * cw + x];
        continue;
      }
      const exr_result_t initialised = decoderReady ? exr_decoding_update(context_, part_, &chunk, &decoder)
                                                    : exr_decoding_initialize(context_, part_, &chunk, &decoder);
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
      exr_result_t r = exr_decoding_choose_default_routines(context_, part_, &decoder);
      if (r == EXR_ERR_SUCCESS) r = exr_decoding_run(context_, part_, &decoder);
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
