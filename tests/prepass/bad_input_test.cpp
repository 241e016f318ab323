// Bad input gets a clear Status, leaves the result empty, and the prepass keeps working.
#include <cmath>
#include <limits>

#include "prepass_support.h"

#ifdef SAO_PREPASS_HAVE_GL
#include <epoxy/gl.h>
#endif

namespace sao::prepasstest {
namespace {

class BadInput : public PrepassTest, public ::testing::WithParamInterface<std::string> {
 protected:
  prepass::Prepass& prepass() { return backend(GetParam()); }
  const LoadedScene& scene() { return loadScene("crease"); }
  Camera camera(std::uint32_t w = 64, std::uint32_t h = 36, std::uint32_t guard = 0) {
    return scenes::makeCamera(scene().scene.views.front(), w, h, INFINITY, ClipDepth::ZeroToOne, true, guard);
  }
  // Renders, expects `code` and a message naming the problem, an empty result, and that the next
  // good call still works.
  void expectError(const scenes::Mesh& mesh, const scenes::View& view, const Camera& cam,
                   const prepass::PrepassOptions& options, StatusCode code, const char* words) {
    prepass::PrepassResult out;
    out.depth.texels.assign(3, 7u);  // stale content must go
    const Status s = prepass().render(mesh, view, cam, options, out);
    EXPECT_EQ(s.code, code) << s.message;
    EXPECT_NE(s.message.find(words), std::string::npos) << s.message;
    EXPECT_EQ(s.message.rfind("prepass: ", 0), 0u) << s.message;
    EXPECT_TRUE(out.depth.texels.empty() && out.position.data.empty() && out.depth2.texels.empty());
    prepass::PrepassResult good;
    const Status ok = prepass().render(scene().scene.mesh, scene().scene.views.front(), camera(), {}, good);
    EXPECT_TRUE(ok) << ok.message;
    EXPECT_EQ(good.depth.texels.size(), 64u * 36u);
  }
};

TEST_P(BadInput, Meshes) {
  const scenes::View& view = scene().scene.views.front();
  const prepass::PrepassOptions options;
  scenes::Mesh empty;
  expectError(empty, view, camera(), options, StatusCode::InvalidInput, "no triangles");
  scenes::Mesh m = scene().scene.mesh;
  m.indices.pop_back();
  expectError(m, view, camera(), options, StatusCode::InvalidInput, "multiple of 3");
  m = scene().scene.mesh;
  m.indices[4] = std::uint32_t(m.positions.size());
  expectError(m, view, camera(), options, StatusCode::InvalidInput, "out of range");
  m = scene().scene.mesh;
  m.positions[2].y = std::numeric_limits<float>::quiet_NaN();
  expectError(m, view, camera(), options, StatusCode::InvalidInput, "not finite");
}

TEST_P(BadInput, SizesAndLimits) {
  const scenes::Mesh& mesh = scene().scene.mesh;
  const scenes::View& view = scene().scene.views.front();
  expectError(mesh, view, camera(0, 36), {}, StatusCode::InvalidExtent, "0x36");
  expectError(mesh, view, camera(64, 0), {}, StatusCode::InvalidExtent, "64x0");
  expectError(mesh, view, camera(64, 36, 0x80000000u), {}, StatusCode::InvalidExtent, "too large");
  std::uint32_t limit = 0;
#ifdef SAO_PREPASS_HAVE_GL
  if (GetParam() == "gl") {
    GLint t = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &t);
    limit = std::uint32_t(t);
  }
#endif
#ifdef SAO_PREPASS_HAVE_VULKAN
  if (GetParam() == "vulkan") limit = vkPrepass().context().properties().limits.maxImageDimension2D;
#endif
  ASSERT_GT(limit, 0u);
  // One texel beyond the device's limit, through the guard band.
  expectError(mesh, view, camera(limit - 15, 36, 8), {}, StatusCode::InvalidExtent, "at most");
}

TEST_P(BadInput, FormatsAndOptions) {
  const scenes::Mesh& mesh = scene().scene.mesh;
  const scenes::View& view = scene().scene.views.front();
  prepass::PrepassOptions options;
  options.format = DepthFormat::LinearZ;
  expectError(mesh, view, camera(), options, StatusCode::UnsupportedFormat, "LinearZ");
  options.format = static_cast<DepthFormat>(42);
  expectError(mesh, view, camera(), options, StatusCode::UnsupportedFormat, "unknown depth format");
  for (double sep : {0.0, -0.5, std::numeric_limits<double>::quiet_NaN(), double(INFINITY)}) {
    options = {};
    options.secondLayer = true;
    options.minSeparation = sep;
    expectError(mesh, view, camera(), options, StatusCode::InvalidInput, "minSeparation");
  }
  options = {};
  options.minSeparation = -1.0;  // ignored without a second layer
  prepass::PrepassResult r;
  EXPECT_TRUE(prepass().render(mesh, view, camera(), options, r));
#ifdef SAO_PREPASS_HAVE_VULKAN
  if (GetParam() == "vulkan") {
    // What the device offers decides; D24 (X8_D24_UNORM_PACK32) is optional in Vulkan.
    for (DepthFormat f : {DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F}) {
      const Status s = vkPrepass().checkFormat(f, true);
      EXPECT_TRUE(s.ok() || s.code == StatusCode::UnsupportedFormat) << s.message;
      std::printf("vulkan %s: %s\n", toString(f), s.ok() ? "supported" : s.message.c_str());
    }
    EXPECT_EQ(vkPrepass().checkFormat(DepthFormat::LinearZ, false).code, StatusCode::UnsupportedFormat);
  }
#endif
}

TEST_P(BadInput, Cameras) {
  const scenes::Mesh& mesh = scene().scene.mesh;
  scenes::View view = scene().scene.views.front();
  Camera c = camera();
  c.projection[0] = std::numeric_limits<double>::quiet_NaN();
  expectError(mesh, view, c, {}, StatusCode::InvalidCamera, "non-finite");
  c = camera();
  c.metersToViewUnits = 0;
  expectError(mesh, view, c, {}, StatusCode::InvalidCamera, "metersToViewUnits");
  scenes::View degenerate = view;
  degenerate.target = degenerate.eye;
  expectError(mesh, degenerate, camera(), {}, StatusCode::InvalidCamera, "view");
  degenerate = view;
  degenerate.eye.x = INFINITY;
  expectError(mesh, degenerate, camera(), {}, StatusCode::InvalidCamera, "not finite");
  const Camera glClip = scenes::makeCamera(view, 64, 36, 100.0, ClipDepth::NegativeOneToOne, false, 0);
  if (prepass().supportsClip(ClipDepth::NegativeOneToOne)) {
    prepass::PrepassResult r;
    EXPECT_TRUE(prepass().render(mesh, view, glClip, {}, r));
  } else {
    expectError(mesh, view, glClip, {}, StatusCode::InvalidCamera, "NegativeOneToOne");
  }
}

GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(BadInput);  // a build without GL and Vulkan
INSTANTIATE_TEST_SUITE_P(Backends, BadInput, ::testing::ValuesIn(backendNames()),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace sao::prepasstest
