// Fuzz target: the EXR loaders of sao::core (sao::readDepthExr and sao::readFloatExr), on the
// bytes written to a scratch file.
//
// Invariants: no crash, no exception, no sanitizer report (OpenEXR itself is Debian's build and is
// not instrumented, but its reads into our buffers and its exceptions are); an error is IoError or
// UnsupportedFormat, names the path and leaves the outputs untouched; a success gives an image
// whose texel count matches its extent (<= kMaxImageSide a side) and, with a camera, an extent of
// width + 2 guard by height + 2 guard and integer texels within their format.
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "sao/io.h"

namespace {

bool isFileError(sao::StatusCode c) { return c == sao::StatusCode::IoError || c == sao::StatusCode::UnsupportedFormat; }

void checkDepth(const std::string& path) {
  sao::DepthImage depth;
  depth.extent = {7, 7};
  sao::Camera camera;
  camera.metersToViewUnits = 42.0;
  bool hasCamera = true;
  const sao::Status st = sao::readDepthExr(path, depth, camera, hasCamera);
  if (!st) {
    SAO_FUZZ_CHECK(isFileError(st.code), "%s: %s", sao::toString(st.code), st.message.c_str());
    SAO_FUZZ_CHECK(st.message.find(path) != std::string::npos, "%s", st.message.c_str());
    SAO_FUZZ_CHECK(depth.extent == (sao::Extent{7, 7}) && depth.texels.empty() && hasCamera &&
                   camera.metersToViewUnits == 42.0, "outputs changed on error");
    return;
  }
  const sao::Extent e = depth.extent;
  SAO_FUZZ_CHECK(e.width >= 1 && e.height >= 1 && e.width <= sao::kMaxImageSide && e.height <= sao::kMaxImageSide);
  SAO_FUZZ_CHECK(depth.texels.size() == std::size_t(e.width) * e.height);
  if (hasCamera) {
    SAO_FUZZ_CHECK(std::uint64_t(e.width) == std::uint64_t(camera.width) + 2ull * camera.guardBand);
    SAO_FUZZ_CHECK(std::uint64_t(e.height) == std::uint64_t(camera.height) + 2ull * camera.guardBand);
    const std::uint32_t max = depth.format == sao::DepthFormat::D16   ? 0xffffu
                              : depth.format == sao::DepthFormat::D24 ? 0xffffffu
                                                                      : 0xffffffffu;
    for (std::uint32_t t : depth.texels) SAO_FUZZ_CHECK(t <= max);
  } else {
    SAO_FUZZ_CHECK(depth.format == sao::DepthFormat::D32F && camera.metersToViewUnits == 42.0);
  }
}

void checkFloat(const std::string& path) {
  sao::FloatImage image;
  std::vector<std::string> names{"sentinel"};
  const sao::Status st = sao::readFloatExr(path, image, names);
  if (!st) {
    SAO_FUZZ_CHECK(isFileError(st.code), "%s: %s", sao::toString(st.code), st.message.c_str());
    SAO_FUZZ_CHECK(image.data.empty() && names.size() == 1 && names[0] == "sentinel", "outputs changed on error");
    return;
  }
  SAO_FUZZ_CHECK(image.channels >= 1 && names.size() == image.channels);
  SAO_FUZZ_CHECK(image.data.size() == std::size_t(image.extent.width) * image.extent.height * image.channels);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = (sao::fuzz::scratchDir() / "input.exr").string();
  sao::fuzz::writeFile(path, data, size);
  checkDepth(path);
  checkFloat(path);
  return 0;
}
