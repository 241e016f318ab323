// The EXR loaders on hostile files (docs/ROBUSTNESS.md), beyond exr_test.cpp's bad-file cases:
// FIFOs, devices and symlink loops; headers that declare more than the file holds (a 2 GiB string
// attribute, a 16384x16384 data window in a few hundred bytes, tiles of 100000 pixels, chunks that
// would decode to gigabytes) - found by fuzz_exr_depth: OpenEXR sizes its allocations from the
// header before it checks them against the file; random damage anywhere in the header. Every case
// returns an error that names the file, quickly and without a large allocation.
#include <sys/resource.h>
#include <sys/stat.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "sao/io.h"
#include "temp_dir.h"

namespace sao {
namespace {

namespace fs = std::filesystem;

using test::readBytes;
using test::writeBytes;

// Peak RSS of the process so far, bytes.
std::uint64_t peakRss() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return std::uint64_t(u.ru_maxrss) * 1024;
}

// Both readers fail with IoError naming the path and `problem` (their memory is bounded by
// exr_memory_test.cpp; no timing here, a loaded machine must not change the verdict).
void expectBothFail(const std::string& path, const std::string& problem) {
  DepthImage depth;
  Camera camera;
  bool hasCamera = false;
  const Status d = readDepthExr(path, depth, camera, hasCamera);
  EXPECT_EQ(d.code, StatusCode::IoError) << toString(d.code) << ": " << d.message;
  EXPECT_NE(d.message.find(path), std::string::npos) << d.message;
  EXPECT_NE(d.message.find(problem), std::string::npos) << "expected \"" << problem << "\" in: " << d.message;
  FloatImage image;
  std::vector<std::string> names;
  const Status f = readFloatExr(path, image, names);
  EXPECT_EQ(f.code, StatusCode::IoError) << f.message;
  EXPECT_NE(f.message.find(problem), std::string::npos) << "expected \"" << problem << "\" in: " << f.message;
}

// Little-endian builders for hand-made headers.
struct Bytes {
  std::vector<char> b;
  Bytes& raw(const void* p, std::size_t n) {
    b.insert(b.end(), static_cast<const char*>(p), static_cast<const char*>(p) + n);
    return *this;
  }
  Bytes& str(const std::string& s) { return raw(s.c_str(), s.size() + 1); }
  Bytes& i32(std::int32_t v) {
    unsigned char x[4] = {std::uint8_t(v), std::uint8_t(v >> 8), std::uint8_t(v >> 16), std::uint8_t(v >> 24)};
    return raw(x, 4);
  }
  Bytes& u8(std::uint8_t v) { return raw(&v, 1); }
  Bytes& f32(float v) { return raw(&v, 4); }
  Bytes& attr(const std::string& name, const std::string& type, const Bytes& value) {
    str(name).str(type).i32(std::int32_t(value.b.size()));
    return raw(value.b.data(), value.b.size());
  }
};

// A scanline EXR header (magic, version 2) with `channels` FLOAT channels, the data window
// (0,0)-(w-1,h-1), the given compression, and `tail` bytes of zeros after it.
std::vector<char> handMadeExr(int channels, int w, int h, std::uint8_t compression, std::size_t tail,
                              bool tiled = false, std::uint32_t tile = 0) {
  Bytes chlist;
  for (int c = 0; c < channels; ++c) {
    char name[16];  // room for any int: -Wformat-truncation cannot bound c
    std::snprintf(name, sizeof name, "c%03d", c);
    chlist.str(name).i32(2).u8(0).u8(0).u8(0).u8(0).i32(1).i32(1);  // FLOAT, linear 0, sampling 1x1
  }
  chlist.u8(0);
  Bytes window;
  window.i32(0).i32(0).i32(w - 1).i32(h - 1);
  Bytes e;
  const unsigned char magic[] = {0x76, 0x2f, 0x31, 0x01};
  e.raw(magic, 4).u8(2).u8(tiled ? 0x02 : 0).u8(0).u8(0);
  e.attr("channels", "chlist", chlist);
  e.attr("compression", "compression", Bytes{}.u8(compression));
  e.attr("dataWindow", "box2i", window);
  e.attr("displayWindow", "box2i", window);
  e.attr("lineOrder", "lineOrder", Bytes{}.u8(0));
  e.attr("pixelAspectRatio", "float", Bytes{}.f32(1.0f));
  e.attr("screenWindowCenter", "v2f", Bytes{}.f32(0).f32(0));
  e.attr("screenWindowWidth", "float", Bytes{}.f32(1.0f));
  if (tiled) e.attr("tiles", "tiledesc", Bytes{}.i32(std::int32_t(tile)).i32(std::int32_t(tile)).u8(0));
  e.u8(0);
  e.b.resize(e.b.size() + tail, 0);
  return e.b;
}

class ExrRobustness : public test::TempDirTest {};

TEST_F(ExrRobustness, FifoDeviceAndSymlinkLoop) {
  const std::string fifo = file("fifo.exr");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  expectBothFail(fifo, "is not a regular file");  // would block in open() until a writer came
  expectBothFail("/dev/zero", "is not a regular file");
  const std::string loop = file("loop.exr");
  fs::create_symlink(loop, loop);
  DepthImage depth;
  Camera camera;
  bool hasCamera = false;
  const Status st = readDepthExr(loop, depth, camera, hasCamera);
  EXPECT_EQ(st.code, StatusCode::IoError) << st.message;
  EXPECT_NE(st.message.find(loop), std::string::npos) << st.message;
}

// A string attribute that declares 2 GiB in an 850-byte file: OpenEXR would allocate and clear it.
TEST_F(ExrRobustness, AttributeLargerThanTheFile) {
  const Camera cam = perspectiveCamera(1.0, 4, 2, 0.1, 50.0, ClipDepth::ZeroToOne, true);
  DepthImage d;
  d.extent = {4, 2};
  d.texels.assign(8, encodeDepth(DepthFormat::D32F, 0.5));
  const std::string good = file("good.exr"), bad = file("bad.exr");
  ASSERT_TRUE(writeDepthExr(good, d, cam).ok());
  std::vector<char> bytes = readBytes(good);
  const std::string key("sao.clipDepth\0string\0", 21);  // the attribute's name and type, each NUL-terminated
  const auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
  ASSERT_NE(at, bytes.end());
  const std::size_t size = std::size_t(at - bytes.begin()) + key.size();
  const std::uint64_t before = peakRss();
  for (std::int32_t declared : {0x7fffffff, 0x10000000, int(bytes.size())}) {
    std::vector<char> b = bytes;
    std::memcpy(&b[size], &declared, 4);
    writeBytes(bad, b);
    expectBothFail(bad, "corrupt header: Attribute 'sao.clipDepth', type 'string': Invalid size " +
                            std::to_string(declared));
  }
  EXPECT_LT(peakRss() - before, std::uint64_t(64) << 20) << "no allocation at the declared size";
}

TEST_F(ExrRobustness, DataWindowsBeyondTheFileOrTheLimit) {
  const std::uint64_t before = peakRss();
  writeBytes(file("huge.exr"), handMadeExr(1, 16384, 16384, 0, 64));
  expectBothFail(file("huge.exr"), "offset table alone (131072 bytes) exceeds the file's");
  writeBytes(file("wide.exr"), handMadeExr(1, 100001, 2, 0, 64));
  expectBothFail(file("wide.exr"), "data window is 100001x2; the largest side read is 16384");
  writeBytes(file("empty.exr"), handMadeExr(1, 0, 5, 0, 64));
  expectBothFail(file("empty.exr"), "corrupt header: Invalid");
  // 16384 x 256 lines (DWAB's chunk) x 200 FLOAT channels: a 3.3 GB decode buffer per chunk.
  writeBytes(file("channels.exr"), handMadeExr(200, 16384, 256, 9, 64));
  expectBothFail(file("channels.exr"), "one chunk would decode to");
  writeBytes(file("tiles.exr"), handMadeExr(1, 64, 64, 0, 64, true, 100000));
  expectBothFail(file("tiles.exr"), "tiles are 100000x100000");
  writeBytes(file("tinytiles.exr"), handMadeExr(1, 16384, 16384, 0, 64, true, 1));
  expectBothFail(file("tinytiles.exr"), "offset table alone");
  // Every side allowed, a complete offset table (8192 one-line chunks), too many pixels in all.
  writeBytes(file("pixels.exr"), handMadeExr(1, 16384, 8192, 0, 8 * 8192));
  expectBothFail(file("pixels.exr"), "data window is 16384x8192 = 134217728 pixels; the most read is 67108864");
  EXPECT_LT(peakRss() - before, std::uint64_t(64) << 20) << "no allocation at the declared sizes";
}

// A complete-looking 16384 x 16384 file (a valid offset table, 64 DWAB chunks of 4 garbage bytes):
// the first band fails to decode before the 1 GiB image is allocated.
TEST_F(ExrRobustness, HugeImageWithGarbageChunksFailsBeforeTheImageIsAllocated) {
  std::vector<char> bytes = handMadeExr(1, 16384, 16384, 9, 0);
  constexpr int kChunks = 64;  // 16384 lines / 256 lines a DWAB chunk
  const std::size_t table = bytes.size();
  bytes.resize(table + 8 * kChunks);
  for (int i = 0; i < kChunks; ++i) {
    const std::uint64_t offset = bytes.size();
    std::memcpy(&bytes[table + 8 * std::size_t(i)], &offset, 8);
    Bytes chunk;
    chunk.i32(i * 256).i32(4).i32(0x5a5a5a5a);
    bytes.insert(bytes.end(), chunk.b.begin(), chunk.b.end());
  }
  writeBytes(file("garbage_chunks.exr"), bytes);
  const std::uint64_t before = peakRss();
  DepthImage depth;
  Camera camera;
  bool hasCamera = false;
  const Status st = readDepthExr(file("garbage_chunks.exr"), depth, camera, hasCamera);
  EXPECT_EQ(st.code, StatusCode::IoError) << st.message;
  EXPECT_LT(peakRss() - before, std::uint64_t(256) << 20) << st.message;
  std::printf("%s (peak RSS +%llu MiB)\n", st.message.c_str(), (unsigned long long)((peakRss() - before) >> 20));
}

// Random damage in the header and the offset table of a real file: an error or a success, never
// a crash, a hang or a huge allocation (the sanitizer build runs this too).
TEST_F(ExrRobustness, CorruptHeadersNeverCrash) {
  const Camera cam = perspectiveCamera(1.0, 12, 8, 0.1, 50.0, ClipDepth::NegativeOneToOne, false);
  DepthImage d;
  d.extent = {12, 8};
  d.format = DepthFormat::D24;
  for (std::uint32_t i = 0; i < 96; ++i) d.texels.push_back(i * 9000);
  ASSERT_TRUE(writeDepthExr(file("good.exr"), d, cam).ok());
  const std::vector<char> bytes = readBytes(file("good.exr"));
  const std::uint64_t before = peakRss();
  int failures = 0, successes = 0;
  for (unsigned seed = 0; seed < 300; ++seed) {
    std::vector<char> b = bytes;
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::size_t> where(8, std::min<std::size_t>(b.size(), 1100) - 1);
    for (int i = 0; i < 1 + int(seed % 4); ++i) b[where(rng)] = char(rng());
    writeBytes(file("corrupt.exr"), b);
    DepthImage out;
    Camera c;
    bool hasCamera = false;
    const Status st = readDepthExr(file("corrupt.exr"), out, c, hasCamera);
    if (st) {
      ++successes;
      EXPECT_EQ(out.texels.size(), std::size_t(out.extent.width) * out.extent.height);
    } else {
      ++failures;
      EXPECT_TRUE(st.code == StatusCode::IoError || st.code == StatusCode::UnsupportedFormat) << st.message;
    }
  }
  std::printf("300 corrupted headers: %d read (damage in unused bytes), %d rejected\n", successes, failures);
  EXPECT_GT(failures, 100);
  EXPECT_LT(peakRss() - before, std::uint64_t(256) << 20);
}

}  // namespace
}  // namespace sao
