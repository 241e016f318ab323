// Depth EXRs as other tools write them (issue 39, "Depth files as other tools write them"): each is
// written at test time with OpenEXR's C++ library (foreign_exr.h) and read with readDepthExr.
#include <ImfFrameBuffer.h>
#include <ImfInputFile.h>
#include <ImfMatrixAttribute.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "foreign_exr.h"
#include "sao/io.h"
#include "temp_dir.h"

namespace sao {
namespace {

using test::ForeignDepth;
using test::writeForeignDepth;

class ForeignExr : public test::TempDirTest {};

// A depth ramp in (0, 1) that differs at every texel: value of the file's pixel i.
float ramp(std::size_t i) { return 0.001f + 0.0007f * float(i % 1300); }

ForeignDepth rampFile(int w, int h) {
  ForeignDepth f;
  f.width = w;
  f.height = h;
  for (std::size_t i = 0; i < std::size_t(w) * h; ++i) f.depth.push_back(ramp(i));
  return f;
}

float texel(const DepthImage& d, std::uint32_t x, std::uint32_t y) {
  return std::bit_cast<float>(d.texels[std::size_t(y) * d.extent.width + x]);
}

// The file's pixel (x, y) (top row first) is image (x, h - 1 - y): the whole ramp, bit for bit.
void expectRamp(const DepthImage& d, int w, int h) {
  ASSERT_EQ(d.extent, (Extent{std::uint32_t(w), std::uint32_t(h)}));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      ASSERT_EQ(texel(d, std::uint32_t(x), std::uint32_t(h - 1 - y)), ramp(std::size_t(y) * w + x)) << x << "," << y;
}

Status read(const std::string& path, DepthImage& d, DepthFileInfo& info, DepthReadOptions options = {}) {
  Camera cam;
  return readDepthExr(path, d, cam, info, options);
}

// The sao.* attributes of a file writeDepthExr wrote, to decorate a foreign file with a camera;
// `leaveOut` names one to omit (not Header::erase afterwards: OpenEXR 3.1's erase leaks the attribute).
std::function<void(Imf::Header&)> saoCamera(const std::string& samplePath, const Camera& cam, const Extent& e,
                                            bool m44f = false, const std::string& leaveOut = "") {
  DepthImage d;
  d.extent = e;
  d.format = DepthFormat::D32F;
  d.texels.assign(std::size_t(e.width) * e.height, std::bit_cast<std::uint32_t>(0.5f));
  EXPECT_TRUE(writeDepthExr(samplePath, d, cam));
  Imf::InputFile in(samplePath.c_str());
  const Imf::Header source = in.header();
  return [source, m44f, leaveOut](Imf::Header& h) {
    for (auto it = source.begin(); it != source.end(); ++it) {
      const std::string name = it.name();
      if (name.rfind("sao.", 0) != 0 || name == leaveOut) continue;
      if (m44f && name == "sao.projection") {
        const auto& m = static_cast<const Imf::M44dAttribute&>(it.attribute()).value();
        Imath::M44f f;
        for (int i = 0; i < 4; ++i)
          for (int j = 0; j < 4; ++j) f[i][j] = float(m[i][j]);
        h.insert(name, Imf::M44fAttribute(f));
      } else {
        h.insert(name, it.attribute());
      }
    }
  };
}

// ---- 1. DWAA / DWAB ----------------------------------------------------------------------------

TEST_F(ForeignExr, DwaaAndDwabAreRead) {
  for (Imf::Compression c : {Imf::DWAA_COMPRESSION, Imf::DWAB_COMPRESSION}) {
    for (Imf::PixelType type : {Imf::FLOAT, Imf::HALF}) {
      ForeignDepth f = rampFile(67, 300);  // several chunks of 32 (DWAA) and 256 (DWAB) lines
      f.compression = c;
      f.type = type;
      if (type == Imf::HALF)
        for (float& v : f.depth) v = float(half(v));
      const std::string path = file("dwa.exr");
      writeForeignDepth(path, f);
      DepthImage d;
      DepthFileInfo info;
      const Status s = read(path, d, info);
      ASSERT_TRUE(s) << s.message;
      EXPECT_EQ(info.compression, c == Imf::DWAA_COMPRESSION ? "DWAA" : "DWAB");
      EXPECT_EQ(info.storedAsHalf, type == Imf::HALF);
      // DWA keeps a channel named Z losslessly (zlib): the ramp comes back bit for bit.
      ASSERT_EQ(d.extent, (Extent{67, 300}));
      for (int y = 0; y < 300; ++y)
        for (int x = 0; x < 67; ++x)
          ASSERT_EQ(texel(d, std::uint32_t(x), std::uint32_t(299 - y)), f.depth[std::size_t(y) * 67 + x]);
    }
  }
}

TEST_F(ForeignExr, LossyDwaChannelIsReadApproximately) {
  ForeignDepth f = rampFile(40, 40);
  f.compression = Imf::DWAA_COMPRESSION;
  f.channels = {"Y"};  // DWA's lossy DCT applies to luminance
  f.depthChannel = "Y";
  const std::string path = file("y.exr");
  writeForeignDepth(path, f);
  DepthImage d;
  DepthFileInfo info;
  ASSERT_TRUE(read(path, d, info));
  EXPECT_TRUE(info.lossy);
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x)
      ASSERT_NEAR(texel(d, std::uint32_t(x), std::uint32_t(39 - y)), f.depth[std::size_t(y) * 40 + x], 0.05);
}

TEST_F(ForeignExr, CorruptDwaChunkIsRefusedNotCrashed) {
  ForeignDepth f = rampFile(64, 64);
  f.compression = Imf::DWAB_COMPRESSION;
  const std::string path = file("dwa.exr");
  writeForeignDepth(path, f);
  std::vector<char> bytes = test::readBytes(path);
  // Every byte of the last 200 (the chunk's payload) in turn, and the payload cut short.
  for (std::size_t k = bytes.size() - 200; k < bytes.size(); k += 7) {
    std::vector<char> bad = bytes;
    bad[k] = char(bad[k] ^ 0x5a);
    test::writeBytes(path, bad);
    DepthImage d;
    DepthFileInfo info;
    (void)read(path, d, info);  // either result, never a crash, a leak or an exception
  }
  test::writeBytes(path, std::vector<char>(bytes.begin(), bytes.end() - 50));
  DepthImage d;
  DepthFileInfo info;
  const Status s = read(path, d, info);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message.find("truncated or corrupt"), std::string::npos) << s.message;
}

// ---- 2. where the depth channel is ------------------------------------------------------------

TEST_F(ForeignExr, DepthInTheSecondPartIsRead) {
  ForeignDepth f = rampFile(9, 7);
  f.partsBefore = {{"R", "G", "B", "A"}};
  const std::string path = file("parts.exr");
  writeForeignDepth(path, f);
  DepthImage d;
  DepthFileInfo info;
  const Status s = read(path, d, info);
  ASSERT_TRUE(s) << s.message;
  EXPECT_EQ(info.part, 1u);
  EXPECT_EQ(info.parts, 2u);
  expectRamp(d, 9, 7);
}

TEST_F(ForeignExr, BlenderMultilayerAndRgbaPlusDepthZ) {
  const std::vector<std::vector<std::string>> layouts = {
      {"ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B", "ViewLayer.Combined.A",
       "ViewLayer.Depth.Z", "ViewLayer.Normal.X", "ViewLayer.Normal.Y", "ViewLayer.Normal.Z", "ViewLayer.Vector.Z"},
      {"R", "G", "B", "A", "depth.Z"}};
  for (const auto& channels : layouts) {
    ForeignDepth f = rampFile(5, 4);
    f.channels = channels;
    f.depthChannel = channels[0][0] == 'V' ? "ViewLayer.Depth.Z" : "depth.Z";
    const std::string path = file("layers.exr");
    writeForeignDepth(path, f);
    DepthImage d;
    DepthFileInfo info;
    const Status s = read(path, d, info);
    ASSERT_TRUE(s) << s.message;
    EXPECT_EQ(info.channel, f.depthChannel);
    expectRamp(d, 5, 4);
  }
}

TEST_F(ForeignExr, NoneOrSeveralDepthChannelsListEveryPart) {
  ForeignDepth several = rampFile(3, 3);
  several.channels = {"Z"};
  several.partsBefore = {{"R", "depth.Z"}};
  const std::string path = file("several.exr");
  writeForeignDepth(path, several);
  DepthImage d;
  DepthFileInfo info;
  Status s = read(path, d, info);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message.find("has 2 parts and 2 depth channels (part 0 \"beauty0\": R, depth.Z; part 1 \"depth\": Z)"),
            std::string::npos)
      << s.message;

  ForeignDepth none = rampFile(3, 3);
  none.channels = {"Y", "A"};
  none.depthChannel = "Y";
  none.partsBefore = {{"R", "G", "B"}};
  writeForeignDepth(path, none);
  s = read(path, d, info);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message.find("has 2 parts and no depth channel (part 0 \"beauty0\": B, G, R; part 1 \"depth\": A, Y)"),
            std::string::npos)
      << s.message;
}

// ---- 3. a data window cropped inside the display window ----------------------------------------

TEST_F(ForeignExr, CropIsPlacedInTheDisplayWindowWithSkyAround) {
  ForeignDepth f = rampFile(4, 3);
  f.origin = {2, 1};
  f.display = Imath::Box2i({0, 0}, {7, 5});
  const std::string path = file("crop.exr");
  writeForeignDepth(path, f);
  for (float sky : {1.0f, 0.0f}) {
    DepthImage d;
    DepthFileInfo info;
    DepthReadOptions options;
    options.skyWithoutCamera = sky;
    const Status s = read(path, d, info, options);
    ASSERT_TRUE(s) << s.message;
    ASSERT_EQ(d.extent, (Extent{8, 6}));
    EXPECT_EQ(info.cropFillTexels, 8u * 6u - 4u * 3u);
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 8; ++x) {
        const bool inData = x >= 2 && x <= 5 && y >= 1 && y <= 3;
        const float want = inData ? ramp(std::size_t(y - 1) * 4 + std::size_t(x - 2)) : sky;
        EXPECT_EQ(texel(d, std::uint32_t(x), std::uint32_t(5 - y)), want) << "display pixel " << x << "," << y;
      }
  }
}

TEST_F(ForeignExr, CropWithACameraIsFilledWithItsClearValue) {
  const Camera cam = perspectiveCamera(1.0, 8, 6, 0.1, INFINITY, ClipDepth::ZeroToOne, true);
  ForeignDepth f = rampFile(4, 3);
  f.origin = {2, 1};
  f.display = Imath::Box2i({0, 0}, {7, 5});
  f.decorate = saoCamera(file("sample.exr"), cam, {8, 6});
  const std::string path = file("crop.exr");
  writeForeignDepth(path, f);
  DepthImage d;
  DepthFileInfo info;
  const Status s = read(path, d, info);
  ASSERT_TRUE(s) << s.message;
  EXPECT_TRUE(info.hasCamera);
  EXPECT_EQ(texel(d, 0, 0), 0.0f);  // reversed-Z: the sky is 0
  EXPECT_EQ(texel(d, 2, 5 - 1), ramp(0));
}

TEST_F(ForeignExr, OverscanAndHugeCropsAreRefusedNamingBothWindows) {
  ForeignDepth over = rampFile(10, 8);
  over.origin = {-1, -1};
  over.display = Imath::Box2i({0, 0}, {7, 5});
  const std::string path = file("over.exr");
  writeForeignDepth(path, over);
  DepthImage d;
  DepthFileInfo info;
  Status s = read(path, d, info);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message.find("data window (-1, -1)-(8, 6) and display window (0, 0)-(7, 5)"), std::string::npos)
      << s.message;

  ForeignDepth huge = rampFile(1, 1);
  huge.display = Imath::Box2i({0, 0}, {16383, 16383});
  writeForeignDepth(path, huge);
  s = read(path, d, info);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message.find("display window (0, 0)-(16383, 16383): the crop leaves"), std::string::npos) << s.message;
}

// ---- 4. sao.projection as m44f -----------------------------------------------------------------

TEST_F(ForeignExr, ProjectionAsM44fIsAccepted) {
  const Camera cam = perspectiveCamera(1.0, 6, 4, 0.1, 100.0, ClipDepth::ZeroToOne, false);
  ForeignDepth f = rampFile(6, 4);
  f.decorate = saoCamera(file("sample.exr"), cam, {6, 4}, true);
  const std::string path = file("m44f.exr");
  writeForeignDepth(path, f);
  DepthImage d;
  Camera back;
  DepthFileInfo info;
  const Status s = readDepthExr(path, d, back, info);
  ASSERT_TRUE(s) << s.message;
  EXPECT_TRUE(info.hasCamera);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(back.projection[std::size_t(i)], double(float(cam.projection[std::size_t(i)])));
}

// ---- 6. and 7. what the program needs for its messages ------------------------------------------

TEST_F(ForeignExr, B44NoiseAroundASkyOfZeroIsReadAsZero) {
  // Reversed-Z as a HALF B44 file: a sky of 0 beside surfaces. B44 packs 4x4 blocks relative to
  // their largest value, so the sky texels of mixed blocks come back slightly negative.
  ForeignDepth f;
  f.width = f.height = 16;
  f.type = Imf::HALF;
  f.compression = Imf::B44_COMPRESSION;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) f.depth.push_back((x + y) % 3 == 0 ? 0.0f : 0.02f + 0.001f * float(x));
  const std::string path = file("b44.exr");
  writeForeignDepth(path, f);
  // The premise: the file holds values below 0 (read with OpenEXR itself).
  {
    Imf::InputFile in(path.c_str());
    std::vector<float> stored(256);
    Imf::FrameBuffer fb;
    fb.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(stored.data()), 4, 64));
    in.setFrameBuffer(fb);
    in.readPixels(0, 15);
    float lowest = 0;
    for (float v : stored) lowest = std::min(lowest, v);
    ASSERT_LT(lowest, 0.0f);
    ASSERT_GT(lowest, -1e-3f);
  }
  DepthImage raw;
  DepthFileInfo info;
  ASSERT_TRUE(read(path, raw, info));
  EXPECT_TRUE(info.lossy);
  EXPECT_TRUE(info.storedAsHalf);
  EXPECT_EQ(info.compression, "B44");
  EXPECT_GT(info.lossyNoiseTexels, 0u);
  EXPECT_LT(info.lossyNoiseWorst, 0.0f);
  EXPECT_GE(info.lossyNoiseWorst, -kLossyDepthNoise);
  for (std::uint32_t t : raw.texels) EXPECT_GE(std::bit_cast<float>(t), 0.0f);
}

TEST_F(ForeignExr, SaoAttributesWithoutVersionAreListed) {
  const Camera cam = perspectiveCamera(1.0, 6, 4, 0.1, 100.0, ClipDepth::ZeroToOne, false);
  ForeignDepth f = rampFile(6, 4);
  f.decorate = saoCamera(file("sample.exr"), cam, {6, 4}, false, "sao.version");
  const std::string path = file("noversion.exr");
  writeForeignDepth(path, f);
  DepthImage d;
  DepthFileInfo info;
  ASSERT_TRUE(read(path, d, info));
  EXPECT_FALSE(info.hasCamera);
  EXPECT_EQ(info.saoAttributes.size(), 11u);
  EXPECT_EQ(info.saoAttributes.front(), "sao.clipDepth");
}

}  // namespace
}  // namespace sao
