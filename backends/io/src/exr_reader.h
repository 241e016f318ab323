// Reading an OpenEXR file that nobody vouches for, through OpenEXR's C core library (OpenEXRCore)
// alone. The C++ reader of OpenEXR 3.1 parses a header differently from the core library where
// the two disagree on a malformed attribute, and sizes allocations from what it parsed before it
// checks them against the file (a 447-byte file made it allocate 1.7 GB), so it never sees an
// input file here; it only writes. Every allocation while reading is bounded before it is made:
// the core library's go through a budget, the image grows only as chunks decode.
// One exception, DWAA/DWAB chunks, which the core library of OpenEXR 3.1 cannot decode: the C++
// library decodes them, but only from a one-chunk image that exr_dwa.h writes in memory from what
// the core library has already parsed and checked (see there): it never parses the user's header.
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
  bool perceptuallyLinear = false;  // pLinear, a hint to lossy compression
};

// One part of a (possibly multi-part) file as its header declares it.
struct PartInfo {
  std::string name;  // its "name" attribute; "" in a single-part file without one
  std::vector<ChannelInfo> channels;
};

// An EXR box (data or display window), inclusive.
struct Box {
  int minX = 0, minY = 0, maxX = -1, maxY = -1;
  bool operator==(const Box&) const = default;
};

class Input {
 public:
  Input();
  ~Input();
  Input(const Input&) = delete;
  Input& operator=(const Input&) = delete;

  // Opens `path` and checks the header: a regular file, the magic number, headers the core
  // library parses without complaint, chunk offset tables (of every part) that fit in the file;
  // then selects part 0 (selectPart).
  Status open(const std::string& path);

  // Every part's name and channels, for choosing one and for messages.
  const std::vector<PartInfo>& parts() const { return parts_; }

  // Makes `part` the one read: a flat image (not deep), a data window of at most kMaxImageSide a
  // side and kMaxExrPixels in all, tiles of at most kMaxImageSide a side, chunks that decode to
  // at most kMaxChunkBytes. The attribute look-ups and readChannels use this part.
  Status selectPart(int part);
  int part() const { return part_; }

  Extent extent() const { return extent_; }  // the data window's
  Box dataWindow() const { return dataWindow_; }
  Box displayWindow() const { return displayWindow_; }
  const std::vector<ChannelInfo>& channels() const { return parts_[std::size_t(part_)].channels; }
  // The part's compression (EXR_COMPRESSION_*) and its name ("ZIP", "B44", "DWAA", ...).
  int compression() const { return compression_; }
  const char* compressionName() const;

  // Typed attribute look-ups. `found` false: the file has no attribute of that name.
  // An attribute of another type fails with a message naming both types.
  Status intAttribute(const char* name, bool& found, int& value) const;
  Status doubleAttribute(const char* name, bool& found, double& value) const;
  Status stringAttribute(const char* name, bool& found, std::string& value) const;
  // m44d, or m44f (what OpenImageIO and Python's OpenEXR write), row-major as stored.
  Status matrixAttribute(const char* name, bool& found, double (&value)[16]) const;
  Status stringVectorAttribute(const char* name, bool& found, std::vector<std::string>& value) const;
  bool hasAttribute(const char* name) const;

  // Reads the named channels (FLOAT or HALF, full resolution) as float, interleaved, image row 0 =
  // the file's bottom scanline. The image grows as chunks decode, so a file that declares more
  // than it holds fails before the whole image is allocated.
  Status readChannels(const std::vector<std::string>& names, std::vector<float>& data) const;

 private:
  Status fail(const std::string& problem) const;
  Status lookup(const char* name, int type, const char* typeName, bool& found, const exr_attribute_t*& out) const;
  bool isDwa() const;
  // One DWAA/DWAB scanline chunk through exr_dwa.h, as readChannels' planar buffer.
  Status decodeDwa(const exr_chunk_info_t& chunk, const std::vector<int>& fileIndex, std::vector<float>& planar,
                   std::size_t y0, std::size_t rows) const;

  std::string path_;
  std::uint64_t fileSize_ = 0;
  exr_context_t context_ = nullptr;
  std::vector<PartInfo> parts_;
  int part_ = 0;
  Extent extent_{};
  Box dataWindow_, displayWindow_;
  int minX_ = 0, minY_ = 0;
  int compression_ = 0;
  bool tiled_ = false;
  std::uint32_t chunkWidth_ = 0, chunkLines_ = 0;  // a tile, or the full width and the lines of a block
};

}  // namespace sao::exr
