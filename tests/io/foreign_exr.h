// Depth EXRs as other tools write them (OpenEXR's C++ library, as Blender, Nuke, OpenImageIO and
// Python do): other compressions, several parts, layer names, cropped data windows, m44f
// matrices. Written at test time by the io tests and by make_foreign_depth for the CLI tests.
#pragma once
#include <ImathBox.h>
#include <ImfCompression.h>
#include <ImfHeader.h>
#include <ImfPixelType.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sao::test {

struct ForeignDepth {
  int width = 0, height = 0;             // the data window's size
  Imath::V2i origin{0, 0};               // the data window's first pixel
  std::optional<Imath::Box2i> display;   // default: the data window
  Imf::Compression compression = Imf::ZIP_COMPRESSION;
  Imf::PixelType type = Imf::FLOAT;
  std::vector<std::string> channels{"Z"};  // every channel but depthChannel holds 0.5
  std::string depthChannel = "Z";
  std::vector<float> depth;                // width * height, the file's top row first
  // Parts written before the depth's (each a list of HALF channels holding 0.25); with any, the
  // file is multi-part and the depth's part is named "depth".
  std::vector<std::vector<std::string>> partsBefore;
  std::function<void(Imf::Header&)> decorate;  // attributes of the depth's part
};

void writeForeignDepth(const std::string& path, const ForeignDepth& f);

}  // namespace sao::test
