// sao::core from a consumer's point of view: the header version equals the library's and the
// package's, settings parse and validate, a plan is made. It links sao::core alone (no OpenEXR,
// stb or graphics API); file I/O is io_main.cpp's.
#include <cstdio>
#include <numbers>
#include <string>

#include "sao/camera.h"
#include "sao/plan.h"
#include "sao/settings.h"
#include "sao/version.h"
#include "consumer_check.h"


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

  std::printf("sao::core: settings, plan (%zu passes): ok\n", plan.passes.size());
  return 0;
}
