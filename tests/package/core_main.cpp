// sao::core from a consumer's point of view: the header version equals the library's and the
// package's, settings parse and validate, a plan is made, and the shader files an engine's own
// renderer would load (sao_SHADER_DIR) hold every compiled pass variant, byte for byte the SPIR-V the
// library embeds, beside their description. It links sao::core alone (no OpenEXR, stb or graphics
// API); file I/O is io_main.cpp's.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

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

  const std::filesystem::path shaders = SAO_SHADER_DIR;
  std::size_t files = 0;
  for (const sao::gen::PassInfo& pass : sao::gen::passes())
    for (const sao::gen::PassVariantInfo& variant : pass.compiled) {
      std::ifstream in(shaders / (std::string(variant.fileStem) + ".spv"), std::ios::binary);
      const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      const auto embedded = sao::gen::spirvModule(variant.spirvBlob);
      CHECK(bytes.size() == embedded.size_bytes());
      CHECK(std::memcmp(bytes.data(), embedded.data(), bytes.size()) == 0);
      CHECK(std::filesystem::exists(shaders / (std::string(variant.fileStem) + ".glsl")));
      ++files;
    }
  CHECK(std::filesystem::exists(shaders / "sao_passes.json"));

  std::printf("sao::core: settings, plan (%zu passes), %zu pass variants' shader files: ok\n", plan.passes.size(), files);
  return 0;
}
