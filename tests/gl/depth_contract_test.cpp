// The depth-value contract (sao/image.h) on OpenGL. GL clamps D32F depth to [0, 1] on upload (NaN
// and -inf to 0, +inf to 1, -0.0 to +0.0), so a D32F texture can never hold NaN, infinities or
// values outside [0, 1]: uploadDepth refuses such images with checkDepthValues' message instead of
// a texel-mismatch count, and accepts -0.0, which gives the bits +0.0 gives. R32F linear z holds
// every bit pattern: its sky values (NaN payloads, +-Inf, -0.0, positive) give the bits +0.0 gives.
// csz level 0 is compared with the CPU reference bit for bit.
#include <bit>
#include <string>

#include "depth_contract.h"
#include "gl_support.h"
#include "image_compare.h"
#include "sao/cpu/reference.h"

namespace sao::gltest {
namespace {

struct Output {
  FloatImage csz0, ao;
};

class DepthContract : public GlTest {
 protected:
  Output render(const Camera& camera, const DepthImage& depth) {
    const GlDepth format = depth.format == DepthFormat::LinearZ ? GlDepth::R32F : GlDepth::D32F;
    const std::uint32_t texture = uploadDepth(depth, format);
    auto effect = makeEffect();
    Output r;
    if (!effect || !texture) return r;
    gl::Inputs in;
    in.depth = {texture, internalFormat(format)};
    const Status st = effect->render(camera, Settings{}, in);
    EXPECT_TRUE(st.ok()) << st.message;
    if (st) {
      r.csz0 = readTextureLevel(effect->texture(gen::ResourceId::csz), 0);
      r.ao = readTexture(effect->aoTexture(), 1);
    }
    effect.reset();
    deleteTexture(texture);
    return r;
  }
};

TEST_F(DepthContract, D32FCannotHoldBadDepthAndSaysWhy) {
  const Camera camera = test::contractCamera(true);
  const DepthImage depth = test::contractDepth(camera, DepthFormat::D32F);
  for (float v : test::badHardwareDepthValues())
    for (GlDepth format : {GlDepth::D32F, GlDepth::D32FS8}) {
      SCOPED_TRACE(std::string(toString(format)) + ", d = " + test::valueName(v));
      const DepthImage bad = test::planted(depth, v);
      std::uint32_t texture = 0;
      const Status st = gl::uploadDepth(bad, format, texture);
      EXPECT_EQ(st.code, StatusCode::InvalidInput);
      EXPECT_EQ(texture, 0u);
      EXPECT_EQ(st.message, std::string("a GL ") + toString(format) +
                                " texture clamps depth to [0, 1], so it cannot hold this image: " +
                                checkDepthValues(bad).message);
    }
}

TEST_F(DepthContract, MinusZeroIsZero) {
  test::expectMinusZeroIsZero([&](const Camera& c, const DepthImage& d) { return render(c, d); });
}

// uploadDepth checks that R32F holds every bit.
TEST_F(DepthContract, LinearZSkyValuesRoundTripAndAreSky) {
  test::expectLinearZSkyValuesAreSky([&](const Camera& c, const DepthImage& d) { return render(c, d); });
}

}  // namespace
}  // namespace sao::gltest
