// sao::core from a consumer's point of view: the header version equals the library's and the
// package's, settings parse and validate, a plan is made, a depth EXR round-trips.
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <system_error>
#include <unistd.h>

#include "sao/camera.h"
#include "sao/io.h"
#include "sao/plan.h"
#include "sao/settings.h"
#include "sao/version.h"

#define CHECK(cond)                                                     \
  do {                                                                  \
    if (!(cond)) {                                                      \
      std::fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
      return 1;                                                         \
    }                                                                   \
  } while (0)

int main() {
  const std::string header = std::to_string(SAO_VERSION_MAJOR) + "." + std::to_string(SAO_VERSION_MINOR) + "." +
                             std::to_string(SAO_VERSION_PATCH);
  std::printf("header %s, package %s, library 0x%06x\n", header.c_str(), SAO_PACKAGE_VERSION, sao::libraryVersion());
  CHECK(sao::libraryVersion() == SAO_VERSION);
  CHECK(header == SAO_PACKAGE_VERSION);

  sao::Settings settings;
  CHECK(sao::validate(settings).ok());
  CHECK(sao::setFromAssignment(settings, "radius=0.5").ok());
  const sao::Status bad = sao::setFromAssignment(settings, "radius=nan");
  CHECK(bad.code == sao::StatusCode::InvalidSetting && !bad.message.empty());

  sao::Camera camera = sao::perspectiveCamera(std::numbers::pi / 3, 64, 36, 0.1, 100.0,
                                              sao::ClipDepth::NegativeOneToOne, false);
  camera.guardBand = 4;
  sao::Plan plan;
  const sao::Status planned = sao::plan(settings, camera, {}, plan);
  CHECK(planned.ok());
  CHECK(plan.inputExtent == (sao::Extent{72, 44}));

  sao::DepthImage depth;
  depth.extent = plan.inputExtent;
  depth.format = sao::DepthFormat::D16;
  depth.texels.assign(std::size_t(72) * 44, 0xffffu);
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("sao_consumer_" + std::to_string(getpid()) + ".exr");
  CHECK(sao::writeDepthExr(path.string(), depth, camera).ok());
  sao::DepthImage back;
  sao::Camera backCamera;
  bool hasCamera = false;
  const sao::Status read = sao::readDepthExr(path.string(), back, backCamera, hasCamera);
  std::error_code ec;
  std::filesystem::remove(path, ec);
  CHECK(read.ok() && hasCamera && back.texels == depth.texels && backCamera.guardBand == 4);
  std::printf("sao::core: settings, plan (%zu passes), EXR round trip: ok\n", plan.passes.size());
  return 0;
}
