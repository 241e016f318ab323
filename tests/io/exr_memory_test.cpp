// Peak memory of the EXR readers on hostile files, counted by this program's own operator new
// (OpenEXR's core library allocates through sao's budgeted allocator, which uses operator new, so
// every byte the read holds is counted; no timer and no RSS, so the verdict is the same on every
// machine and under the sanitizers). The limit of the issue that found the 447-byte file: < 64 MiB.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

#include "sao/io.h"

namespace {

// Live and peak bytes of operator new, each block tagged with its size in front.
std::atomic<std::uint64_t> gLive{0};
std::atomic<std::uint64_t> gPeak{0};
constexpr std::size_t kTag = 16;

void* countedAlloc(std::size_t n) {
  auto* p = static_cast<unsigned char*>(std::malloc(n + kTag));
  if (!p) return nullptr;
  std::memcpy(p, &n, sizeof n);
  const std::uint64_t live = gLive.fetch_add(n) + n;
  std::uint64_t peak = gPeak.load();
  while (live > peak && !gPeak.compare_exchange_weak(peak, live)) {
  }
  return p + kTag;
}

void countedFree(void* q) {
  if (!q) return;
  auto* p = static_cast<unsigned char*>(q) - kTag;
  std::size_t n = 0;
  std::memcpy(&n, p, sizeof n);
  gLive.fetch_sub(n);
  std::free(p);
}

}  // namespace

void* operator new(std::size_t n) {
  if (void* p = countedAlloc(n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return countedAlloc(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return countedAlloc(n); }
void operator delete(void* p) noexcept { countedFree(p); }
void operator delete[](void* p) noexcept { countedFree(p); }
void operator delete(void* p, std::size_t) noexcept { countedFree(p); }
void operator delete[](void* p, std::size_t) noexcept { countedFree(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { countedFree(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { countedFree(p); }

namespace sao {
namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kLimit = std::uint64_t(64) << 20;

struct Peak {
  Status status;
  std::uint64_t bytes = 0;  // above what was live before the read
};

template <class Read>
Peak measure(Read&& read) {
  const std::uint64_t before = gLive.load();
  gPeak.store(before);
  Peak p;
  p.status = read();
  p.bytes = gPeak.load() - before;
  return p;
}

// Every committed exr_depth fuzz regression, the 447-byte file of the issue among them: both
// readers refuse it, naming the file, with under 64 MiB at the peak.
TEST(ExrMemory, FuzzRegressionsAreRefusedWithBoundedMemory) {
  const fs::path dir = fs::path(SAO_SOURCE_DIR) / "tests/fuzz/regressions/exr_depth";
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".exr") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 6u) << dir;
  bool sawTheIssuesFile = false;
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.filename().string());
    sawTheIssuesFile |= fs::file_size(f) == 447;
    const Peak depth = measure([&] {
      DepthImage d;
      Camera c;
      bool hasCamera = false;
      return readDepthExr(f.string(), d, c, hasCamera);
    });
    const Peak image = measure([&] {
      FloatImage img;
      std::vector<std::string> names;
      return readFloatExr(f.string(), img, names);
    });
    std::printf("%-48s %4ju bytes  depth: peak %9ju bytes  %s\n%-48s %4s        float: peak %9ju bytes  %s\n",
                f.filename().c_str(), std::uintmax_t(fs::file_size(f)), std::uintmax_t(depth.bytes),
                depth.status.message.c_str(), "", "", std::uintmax_t(image.bytes), image.status.message.c_str());
    EXPECT_FALSE(depth.status.ok());
    EXPECT_FALSE(image.status.ok());
    EXPECT_NE(depth.status.message.find(f.string()), std::string::npos) << depth.status.message;
    EXPECT_LT(depth.bytes, kLimit);
    EXPECT_LT(image.bytes, kLimit);
  }
  EXPECT_TRUE(sawTheIssuesFile) << "the 447-byte regression is committed";
}

// A well-formed file holds what it declares: the count sees the image itself (so the counter
// counts), and little beyond it.
TEST(ExrMemory, AGoodFileCostsAboutItsImage) {
  const fs::path path = fs::temp_directory_path() / ("sao_exr_memory_" + std::to_string(::getpid()) + ".exr");
  const Camera cam = perspectiveCamera(1.0, 1024, 512, 0.1, 50.0, ClipDepth::ZeroToOne, true);
  DepthImage d;
  d.extent = {1024, 512};
  d.texels.assign(std::size_t(1024) * 512, encodeDepth(DepthFormat::D32F, 0.25));
  ASSERT_TRUE(writeDepthExr(path.string(), d, cam));
  const std::uint64_t imageBytes = std::uint64_t(1024) * 512 * 4;
  const Peak p = measure([&] {
    DepthImage out;
    Camera c;
    bool hasCamera = false;
    return readDepthExr(path.string(), out, c, hasCamera);
  });
  fs::remove(path);
  ASSERT_TRUE(p.status) << p.status.message;
  std::printf("1024x512 D32F file: peak %ju bytes (%.2f x the image)\n", std::uintmax_t(p.bytes),
              double(p.bytes) / double(imageBytes));
  EXPECT_GE(p.bytes, imageBytes);
  EXPECT_LT(p.bytes, 4 * imageBytes);
}

}  // namespace
}  // namespace sao
