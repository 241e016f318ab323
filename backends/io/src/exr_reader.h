// Reading an OpenEXR file that nobody vouches for, through OpenEXR's C core library (OpenEXRCore)
// alone. The C++ reader of OpenEXR 3.1 parses a header differently from the core library where
// the two disagree on a malformed attribute, and sizes allocations from what it parsed before it
// checks them against the file (a 447-byte file made it allocate 1.7 GB), so it never sees an
// input file here; it only writes. Every allocation while reading is bounded before it is made:
// the core library's go through a budget, the image grows only as chunks decode.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <openexr.h>

#include "sao/image.h"
#include "sao/status.h"

namespace sao::exr {

// Most bytes the core library may hold at once while reading one file (header, chunk table,
// compressed and decompressed buffers of one chunk). A legitimate file needs a few MiB.
inline constexpr std::uint64_t kCoreMemoryBudget = std::uint64_t(48) << 20;
// Largest decoded chunk (all channels of one scanline block or tile).
inline constexpr std::uint64_t kMaxChunkBytes = std::uint64_t(32) << 20;

// One channel as the file declares it.
struct ChannelInfo {
  std::string name;
  int pixelType = 0;  // 0 UINT, 1 HALF, 2 FLOAT (the file's encoding)
  int xSampling = 1, ySampling = 1;
};

class Input {
 public:
  Input();
  ~Input();
  Input(const Input&) = delete;
  Input& operator=(const Input&) = delete;

  // Opens `path` and checks the header: a regular file, the magic number, a header the core
  // library parses without complaint, a flat image (not deep), a data window of at most
  // kMaxImageSide a side and kMaxExrPixels in all, tiles of at most kMaxImageSide a side,
  // a chunk offset table that fits in the file, chunks that decode to at most kMaxChunkBytes.
  Status open(const std::string& path);

  Extent extent() const { return extent_; }
  const std::vector<ChannelInfo>& channels() const { return channels_; }

  // Typed attribute look-ups. `found` false: the file has no attribute of that name.
  // An attribute of another type fails with a message naming both types.
  Status intAttribute(const char* name, bool& found, int& value) const;
  Status doubleAttribute(const char* name, bool& found, double& value) const;
  Status stringAttribute(const char* name, bool& found, std::string& value) const;
  Status matrixAttribute(const char* name, bool& found, double (&value)[16]) const;  // m44d, row-major as stored
  Status stringVectorAttribute(const char* name, bool& found, std::vector<std::string>& value) const;
  bool hasAttribute(const char* name) const;

  // Reads the named channels (FLOAT or HALF, full resolution) as float, interleaved, image row 0 =
  // the file's bottom scanline. The image grows as chunks decode, so a file that declares more
  // than it holds fails before the whole image is allocated.
  Status readChannels(const std::vector<std::string>& names, std::vector<float>& data) const;

 private:
  Status fail(const std::string& problem) const;
  Status lookup(const char* name, int type, const char* typeName, bool& found, const exr_attribute_t*& out) const;

  std::string path_;
  exr_context_t context_ = nullptr;
  Extent extent_{};
  int minX_ = 0, minY_ = 0;
  bool tiled_ = false;
  std::uint32_t chunkWidth_ = 0, chunkLines_ = 0;  // a tile, or the full width and the lines of a block
  std::vector<ChannelInfo> channels_;
};

}  // namespace sao::exr
