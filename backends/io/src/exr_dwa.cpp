// DWAA/DWAB chunks through OpenEXR's C++ library; see exr_dwa.h for why that is safe.
#include "exr_dwa.h"

#include <cstring>
#include <exception>
#include <cstdint>

#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStdIO.h>
#include <ImfVersion.h>
#include <openexr.h>

namespace sao::exr {
namespace {

void putLittleEndian(std::string& out, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(char((v >> (8 * i)) & 0xff));
}

// The one-chunk EXR: magic, version, our header, a one-entry offset table, the chunk.
std::string oneChunkFile(const DwaChunk& chunk) {
  const Imath::Box2i window({chunk.minX, chunk.minY}, {chunk.maxX, chunk.minY + chunk.lines - 1});
  Imf::Header header(window, window);
  header.compression() = chunk.compression == EXR_COMPRESSION_DWAB ? Imf::DWAB_COMPRESSION : Imf::DWAA_COMPRESSION;
  header.lineOrder() = Imf::INCREASING_Y;
  bool longNames = false;
  for (const ChannelInfo& c : chunk.channels) {
    const auto type = c.pixelType == EXR_PIXEL_HALF ? Imf::HALF : c.pixelType == EXR_PIXEL_FLOAT ? Imf::FLOAT : Imf::UINT;
    header.channels().insert(c.name, Imf::Channel(type, c.xSampling, c.ySampling, c.perceptuallyLinear));
    longNames |= c.name.size() > 31;
  }
  Imf::StdOSStream attributes;
  header.writeTo(attributes);
  std::string file;
  putLittleEndian(file, std::uint32_t(Imf::MAGIC), 4);
  putLittleEndian(file, std::uint32_t(Imf::EXR_VERSION | (longNames ? Imf::LONG_NAMES_FLAG : 0)), 4);
  file += attributes.str();
  putLittleEndian(file, file.size() + 8, 8);  // the chunk follows the table
  putLittleEndian(file, std::uint32_t(chunk.minY), 4);
  putLittleEndian(file, chunk.packed.size(), 4);
  file.append(reinterpret_cast<const char*>(chunk.packed.data()), chunk.packed.size());
  return file;
}

}  // namespace

bool decodeDwaChunk(const DwaChunk& chunk, const std::vector<int>& wanted, std::vector<float>& planar,
                    std::string& problem) {
  try {
    Imf::StdISStream stream;
    stream.str(oneChunkFile(chunk));
    Imf::InputFile file(stream);
    const std::size_t width = std::size_t(chunk.maxX - chunk.minX + 1), lines = std::size_t(chunk.lines);
    planar.assign(width * lines * wanted.size(), 0.0f);
    Imf::FrameBuffer buffer;
    for (std::size_t k = 0; k < wanted.size(); ++k) {
      // Slices address pixel (x, y) at base + x * xStride + y * yStride: shift by the window's origin.
      float* first = planar.data() + k * width * lines;
      // (in integers: the shifted address lies outside the buffer and is never dereferenced).
      const std::uintptr_t shift = std::uintptr_t(std::intptr_t(chunk.minX) * 4 + std::intptr_t(chunk.minY) * std::intptr_t(width * 4));
      char* base = reinterpret_cast<char*>(reinterpret_cast<std::uintptr_t>(first) - shift);
      buffer.insert(chunk.channels[std::size_t(wanted[k])].name, Imf::Slice(Imf::FLOAT, base, 4, width * 4));
    }
    file.setFrameBuffer(buffer);
    file.readPixels(chunk.minY, chunk.minY + chunk.lines - 1);
    return true;
  } catch (const std::exception& e) {
    problem = e.what();
  } catch (...) {
    problem = "unknown error";
  }
  return false;
}

}  // namespace sao::exr
