// sao::io from a consumer's point of view: a depth EXR with its camera, a two-channel float EXR and
// an AO PNG written into a folder of our own and read back (the EXRs bit for bit, the PNG by its
// signature), a missing file and a NaN pixel refused with a message naming the problem.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>
#include <system_error>
#include <unistd.h>
#include <vector>

#include "sao/camera.h"
#include "sao/io.h"
#include "consumer_check.h"


namespace {

// Removes the folder on every way out of main.
struct TempDir {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("sao_consumer_io_" + std::to_string(getpid()));
  TempDir() { std::filesystem::create_directories(path); }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string file(const char* name) const { return (path / name).string(); }
};

}  // namespace

int main() {
  const TempDir dir;

  // A D24 depth image with its camera: 64x36 viewport, guard band 4.
  sao::Camera camera = sao::perspectiveCamera(std::numbers::pi / 3, 64, 36, 0.1, 100.0,
                                              sao::ClipDepth::ZeroToOne, true);
  camera.guardBand = 4;
  sao::DepthImage depth;
  depth.extent = {72, 44};
  depth.format = sao::DepthFormat::D24;
  for (std::uint32_t i = 0; i < 72u * 44u; ++i) depth.texels.push_back((i * 2654435761u) & 0xffffffu);
  CHECK(sao::writeDepthExr(dir.file("depth.exr"), depth, camera).ok());
  sao::DepthImage depthBack;
  sao::Camera cameraBack;
  bool hasCamera = false;
  CHECK(sao::readDepthExr(dir.file("depth.exr"), depthBack, cameraBack, hasCamera).ok());
  CHECK(hasCamera && depthBack.format == sao::DepthFormat::D24 && depthBack.extent == depth.extent);
  CHECK(depthBack.texels == depth.texels);
  CHECK(cameraBack.projection == camera.projection && cameraBack.reversedZ && cameraBack.guardBand == 4);

  // Two float channels, names kept in the order given (EXR itself sorts them).
  sao::FloatImage image({5, 3}, 2);
  for (std::size_t i = 0; i < image.data.size(); ++i) image.data[i] = float(i) * 0.37f - 1.0f;
  CHECK(sao::writeFloatExr(dir.file("float.exr"), image, {"z", "a"}).ok());
  sao::FloatImage imageBack;
  std::vector<std::string> names;
  CHECK(sao::readFloatExr(dir.file("float.exr"), imageBack, names).ok());
  CHECK(imageBack.extent == image.extent && imageBack.channels == 2);
  CHECK(std::memcmp(imageBack.data.data(), image.data.data(), image.data.size() * sizeof(float)) == 0);
  CHECK((names == std::vector<std::string>{"z", "a"}));

  // The AO PNG: written, and a PNG by its signature.
  sao::FloatImage ao({16, 8}, 1, 0.5f);
  CHECK(sao::writeAoPng(dir.file("ao.png"), ao).ok());
  std::ifstream png(dir.file("ao.png"), std::ios::binary);
  char signature[8] = {};
  CHECK(png.read(signature, 8) && std::memcmp(signature, "\x89PNG\r\n\x1a\n", 8) == 0);

  // Bad input: a missing file, a NaN pixel.
  const sao::Status missing = sao::readDepthExr(dir.file("none.exr"), depthBack, cameraBack, hasCamera);
  CHECK(missing.code == sao::StatusCode::IoError && missing.message.find("none.exr") != std::string::npos);
  ao.at(3, 2) = std::numeric_limits<float>::quiet_NaN();
  const sao::Status nan = sao::writeAoPng(dir.file("nan.png"), ao);
  CHECK(nan.code == sao::StatusCode::InvalidInput && nan.message.find("NaN") != std::string::npos);

  std::printf("sao::io: depth EXR (camera, D24 bits), float EXR (2 channels), AO PNG, 2 refusals: ok\n");
  return 0;
}
