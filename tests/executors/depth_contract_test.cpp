// The depth-value contract (sao/image.h) on each API, values planted in a crease (tests/cpu/depth_contract.h):
// -0.0 gives the bits of +0.0, and so do R32F linear-z sky values (NaN payloads, +-Inf, -0.0, positive); D32F /
// D32FS8 depth that is NaN, +-Inf or outside [0, 1] is sky like the clear value on Vulkan, and refused by GL
// and GLES, which clamp it at upload (checkDepthValues' message). csz level 0 is bit for bit the CPU reference's.
#include "depth_contract.h"
#include "harness.h"

namespace sao::exectest {
namespace {

struct Rendered {
  Status status;
  FloatImage csz0, ao;  // empty after a failure
};

// One frame with the default settings; a failure fails the test unless `mayFail`.
Rendered render(Executor& e, const Camera& camera, const DepthImage& depth, Depth format, bool mayFail = false) {
  Frame f;
  f.camera = camera;
  f.depth = &depth;
  f.format = format;
  Rendered r;
  r.status = e.render(f);
  EXPECT_TRUE(mayFail || r.status.ok()) << r.status.message;
  if (r.status) r.csz0 = e.image(gen::ResourceId::csz, 0), r.ao = e.output();
  return r;
}

using DepthContract = ApiTest;

TEST_P(DepthContract, BadHardwareDepthIsSkyLikeTheClearValue) {
  auto e = make();
  for (bool reversedZ : {false, true})
    for (Depth format : {Depth::D32F, Depth::D32FS8}) {
      const Camera camera = test::contractCamera(reversedZ);
      const DepthImage depth = test::contractDepth(camera, DepthFormat::D32F);
      const Rendered clear = render(*e, camera, test::planted(depth, float(test::clearDepth(camera))), format);
      ASSERT_FALSE(clear.ao.data.empty());
      for (float v : test::badHardwareDepthValues()) {
        SCOPED_TRACE(std::string(reversedZ ? "reversed-Z " : "standard ") + toString(format) + ", d = " +
                     test::valueName(v));
        const DepthImage bad = test::planted(depth, v);
        const bool clamps = api() == Api::Gl || api() == Api::Gles;
        const Rendered r = render(*e, camera, bad, format, /*mayFail=*/clamps);
        if (clamps) {  // a GL (or ES) D32F texture cannot hold the image: refused, saying why
          EXPECT_EQ(r.status.code, StatusCode::InvalidInput);
          EXPECT_EQ(r.status.message, std::string("a GL ") + toString(format) +
                                          " texture clamps depth to [0, 1], so it cannot hold this image: " +
                                          checkDepthValues(bad).message);
          continue;
        }
        EXPECT_EQ(test::plantedNotSky(r.csz0), 0u);
        EXPECT_TRUE(test::sameBits(r.csz0, clear.csz0));
        EXPECT_TRUE(test::sameBits(r.ao, clear.ao));
        EXPECT_TRUE(test::sameBits(r.csz0, test::cpuCsz0(camera, bad)));
      }
    }
}

TEST_P(DepthContract, MinusZeroIsZero) {
  auto e = make();
  test::expectMinusZeroIsZero([&](const Camera& c, const DepthImage& d) { return render(*e, c, d, Depth::D32F); });
}

// R32F holds every bit: GL's and GLES's uploads read it back to check, Vulkan's is a buffer copy.
TEST_P(DepthContract, LinearZSkyValuesRoundTripAndAreSky) {
  auto e = make();
  test::expectLinearZSkyValuesAreSky([&](const Camera& c, const DepthImage& d) { return render(*e, c, d, Depth::R32F); });
}
SAO_INSTANTIATE_APIS(DepthContract);

}  // namespace
}  // namespace sao::exectest
