// DWAA/DWAB chunks, which OpenEXRCore 3.1 (Debian 12) cannot decompress ("DWA/A decompression not
// yet implemented in C"), decoded by OpenEXR's C++ library instead.
//
// Why this keeps exr_reader.h's promise (the C++ library never parses a file nobody vouches for):
// the C++ library is handed a one-chunk EXR that is written here, in memory, from values the core
// library has already parsed and exr::Input has already checked: a header of our own (the chunk's
// lines as its data window, the part's channels, DWAA or DWAB), a one-entry offset table of our
// own, and the chunk's packed bytes, which the core library read from where its offset table says
// and whose size is at most kMaxChunkBytes. So every allocation the C++ library sizes from a
// header is sized by our header (one chunk, checked), and the only bytes of the user's file it
// reads are the compressed payload, whose own size fields the DWA decompressor checks against the
// payload's length before it allocates. Its exceptions are caught and returned as a Status.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "exr_reader.h"

namespace sao::exr {

struct DwaChunk {
  int compression = 0;                   // EXR_COMPRESSION_DWAA or _DWAB
  std::vector<ChannelInfo> channels;     // all of the part's, as declared
  int minX = 0, maxX = 0;                // the data window's columns
  int minY = 0, lines = 0;               // the chunk's first line (file coordinates) and line count
  std::vector<std::uint8_t> packed;      // the chunk's bytes as stored
};

// Decodes the named channels (indices into chunk.channels, FLOAT or HALF) of one scanline chunk
// into `planar`: channel after channel, each `lines` rows of the data window's width, top row
// first (the file's order), as float. On failure the message says what the library reported.
bool decodeDwaChunk(const DwaChunk& chunk, const std::vector<int>& wanted, std::vector<float>& planar,
                    std::string& problem);

}  // namespace sao::exr
