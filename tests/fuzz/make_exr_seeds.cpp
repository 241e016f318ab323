// Writes the seed corpus of the fuzz_exr_depth target (corpus/exr_depth/): small depth EXRs as
// sao::writeDepthExr writes them (every depth format, with the camera attributes), float EXRs of
// several channels, and foreign single-channel files in each scanline compression plus a tiled
// one, so that the fuzzer starts from every code path of the loaders.
//   cmake --build build --target fuzz_make_exr_seeds && build/bin/fuzz_make_exr_seeds tests/fuzz/corpus/exr_depth
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfTiledOutputFile.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "sao/io.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_make_exr_seeds DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  int failures = 0;
  auto check = [&](const sao::Status& st) {
    if (!st) {
      std::fprintf(stderr, "%s\n", st.message.c_str());
      ++failures;
    }
  };

  // sao depth files: a 4x2 viewport with a guard band of 1 -> 6x4 texels.
  sao::Camera cam = sao::perspectiveCamera(1.0, 4, 2, 0.1, 50.0, sao::ClipDepth::ZeroToOne, true);
  cam.guardBand = 1;
  const std::pair<sao::DepthFormat, const char*> formats[] = {
      {sao::DepthFormat::D16, "d16"}, {sao::DepthFormat::D24, "d24"}, {sao::DepthFormat::D32F, "d32f"},
      {sao::DepthFormat::LinearZ, "linearz"}};
  for (const auto& [f, name] : formats) {
    sao::DepthImage d;
    d.extent = {6, 4};
    d.format = f;
    for (std::uint32_t i = 0; i < 24; ++i)
      d.texels.push_back(f == sao::DepthFormat::LinearZ ? sao::encodeDepth(f, -1.0 - i) : sao::encodeDepth(f, i / 23.0));
    check(sao::writeDepthExr(dir + "/depth_" + name + ".exr", d, cam));
  }

  // Float EXRs (intermediates): 1 and 3 channels with the sao.channels order attribute.
  sao::FloatImage rg({3, 2}, 2, 0.5f), rgb({2, 2}, 3, -1.0f);
  check(sao::writeFloatExr(dir + "/float_2ch.exr", rg, {"ao", "key"}));
  check(sao::writeFloatExr(dir + "/float_3ch_z.exr", rgb, {"X", "Z", "B"}));

  // Foreign files: one HALF channel "R", 4x3, one per scanline compression; one tiled FLOAT "Z".
  std::vector<half> px(12);
  for (int i = 0; i < 12; ++i) px[std::size_t(i)] = half(float(i) / 11.0f);
  const struct {
    const char* name;
    Imf::Compression c;
  } codecs[] = {{"none", Imf::NO_COMPRESSION}, {"rle", Imf::RLE_COMPRESSION}, {"zips", Imf::ZIPS_COMPRESSION},
                {"piz", Imf::PIZ_COMPRESSION}, {"pxr24", Imf::PXR24_COMPRESSION}, {"b44", Imf::B44_COMPRESSION},
                {"dwaa", Imf::DWAA_COMPRESSION}, {"dwab", Imf::DWAB_COMPRESSION}};
  for (const auto& codec : codecs) {
    Imf::Header h(4, 3);
    h.compression() = codec.c;
    h.channels().insert("R", Imf::Channel(Imf::HALF));
    Imf::OutputFile out((dir + "/foreign_half_" + codec.name + ".exr").c_str(), h);
    Imf::FrameBuffer fb;
    fb.insert("R", Imf::Slice(Imf::HALF, reinterpret_cast<char*>(px.data()), sizeof(half), sizeof(half) * 4));
    out.setFrameBuffer(fb);
    out.writePixels(3);
  }
  {
    Imf::Header h(5, 3);
    h.setTileDescription(Imf::TileDescription(2, 2, Imf::ONE_LEVEL));
    h.channels().insert("Z", Imf::Channel(Imf::FLOAT));
    std::vector<float> z(15, 0.25f);
    Imf::TiledOutputFile out((dir + "/foreign_tiled_z.exr").c_str(), h);
    Imf::FrameBuffer fb;
    fb.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(z.data()), sizeof(float), sizeof(float) * 5));
    out.setFrameBuffer(fb);
    out.writeTiles(0, out.numXTiles() - 1, 0, out.numYTiles() - 1);
  }
  // DWA with data that compresses (4x3 above is stored raw): 16x16, a lossy "Y" and a lossless "Z".
  for (const auto& [name, c] : {std::pair{"dwaa", Imf::DWAA_COMPRESSION}, std::pair{"dwab", Imf::DWAB_COMPRESSION}}) {
    Imf::Header h(16, 16);
    h.compression() = c;
    h.channels().insert("Y", Imf::Channel(Imf::HALF));
    h.channels().insert("Z", Imf::Channel(Imf::FLOAT));
    std::vector<half> y(256);
    std::vector<float> z(256);
    for (int i = 0; i < 256; ++i) {
      y[std::size_t(i)] = half(std::sin(float(i) * 0.1f));
      z[std::size_t(i)] = float(i % 16) * 0.05f;
    }
    Imf::OutputFile out((dir + "/foreign_yz_" + name + ".exr").c_str(), h);
    Imf::FrameBuffer fb;
    fb.insert("Y", Imf::Slice(Imf::HALF, reinterpret_cast<char*>(y.data()), sizeof(half), sizeof(half) * 16));
    fb.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(z.data()), sizeof(float), sizeof(float) * 16));
    out.setFrameBuffer(fb);
    out.writePixels(16);
  }
  {
    // Two parts, the depth ("depth.Z") in the second; the first's data window cropped inside its
    // display window.
    Imf::Header beauty(Imath::Box2i({0, 0}, {3, 2}), Imath::Box2i({1, 1}, {2, 2}));
    beauty.channels().insert("R", Imf::Channel(Imf::HALF));
    beauty.setName("beauty");
    beauty.setType(Imf::SCANLINEIMAGE);
    Imf::Header depth(4, 3);
    depth.channels().insert("depth.Z", Imf::Channel(Imf::HALF));
    depth.setName("depth");
    depth.setType(Imf::SCANLINEIMAGE);
    const Imf::Header headers[] = {beauty, depth};
    Imf::MultiPartOutputFile out((dir + "/foreign_two_parts.exr").c_str(), headers, 2);
    for (int p = 0; p < 2; ++p) {
      Imf::OutputPart part(out, p);
      Imf::FrameBuffer fb;
      const int w = p == 0 ? 2 : 4, x0 = p == 0 ? 1 : 0, y0 = p == 0 ? 1 : 0;
      char* base = reinterpret_cast<char*>(px.data()) - (x0 + y0 * w) * int(sizeof(half));
      fb.insert(p == 0 ? "R" : "depth.Z", Imf::Slice(Imf::HALF, base, sizeof(half), sizeof(half) * std::size_t(w)));
      part.setFrameBuffer(fb);
      part.writePixels(p == 0 ? 2 : 3);
    }
  }
  std::printf("seeds written to %s (%d failures)\n", dir.c_str(), failures);
  return failures ? 1 : 0;
}
