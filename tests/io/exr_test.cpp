// writeDepthExr / readDepthExr / writeFloatExr / readFloatExr: exact round trips for every depth
// format and camera convention, the file layout (attributes, row order), foreign files, and every
// way a file can be bad.
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
#include <ImfStringVectorAttribute.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "sao/io.h"
#include "temp_dir.h"

namespace sao {

// Readable names of parameterised tests in ctest.
void PrintTo(DepthFormat f, std::ostream* os) { *os << toString(f); }

namespace {

namespace fs = std::filesystem;
// Tests of this file that need nothing but a temporary directory.
class ExrFile : public test::TempDirTest {};

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---- fixtures -------------------------------------------------------------------------------------

enum class CameraCase { PerspectiveGl, PerspectiveInfiniteReversed, OrthographicReversed };

const char* name(CameraCase c) {
  switch (c) {
    case CameraCase::PerspectiveGl: return "PerspectiveGl";
    case CameraCase::PerspectiveInfiniteReversed: return "PerspectiveInfiniteReversed";
    case CameraCase::OrthographicReversed: return "OrthographicReversed";
  }
  return "?";
}

const char* name(DepthFormat f) {
  switch (f) {
    case DepthFormat::D16: return "D16";
    case DepthFormat::D24: return "D24";
    case DepthFormat::D32F: return "D32F";
    case DepthFormat::LinearZ: return "LinearZ";
  }
  return "?";
}

void PrintTo(CameraCase c, std::ostream* os) { *os << name(c); }

Camera makeCamera(CameraCase c, std::uint32_t w = 37, std::uint32_t h = 23, std::uint32_t guard = 4) {
  Camera cam;
  switch (c) {
    case CameraCase::PerspectiveGl:
      cam = perspectiveCamera(1.1, w, h, 0.1, 250.0, ClipDepth::NegativeOneToOne, false);
      break;
    case CameraCase::PerspectiveInfiniteReversed:
      cam = perspectiveCamera(0.7, w, h, 0.05, kInf, ClipDepth::ZeroToOne, true);
      cam.flipY = true;
      cam.metersToViewUnits = 100.0 / 3.0;
      break;
    case CameraCase::OrthographicReversed:
      cam = orthographicCamera(12.5, w, h, 0.5, 80.0, ClipDepth::ZeroToOne, true);
      cam.metersToViewUnits = 0.3048;
      break;
  }
  cam.guardBand = guard;
  return cam;
}

DepthImage makeDepth(DepthFormat format, const Camera& cam, std::uint32_t seed) {
  DepthImage d;
  d.format = format;
  d.extent = {cam.width + 2 * cam.guardBand, cam.height + 2 * cam.guardBand};
  d.texels.resize(std::size_t(d.extent.width) * d.extent.height);
  std::mt19937 rng(seed);
  std::vector<std::uint32_t> specials;
  switch (format) {
    case DepthFormat::D16:
      specials = {0, 0xffff, 1, 0xfffe, 0x8000};
      for (auto& t : d.texels) t = rng() & 0xffffu;
      break;
    case DepthFormat::D24:
      specials = {0, 0xffffff, 1, 0xfffffe, 0x800000, 0xfffff0};
      for (auto& t : d.texels) t = rng() & 0xffffffu;
      break;
    case DepthFormat::D32F:
      specials = {std::bit_cast<std::uint32_t>(0.0f), std::bit_cast<std::uint32_t>(1.0f), 0x80000000u /* -0 */,
                  0x00000001u /* smallest denormal */, std::bit_cast<std::uint32_t>(std::nextafter(1.0f, 0.0f))};
      for (auto& t : d.texels) t = std::bit_cast<std::uint32_t>(std::uniform_real_distribution<float>(0.0f, 1.0f)(rng));
      break;
    case DepthFormat::LinearZ:
      specials = {0xff800000u /* -inf */, 0x7f800000u /* +inf */, 0x7fc00000u /* NaN */, 0x7fc12345u /* NaN payload */,
                  0x80000000u, std::bit_cast<std::uint32_t>(-std::numeric_limits<float>::max())};
      for (auto& t : d.texels)
        t = std::bit_cast<std::uint32_t>(std::uniform_real_distribution<float>(-1000.0f, -0.01f)(rng));
      break;
  }
  for (std::size_t i = 0; i < specials.size() && i * 7 < d.texels.size(); ++i) d.texels[i * 7] = specials[i];
  return d;
}

void expectSameCamera(const Camera& a, const Camera& b) {
  EXPECT_EQ(0, std::memcmp(a.projection.data(), b.projection.data(), sizeof(double) * 16));
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.clipDepth, b.clipDepth);
  EXPECT_EQ(a.reversedZ, b.reversedZ);
  EXPECT_EQ(a.infiniteFar, b.infiniteFar);
  EXPECT_EQ(a.flipY, b.flipY);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a.metersToViewUnits), std::bit_cast<std::uint64_t>(b.metersToViewUnits));
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.guardBand, b.guardBand);
}

// A camera nobody would write: a read that fails or finds no camera must leave it alone.
Camera sentinelCamera() {
  Camera c;
  c.projection.fill(7.0);
  c.metersToViewUnits = 42.0;
  c.width = 3;
  return c;
}

// ---- raw OpenEXR access ---------------------------------------------------------------------------

struct RawExr {
  Imf::Header header;
  int width = 0, height = 0;
  std::vector<float> top;  // one channel, file order: the top scanline first
};

RawExr readRaw(const std::string& path, const std::string& channel) {
  Imf::InputFile in(path.c_str());
  RawExr r;
  r.header = in.header();
  const Imath::Box2i dw = r.header.dataWindow();
  r.width = dw.max.x - dw.min.x + 1;
  r.height = dw.max.y - dw.min.y + 1;
  r.top.resize(std::size_t(r.width) * r.height);
  Imf::FrameBuffer fb;
  fb.insert(channel, Imf::Slice::Make(Imf::FLOAT, r.top.data(), dw));
  in.setFrameBuffer(fb);
  in.readPixels(dw.min.y, dw.max.y);
  return r;
}

// Copies a single-channel "Z" file, letting the test change the header and the pixels.
void rewrite(const std::string& src, const std::string& dst, const std::function<void(Imf::Header&)>& header,
             const std::function<void(std::vector<float>&)>& pixels = {}) {
  RawExr r = readRaw(src, "Z");
  header(r.header);
  if (pixels) pixels(r.top);
  Imf::OutputFile out(dst.c_str(), r.header);
  Imf::FrameBuffer fb;
  fb.insert("Z", Imf::Slice::Make(Imf::FLOAT, r.top.data(), r.header.dataWindow()));
  out.setFrameBuffer(fb);
  out.writePixels(r.height);
}

// Header::erase of OpenEXR 3.1 leaks the attribute; copy every other attribute into a new header.
void eraseAttribute(Imf::Header& h, const char* name) {
  Imf::Header out;
  for (auto it = h.begin(); it != h.end(); ++it)
    if (std::string(it.name()) != name) out.insert(it.name(), it.attribute());
  h = out;
}

using test::readBytes;
using test::writeBytes;

// Asserts a failed read with the given code, a message naming the path and `problem`, and the
// outputs untouched.
void expectReadFails(const std::string& path, StatusCode code, const std::string& problem) {
  DepthImage depth;
  depth.extent = {1, 1};
  depth.texels = {12345};
  Camera cam = sentinelCamera();
  bool hasCamera = true;
  const Status s = readDepthExr(path, depth, cam, hasCamera);
  EXPECT_EQ(s.code, code) << toString(s.code) << ": " << s.message;
  EXPECT_NE(s.message.find(path), std::string::npos) << s.message;
  EXPECT_NE(s.message.find(problem), std::string::npos) << "expected \"" << problem << "\" in: " << s.message;
  EXPECT_EQ(depth.texels, std::vector<std::uint32_t>{12345});
  EXPECT_EQ(cam.metersToViewUnits, 42.0);
  EXPECT_TRUE(hasCamera);
}

// ---- round trips ----------------------------------------------------------------------------------

class DepthRoundTrip : public test::TempDirTest, public ::testing::WithParamInterface<std::tuple<DepthFormat, CameraCase>> {};

TEST_P(DepthRoundTrip, TexelsAndCameraAreIdentical) {
  const auto [format, cameraCase] = GetParam();
  const Camera cam = makeCamera(cameraCase);
  const DepthImage depth = makeDepth(format, cam, 17u + unsigned(format) * 3 + unsigned(cameraCase));
  const std::string path = file("depth.exr");
  ASSERT_TRUE(writeDepthExr(path, depth, cam)) << writeDepthExr(path, depth, cam).message;

  DepthImage back;
  Camera camBack = sentinelCamera();
  bool hasCamera = false;
  const Status s = readDepthExr(path, back, camBack, hasCamera);
  ASSERT_TRUE(s) << s.message;
  EXPECT_TRUE(hasCamera);
  EXPECT_EQ(back.format, format);
  EXPECT_EQ(back.extent, depth.extent);
  ASSERT_EQ(back.texels.size(), depth.texels.size());
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < depth.texels.size(); ++i)
    if (back.texels[i] != depth.texels[i] && ++mismatches <= 5)
      ADD_FAILURE() << "texel " << i << ": wrote 0x" << std::hex << depth.texels[i] << ", read 0x" << back.texels[i];
  EXPECT_EQ(mismatches, 0u);
  expectSameCamera(camBack, cam);
  if (cameraCase == CameraCase::PerspectiveInfiniteReversed) {
    EXPECT_TRUE(camBack.infiniteFar);
    DepthModel model;
    EXPECT_TRUE(analyze(camBack, model)) << "the camera read back is still a valid infinite projection";
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllFormatsAndCameras, DepthRoundTrip,
    ::testing::Combine(::testing::Values(DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F, DepthFormat::LinearZ),
                       ::testing::Values(CameraCase::PerspectiveGl, CameraCase::PerspectiveInfiniteReversed,
                                         CameraCase::OrthographicReversed)),
    [](const auto& info) {
      return std::string(name(std::get<0>(info.param))) + "_" + name(std::get<1>(info.param));
    });

// Every integer value of D16 and D24 survives the trip through float.
class ExhaustiveIntegerDepth : public test::TempDirTest {
 protected:
  void check(DepthFormat format, std::uint32_t side) {
    Camera cam = makeCamera(CameraCase::PerspectiveGl, side, side, 0);
    DepthImage depth;
    depth.format = format;
    depth.extent = {side, side};
    depth.texels.resize(std::size_t(side) * side);
    for (std::size_t i = 0; i < depth.texels.size(); ++i) depth.texels[i] = std::uint32_t(i);
    const std::string path = file("all.exr");
    ASSERT_TRUE(writeDepthExr(path, depth, cam));
    DepthImage back;
    bool hasCamera = false;
    ASSERT_TRUE(readDepthExr(path, back, cam, hasCamera));
    ASSERT_EQ(back.texels.size(), depth.texels.size());
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < depth.texels.size(); ++i)
      if (back.texels[i] != depth.texels[i]) ++mismatches;
    EXPECT_EQ(mismatches, 0u);
  }
};

TEST_F(ExhaustiveIntegerDepth, AllD16Values) { check(DepthFormat::D16, 256); }
TEST_F(ExhaustiveIntegerDepth, AllD24Values) { check(DepthFormat::D24, 4096); }

TEST_F(ExrFile, DepthFileLayout) {
  const Camera cam = makeCamera(CameraCase::PerspectiveInfiniteReversed, 5, 3, 1);
  const DepthImage depth = makeDepth(DepthFormat::D16, cam, 3);
  const std::string path = file("layout.exr");
  ASSERT_TRUE(writeDepthExr(path, depth, cam));

  const RawExr raw = readRaw(path, "Z");
  const Imf::ChannelList& channels = raw.header.channels();
  ASSERT_NE(channels.findChannel("Z"), nullptr);
  EXPECT_EQ(channels.findChannel("Z")->type, Imf::FLOAT);
  int channelCount = 0;
  for (auto it = channels.begin(); it != channels.end(); ++it) ++channelCount;
  EXPECT_EQ(channelCount, 1);
  EXPECT_EQ(raw.header.dataWindow(), Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(6, 4)));
  EXPECT_EQ(raw.header.compression(), Imf::ZIP_COMPRESSION);

  // Row order: the file's top scanline is image row height-1; D16 is stored as v / 65535.
  for (int y = 0; y < raw.height; ++y)
    for (int x = 0; x < raw.width; ++x) {
      const std::uint32_t t = depth.texels[std::size_t(raw.height - 1 - y) * raw.width + x];
      EXPECT_EQ(raw.top[std::size_t(y) * raw.width + x], static_cast<float>(double(t) / 65535.0)) << x << "," << y;
    }

  const auto* version = raw.header.findTypedAttribute<Imf::IntAttribute>("sao.version");
  ASSERT_NE(version, nullptr);
  EXPECT_EQ(version->value(), 1);
  const auto* proj = raw.header.findTypedAttribute<Imf::M44dAttribute>("sao.projection");
  ASSERT_NE(proj, nullptr);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_EQ(proj->value()[c][r], cam.projection[std::size_t(c * 4 + r)]);
  EXPECT_EQ(proj->value()[2][3], -1.0) << "perspective: element (row 3, column 2) is -1";
  auto str = [&](const char* n) {
    const auto* a = raw.header.findTypedAttribute<Imf::StringAttribute>(n);
    return a ? a->value() : std::string("<missing>");
  };
  auto integer = [&](const char* n) {
    const auto* a = raw.header.findTypedAttribute<Imf::IntAttribute>(n);
    return a ? a->value() : -999;
  };
  EXPECT_EQ(str("sao.kind"), "perspective");
  EXPECT_EQ(str("sao.clipDepth"), "zeroToOne");
  EXPECT_EQ(str("sao.depthFormat"), "D16");
  EXPECT_EQ(integer("sao.reversedZ"), 1);
  EXPECT_EQ(integer("sao.infiniteFar"), 1);
  EXPECT_EQ(integer("sao.flipY"), 1);
  EXPECT_EQ(integer("sao.width"), 5);
  EXPECT_EQ(integer("sao.height"), 3);
  EXPECT_EQ(integer("sao.guardBand"), 1);
  const auto* meters = raw.header.findTypedAttribute<Imf::DoubleAttribute>("sao.metersToViewUnits");
  ASSERT_NE(meters, nullptr);
  EXPECT_EQ(meters->value(), cam.metersToViewUnits);
}

// ---- foreign files --------------------------------------------------------------------------------

// Writes a flat EXR with the given channels (all of `type`), data window origin `origin`; pixel
// (x, y) of channel c (file order, top scanline first) is value(c, x, y).
void writeForeign(const std::string& path, const std::vector<std::string>& names, Imf::PixelType type, int w, int h,
                  Imath::V2i origin, const std::function<float(std::size_t, int, int)>& value) {
  const Imath::Box2i dw(origin, origin + Imath::V2i(w - 1, h - 1));
  Imf::Header header(Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(w - 1, h - 1)), dw);
  std::vector<std::vector<float>> f(names.size(), std::vector<float>(std::size_t(w) * h));
  std::vector<std::vector<half>> hv(names.size(), std::vector<half>(std::size_t(w) * h));
  std::vector<std::vector<unsigned>> u(names.size(), std::vector<unsigned>(std::size_t(w) * h));
  Imf::FrameBuffer fb;
  for (std::size_t c = 0; c < names.size(); ++c) {
    header.channels().insert(names[c], Imf::Channel(type));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t i = std::size_t(y) * w + x;
        f[c][i] = value(c, x, y);
        hv[c][i] = half(f[c][i]);
        u[c][i] = unsigned(f[c][i]);
      }
    const void* ptr = type == Imf::FLOAT ? static_cast<const void*>(f[c].data())
                      : type == Imf::HALF ? static_cast<const void*>(hv[c].data())
                                          : static_cast<const void*>(u[c].data());
    fb.insert(names[c], Imf::Slice::Make(type, ptr, dw));
  }
  Imf::OutputFile out(path.c_str(), header);
  out.setFrameBuffer(fb);
  out.writePixels(h);
}

TEST_F(ExrFile, ForeignHalfFileWithOffsetDataWindowReadsAsD32F) {
  const std::string path = file("foreign.exr");
  const int w = 6, h = 4;
  auto value = [](std::size_t, int x, int y) { return 0.125f * float(x) + 0.0078125f * float(y); };
  writeForeign(path, {"depth"}, Imf::HALF, w, h, Imath::V2i(10, -20), value);

  DepthImage depth;
  Camera cam = sentinelCamera();
  bool hasCamera = true;
  const Status s = readDepthExr(path, depth, cam, hasCamera);
  ASSERT_TRUE(s) << s.message;
  EXPECT_FALSE(hasCamera);
  EXPECT_EQ(cam.metersToViewUnits, 42.0) << "camera untouched";
  EXPECT_EQ(depth.format, DepthFormat::D32F);
  EXPECT_EQ(depth.extent, (Extent{std::uint32_t(w), std::uint32_t(h)}));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      EXPECT_EQ(depth.value(std::uint32_t(x), std::uint32_t(h - 1 - y)), double(float(half(value(0, x, y)))))
          << "file pixel " << x << "," << y << " is image row " << h - 1 - y;
}

TEST_F(ExrFile, ForeignFilePrefersZAmongSeveralChannels) {
  const std::string path = file("za.exr");
  writeForeign(path, {"A", "B", "Z"}, Imf::FLOAT, 3, 2, Imath::V2i(0, 0),
               [](std::size_t c, int x, int y) { return float(c * 100 + std::size_t(y) * 10 + std::size_t(x)); });
  DepthImage depth;
  Camera cam = sentinelCamera();
  bool hasCamera = true;
  ASSERT_TRUE(readDepthExr(path, depth, cam, hasCamera));
  EXPECT_FALSE(hasCamera);
  EXPECT_EQ(depth.value(2, 1), 202.0);  // Z (index 2), file row 0 = image row 1
  EXPECT_EQ(depth.value(0, 0), 210.0);
}

TEST_F(ExrFile, ForeignSingleRChannelIsRead) {
  const std::string path = file("r.exr");
  writeForeign(path, {"R"}, Imf::FLOAT, 2, 2, Imath::V2i(0, 0), [](std::size_t, int x, int y) { return float(x + 2 * y); });
  DepthImage depth;
  Camera cam;
  bool hasCamera = true;
  ASSERT_TRUE(readDepthExr(path, depth, cam, hasCamera));
  EXPECT_EQ(depth.value(1, 1), 1.0);
  EXPECT_EQ(depth.value(1, 0), 3.0);
}

TEST_F(ExrFile, FloatExrWithZReadsAsForeignDepth) {
  FloatImage img({4, 3}, 1);
  for (std::uint32_t y = 0; y < 3; ++y)
    for (std::uint32_t x = 0; x < 4; ++x) img.at(x, y) = float(x) * 0.25f + float(y);
  const std::string path = file("z.exr");
  ASSERT_TRUE(writeFloatExr(path, img, {"Z"}));
  DepthImage depth;
  Camera cam;
  bool hasCamera = true;
  ASSERT_TRUE(readDepthExr(path, depth, cam, hasCamera));
  EXPECT_FALSE(hasCamera);
  for (std::uint32_t y = 0; y < 3; ++y)
    for (std::uint32_t x = 0; x < 4; ++x) EXPECT_EQ(depth.value(x, y), double(img.at(x, y)));
}

TEST_F(ExrFile, ThreeChannelsWithoutZAreRejected) {
  FloatImage rgb({4, 4}, 3, 0.5f);
  const std::string path = file("rgb.exr");
  ASSERT_TRUE(writeFloatExr(path, rgb, {"R", "G", "B"}));
  expectReadFails(path, StatusCode::IoError, "3 channels (B, G, R)");
}

TEST_F(ExrFile, UintChannelIsUnsupported) {
  const std::string path = file("uint.exr");
  writeForeign(path, {"Z"}, Imf::UINT, 2, 2, Imath::V2i(0, 0), [](std::size_t, int, int) { return 3.0f; });
  expectReadFails(path, StatusCode::UnsupportedFormat, "UINT");
}

// ---- bad files ------------------------------------------------------------------------------------

TEST_F(ExrFile, MissingFile) { expectReadFails(file("nothing-here.exr"), StatusCode::IoError, "no such file"); }

TEST_F(ExrFile, Directory) {
  fs::create_directory(file("adir.exr"));
  expectReadFails(file("adir.exr"), StatusCode::IoError, "is a directory");
  const Camera cam = makeCamera(CameraCase::PerspectiveGl, 2, 2, 0);
  const Status s = writeDepthExr(file("adir.exr"), makeDepth(DepthFormat::D32F, cam, 1), cam);
  EXPECT_EQ(s.code, StatusCode::IoError);
  EXPECT_NE(s.message.find("is a directory"), std::string::npos) << s.message;
  EXPECT_TRUE(fs::is_directory(file("adir.exr")));
}

TEST_F(ExrFile, RandomBytes) {
  std::vector<char> bytes(4096);
  std::mt19937 rng(5);
  for (char& b : bytes) b = char(rng());
  writeBytes(file("random.exr"), bytes);
  expectReadFails(file("random.exr"), StatusCode::IoError, "not an OpenEXR file");
  writeBytes(file("empty.exr"), {});
  expectReadFails(file("empty.exr"), StatusCode::IoError, "not an OpenEXR file");
}

TEST_F(ExrFile, MagicNumberThenGarbage) {
  std::vector<char> bytes(4096);
  std::mt19937 rng(9);
  for (char& b : bytes) b = char(rng());
  const unsigned char magic[] = {0x76, 0x2f, 0x31, 0x01, 0x02, 0, 0, 0};
  std::memcpy(bytes.data(), magic, sizeof magic);
  writeBytes(file("garbage.exr"), bytes);
  expectReadFails(file("garbage.exr"), StatusCode::IoError, "corrupt header");
}

class BadDepthFile : public test::TempDirTest {
 protected:
  void SetUp() override {
    test::TempDirTest::SetUp();
    cam_ = makeCamera(CameraCase::PerspectiveGl, 120, 90, 4);
    depth_ = makeDepth(DepthFormat::D32F, cam_, 11);
    ASSERT_TRUE(writeDepthExr(good_ = file("good.exr"), depth_, cam_));
  }
  Camera cam_;
  DepthImage depth_;
  std::string good_;
};

TEST_F(BadDepthFile, TruncatedToHalf) {
  const std::string path = file("half.exr");
  fs::copy_file(good_, path);
  fs::resize_file(path, fs::file_size(path) / 2);
  expectReadFails(path, StatusCode::IoError, "is truncated or corrupt: the chunk of rows 48..63 cannot be located");
}

TEST_F(BadDepthFile, TruncatedInsideTheHeader) {
  for (std::uintmax_t size : {4u, 8u, 40u, 200u}) {
    SCOPED_TRACE(size);
    const std::string path = file("cut" + std::to_string(size) + ".exr");
    fs::copy_file(good_, path);
    fs::resize_file(path, size);
    expectReadFails(path, StatusCode::IoError, path);
  }
}

TEST_F(BadDepthFile, CorruptPixelDataNeverCrashes) {
  const std::vector<char> bytes = readBytes(good_);
  ASSERT_GT(bytes.size(), 4000u);
  for (unsigned seed = 0; seed < 40; ++seed) {
    std::vector<char> bad = bytes;
    std::mt19937 rng(seed);
    // Past the header (under 1 KiB here): the line offsets and the compressed scanlines.
    std::uniform_int_distribution<std::size_t> where(bytes.size() / 4, bytes.size() - 1);
    for (int i = 0; i < 1 + int(seed % 8); ++i) bad[where(rng)] = char(rng());
    const std::string path = file("corrupt.exr");
    writeBytes(path, bad);
    DepthImage depth;
    Camera cam;
    bool hasCamera = false;
    const Status s = readDepthExr(path, depth, cam, hasCamera);
    if (!s) {
      EXPECT_EQ(s.code, StatusCode::IoError) << s.message;
      EXPECT_NE(s.message.find(path), std::string::npos) << s.message;
    }
  }
}

struct HeaderCase {
  const char* name;
  std::function<void(Imf::Header&)> mutate;
  StatusCode code;
  const char* problem;
};

void PrintTo(const HeaderCase& c, std::ostream* os) { *os << c.name; }

class BadHeader : public BadDepthFile, public ::testing::WithParamInterface<HeaderCase> {};

TEST_P(BadHeader, IsRejected) {
  const std::string path = file("bad.exr");
  rewrite(good_, path, GetParam().mutate);
  expectReadFails(path, GetParam().code, GetParam().problem);
}

Imath::M44d projectionWith(int c, int r, double v) {
  const Camera cam = perspectiveCamera(1.1, 120, 90, 0.1, 250.0, ClipDepth::NegativeOneToOne, false);
  Imath::M44d m;
  for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = cam.projection[std::size_t(i)];
  m[c][r] = v;
  return m;
}

INSTANTIATE_TEST_SUITE_P(
    AllProblems, BadHeader,
    ::testing::Values(
        HeaderCase{"NaNInProjection",
                   [](Imf::Header& h) { h.insert("sao.projection", Imf::M44dAttribute(projectionWith(2, 2, kNaN))); },
                   StatusCode::IoError, "sao.projection element 10 (row 2, column 2) is not finite"},
        HeaderCase{"InfInProjection",
                   [](Imf::Header& h) { h.insert("sao.projection", Imf::M44dAttribute(projectionWith(0, 0, -kInf))); },
                   StatusCode::IoError, "sao.projection element 0"},
        HeaderCase{"InfiniteMetersToViewUnits",
                   [](Imf::Header& h) { h.insert("sao.metersToViewUnits", Imf::DoubleAttribute(kInf)); },
                   StatusCode::IoError, "sao.metersToViewUnits is not finite"},
        HeaderCase{"NaNMetersToViewUnits",
                   [](Imf::Header& h) { h.insert("sao.metersToViewUnits", Imf::DoubleAttribute(kNaN)); },
                   StatusCode::IoError, "sao.metersToViewUnits is not finite"},
        HeaderCase{"UnknownDepthFormat",
                   [](Imf::Header& h) { h.insert("sao.depthFormat", Imf::StringAttribute("D15")); },
                   StatusCode::UnsupportedFormat, "sao.depthFormat is \"D15\""},
        HeaderCase{"UnknownKind", [](Imf::Header& h) { h.insert("sao.kind", Imf::StringAttribute("fisheye")); },
                   StatusCode::UnsupportedFormat, "sao.kind is \"fisheye\""},
        HeaderCase{"UnknownClipDepth",
                   [](Imf::Header& h) { h.insert("sao.clipDepth", Imf::StringAttribute("minusOneToOne")); },
                   StatusCode::UnsupportedFormat, "sao.clipDepth is \"minusOneToOne\""},
        HeaderCase{"WidthMismatch", [](Imf::Header& h) { h.insert("sao.width", Imf::IntAttribute(121)); },
                   StatusCode::IoError, "depth image is 128x98, but the camera's 121x90 viewport"},
        HeaderCase{"GuardBandMismatch", [](Imf::Header& h) { h.insert("sao.guardBand", Imf::IntAttribute(0)); },
                   StatusCode::IoError, "with a guard band of 0 needs 120x90"},
        HeaderCase{"NegativeHeight", [](Imf::Header& h) { h.insert("sao.height", Imf::IntAttribute(-90)); },
                   StatusCode::IoError, "sao.height is -90"},
        HeaderCase{"WidthOfWrongType", [](Imf::Header& h) {
                     eraseAttribute(h, "sao.width");
                     h.insert("sao.width", Imf::StringAttribute("120"));
                   },
                   StatusCode::IoError, "sao.width is of type string, expected int"},
        HeaderCase{"FlagOutOfRange", [](Imf::Header& h) { h.insert("sao.reversedZ", Imf::IntAttribute(2)); },
                   StatusCode::IoError, "sao.reversedZ is 2; expected 0 or 1"},
        HeaderCase{"MissingKind", [](Imf::Header& h) { eraseAttribute(h, "sao.kind"); }, StatusCode::IoError,
                   "has sao.version but no sao.kind attribute"},
        HeaderCase{"MissingProjection", [](Imf::Header& h) { eraseAttribute(h, "sao.projection"); }, StatusCode::IoError,
                   "no sao.projection"},
        HeaderCase{"FutureVersion", [](Imf::Header& h) { h.insert("sao.version", Imf::IntAttribute(2)); },
                   StatusCode::UnsupportedFormat, "sao.version is 2"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST_F(BadDepthFile, WithoutVersionTheFileIsForeign) {
  const std::string path = file("noversion.exr");
  rewrite(good_, path, [](Imf::Header& h) { eraseAttribute(h, "sao.version"); });
  DepthImage depth;
  Camera cam = sentinelCamera();
  bool hasCamera = true;
  ASSERT_TRUE(readDepthExr(path, depth, cam, hasCamera));
  EXPECT_FALSE(hasCamera);
  EXPECT_EQ(cam.metersToViewUnits, 42.0);
  EXPECT_EQ(depth.texels, depth_.texels);  // D32F either way
}

TEST_F(ExrFile, IntegerDepthOutOfRangeIsRejected) {
  const Camera cam = makeCamera(CameraCase::PerspectiveGl, 8, 8, 0);
  const std::string good = file("d16.exr"), bad = file("d16bad.exr"), nan = file("d16nan.exr");
  ASSERT_TRUE(writeDepthExr(good, makeDepth(DepthFormat::D16, cam, 2), cam));
  rewrite(good, bad, [](Imf::Header&) {}, [](std::vector<float>& p) { p[3] = 1.5f; });
  expectReadFails(bad, StatusCode::IoError, "Z at (3, 7) is 1.5");
  rewrite(good, nan, [](Imf::Header&) {}, [](std::vector<float>& p) { p[9] = std::numeric_limits<float>::quiet_NaN(); });
  expectReadFails(nan, StatusCode::IoError, "not a normalised D16 depth");
}

// ---- writer checks --------------------------------------------------------------------------------

TEST_F(ExrFile, WriterRejectsBadInput) {
  const Camera cam = makeCamera(CameraCase::PerspectiveGl, 8, 6, 1);
  const std::string path = file("w.exr");
  auto expectFails = [&](const DepthImage& d, const Camera& c, StatusCode code, const std::string& problem) {
    const Status s = writeDepthExr(path, d, c);
    EXPECT_EQ(s.code, code) << s.message;
    EXPECT_NE(s.message.find(path), std::string::npos) << s.message;
    EXPECT_NE(s.message.find(problem), std::string::npos) << "expected \"" << problem << "\" in: " << s.message;
    EXPECT_FALSE(fs::exists(path));
  };
  const DepthImage good = makeDepth(DepthFormat::D16, cam, 1);

  expectFails(DepthImage{}, cam, StatusCode::InvalidExtent, "both sides must be > 0");
  DepthImage d = good;
  d.texels.pop_back();
  expectFails(d, cam, StatusCode::InvalidInput, "has 79 texels, its extent needs 80");
  d = good;
  d.texels[10] = 0x10000;
  expectFails(d, cam, StatusCode::InvalidInput, "texel (0, 1) is 65536, above the largest D16 value 65535");
  d = good;
  d.format = DepthFormat::D24;
  d.texels[11] = 0x1000000;
  expectFails(d, cam, StatusCode::InvalidInput, "above the largest D24 value");
  Camera c = cam;
  c.projection[5] = kNaN;
  expectFails(good, c, StatusCode::InvalidInput, "projection element 5 is not finite");
  c = cam;
  c.metersToViewUnits = -kInf;
  expectFails(good, c, StatusCode::InvalidInput, "metersToViewUnits is not finite");
  c = cam;
  c.guardBand = 0;
  expectFails(good, c, StatusCode::InvalidInput, "depth image is 10x8, but the camera's 8x6 viewport");

  const std::string nowhere = file("no/such/dir/w.exr");
  const Status s = writeDepthExr(nowhere, good, cam);
  EXPECT_EQ(s.code, StatusCode::IoError);
  EXPECT_NE(s.message.find(nowhere), std::string::npos) << s.message;
}

// ---- float images ---------------------------------------------------------------------------------

TEST_F(ExrFile, FloatExrRoundTripKeepsBitsNamesAndOrder) {
  FloatImage img({7, 5}, 3);
  std::mt19937 rng(4);
  for (float& v : img.data) v = std::uniform_real_distribution<float>(-3.0f, 3.0f)(rng);
  img.data[0] = std::numeric_limits<float>::quiet_NaN();
  img.data[1] = std::numeric_limits<float>::infinity();
  img.data[2] = -0.0f;
  img.data[4] = std::numeric_limits<float>::denorm_min();
  const std::vector<std::string> names = {"z", "ao", "normal.x"};  // not alphabetical
  const std::string path = file("float.exr");
  ASSERT_TRUE(writeFloatExr(path, img, names));

  FloatImage back;
  std::vector<std::string> namesBack;
  const Status s = readFloatExr(path, back, namesBack);
  ASSERT_TRUE(s) << s.message;
  EXPECT_EQ(namesBack, names);
  EXPECT_EQ(back.extent, img.extent);
  EXPECT_EQ(back.channels, 3u);
  ASSERT_EQ(back.data.size(), img.data.size());
  EXPECT_EQ(0, std::memcmp(back.data.data(), img.data.data(), img.data.size() * sizeof(float)));

  // Same row order as the depth file: the top scanline is image row height-1.
  const RawExr raw = readRaw(path, "ao");
  for (int y = 0; y < raw.height; ++y)
    for (int x = 0; x < raw.width; ++x)
      EXPECT_EQ(raw.top[std::size_t(y) * raw.width + x], img.at(std::uint32_t(x), std::uint32_t(raw.height - 1 - y), 1));
}

TEST_F(ExrFile, FloatExrWriterRejectsBadNames) {
  const FloatImage img({2, 2}, 2);
  const std::string path = file("f.exr");
  auto expectFails = [&](const std::vector<std::string>& names, const std::string& problem) {
    const Status s = writeFloatExr(path, img, names);
    EXPECT_EQ(s.code, StatusCode::InvalidInput);
    EXPECT_NE(s.message.find(problem), std::string::npos) << s.message;
    EXPECT_FALSE(fs::exists(path));
  };
  expectFails({"a"}, "1 channel names for an image with 2 channels");
  expectFails({"a", "a"}, "\"a\" used twice");
  expectFails({"a", ""}, "empty channel name");
  FloatImage short_ = img;
  short_.data.pop_back();
  EXPECT_EQ(writeFloatExr(path, short_, {"a", "b"}).code, StatusCode::InvalidInput);
  EXPECT_EQ(writeFloatExr(path, FloatImage{}, {"a"}).code, StatusCode::InvalidExtent);
}

TEST_F(ExrFile, ReadFloatExrErrors) {
  FloatImage img;
  std::vector<std::string> names;
  Status s = readFloatExr(file("missing.exr"), img, names);
  EXPECT_EQ(s.code, StatusCode::IoError);
  EXPECT_NE(s.message.find("no such file"), std::string::npos) << s.message;
  s = readFloatExr(tmp_.path().string(), img, names);
  EXPECT_EQ(s.code, StatusCode::IoError);
  EXPECT_NE(s.message.find("is a directory"), std::string::npos) << s.message;
}

}  // namespace
}  // namespace sao
