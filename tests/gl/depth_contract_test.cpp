// The depth-value contract on OpenGL, what only GL has: gl::uploadDepth refuses D32F / D32FS8
// images a GL texture cannot hold (GL clamps depth to [0, 1]) without making a texture. The
// refusal's message, -0.0 and linear-z sky values on both APIs: tests/executors/depth_contract_test.cpp.
#include <string>

#include "depth_contract.h"
#include "gl_support.h"

namespace sao::gltest {
namespace {

class DepthContract : public GlTest {};

TEST_F(DepthContract, RefusedD32FUploadMakesNoTexture) {
  const DepthImage depth = test::contractDepth(test::contractCamera(true), DepthFormat::D32F);
  for (float v : test::badHardwareDepthValues())
    for (GlDepth format : {GlDepth::D32F, GlDepth::D32FS8}) {
      SCOPED_TRACE(std::string(toString(format)) + ", d = " + test::valueName(v));
      std::uint32_t texture = 0;
      EXPECT_EQ(gl::uploadDepth(test::planted(depth, v), format, texture).code, StatusCode::InvalidInput);
      EXPECT_EQ(texture, 0u);
    }
}

}  // namespace
}  // namespace sao::gltest
