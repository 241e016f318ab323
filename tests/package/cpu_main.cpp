// sao::cpu from a consumer's point of view: the installed CPU reference (the oracle an engine tests
// its own port against) runs the default settings on a linear-z floor with a step, gives A in
// [0, 1] with the step's foot darker than the open floor, and refuses a missing depth by name.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <string>

#include "sao/cpu/reference.h"
#include "consumer_check.h"

int main() {
  const sao::Camera camera =
      sao::perspectiveCamera(std::numbers::pi / 3, 96, 64, 0.1, 100.0, sao::ClipDepth::ZeroToOne, false);
  // Linear camera-space z (negative in front): a floor 4 m away whose right half steps 0.3 m nearer.
  sao::DepthImage depth;
  depth.extent = {96, 64};
  depth.format = sao::DepthFormat::LinearZ;
  for (std::uint32_t y = 0; y < 64; ++y)
    for (std::uint32_t x = 0; x < 96; ++x) {
      const float z = x < 48 ? -4.0f : -3.7f;
      std::uint32_t bits;
      std::memcpy(&bits, &z, sizeof bits);
      depth.texels.push_back(bits);
    }
  sao::cpu::Inputs inputs;
  inputs.depth = &depth;
  sao::cpu::Options options;
  options.precision = sao::cpu::Precision::Float;
  sao::cpu::Result result;
  const sao::Status st = sao::cpu::run(sao::Settings{}, camera, inputs, options, result);
  if (!st) std::fprintf(stderr, "sao::cpu::run: %s\n", st.message.c_str());
  CHECK(st.ok());
  CHECK(result.ao.extent == (sao::Extent{96, 64}) && result.ao.channels == 1);
  for (float a : result.ao.data) CHECK(std::isfinite(a) && a >= 0.0f && a <= 1.0f);
  const float foot = result.ao.data[32 * 96 + 46], open = result.ao.data[32 * 96 + 8];
  std::printf("sao::cpu: %zu passes, A at the step's foot %.4f, on the open floor %.4f\n", result.plan.passes.size(),
              foot, open);
  CHECK(foot < open);

  sao::cpu::Inputs none;
  const sao::Status missing = sao::cpu::run(sao::Settings{}, camera, none, options, result);
  CHECK(!missing.ok() && missing.message.find("depth") != std::string::npos);
  return 0;
}
