// The OpenGL backend against the CPU reference (sao::cpu, float mode) on analytic scenes:
// every preset x D16 / D24 / D32F x five scenes, a few more inputs and conventions, and the
// orientation of an asymmetric input. Final AO and raw (pre-blur) AO: at least 99.9% of the
// pixels within 2/255 and none beyond 4/255. Failing comparisons write actual / expected /
// difference images under tests/gl/failures in the build tree.
#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numbers>

#include "analytic_scenes.h"
#include "normal_encodings.h"
#include <ostream>

#include "gl_support.h"
#include "image_compare.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"

namespace sao::gltest {
namespace {

constexpr double kWithin = 2.0 / 255.0, kNever = 4.0 / 255.0;
constexpr std::uint32_t kWidth = 160, kHeight = 90, kGuard = 8;

struct Run {
  FloatImage ao, raw;
};

struct Inputs {
  const DepthImage* depth = nullptr;
  const DepthImage* depth2 = nullptr;
  const FloatImage* normals = nullptr;
  GlDepth format = GlDepth::D32F;
};

// One GL render and one CPU float render of the same inputs; compares final and raw AO (and the
// final AO with `alsoFinal` when given: another CPU result it must agree with).
void compareWithCpu(gl::Effect& effect, const Camera& cam, const Settings& settings, const Inputs& in,
                    const std::string& name, const FloatImage* alsoFinal = nullptr) {
  cpu::Result ref;
  cpu::Inputs ci;
  ci.depth = in.depth;
  ci.depth2 = in.depth2;
  ci.normals = in.normals;
  const Status cst = cpu::run(settings, cam, ci, cpu::Options{cpu::Precision::Float, 2}, ref);
  ASSERT_TRUE(cst.ok()) << cst.message;

  const GLuint depthTex = uploadDepth(*in.depth, in.format);
  const GLuint depth2Tex = in.depth2 ? uploadDepth(*in.depth2, in.format) : 0;
  const GLuint normalTex = in.normals ? uploadNormals(*in.normals) : 0;
  gl::Inputs gi;
  gi.depth = {depthTex, internalFormat(in.format)};
  gi.depth2 = {depth2Tex, depth2Tex ? internalFormat(in.format) : 0};
  gi.normals = normalTex;
  const Status st = effect.render(cam, settings, gi);
  ASSERT_TRUE(st.ok()) << st.message;
  EXPECT_EQ(effect.plan().cszLevels, ref.plan.cszLevels);
  EXPECT_EQ(effect.plan().passes.size(), ref.plan.passes.size());
  EXPECT_EQ(std::memcmp(&effect.params(), &ref.params, sizeof ref.params), 0) << "parameter blocks differ";
  const FloatImage ao = readTexture(effect.aoTexture(), 1);
  const FloatImage raw = readTexture(effect.texture(gen::ResourceId::ao_raw), 2);
  deleteTexture(depthTex);
  deleteTexture(depth2Tex);
  deleteTexture(normalTex);

  std::string noteFinal, noteRaw;
  const Agreement f = compare(ao, ref.ao, 0, kWithin, kNever, name + "_final", &noteFinal);
  const Agreement r = compare(raw, ref.aoRaw, 0, kWithin, kNever, name + "_raw", &noteRaw);
  double meanA = 0, minA = 1;
  std::size_t occluded = 0;
  for (float v : ref.ao.data) {
    meanA += v;
    minA = std::min(minA, double(v));
    occluded += v < 0.99f;
  }
  meanA /= double(ref.ao.data.size());
  std::printf("AGREEMENT %-30s final max %.4f/255 p99.9 %.4f/255 within2 %.4f | raw max %.4f/255 p99.9 %.4f/255 "
              "within2 %.4f | CPU A mean %.3f min %.3f, %.1f%% of pixels < 0.99\n",
              name.c_str(), f.maxAbs * 255, f.p999 * 255, f.fractionWithin, r.maxAbs * 255, r.p999 * 255,
              r.fractionWithin, meanA, minA, 100.0 * double(occluded) / double(ref.ao.data.size()));
  EXPECT_TRUE(acceptable(f)) << name << " final AO: max |diff| " << f.maxAbs * 255 << "/255, "
                             << f.fractionWithin * 100 << "% within 2/255, " << f.beyond << " beyond 4/255, "
                             << f.nonFinite << " non-finite; " << noteFinal;
  EXPECT_TRUE(acceptable(r)) << name << " raw AO: max |diff| " << r.maxAbs * 255 << "/255, "
                             << r.fractionWithin * 100 << "% within 2/255, " << r.beyond << " beyond 4/255, "
                             << r.nonFinite << " non-finite; " << noteRaw;
  if (alsoFinal != nullptr) {
    const Agreement a = compare(ao, *alsoFinal, 0, kWithin, kNever, name + "_also");
    std::printf("AGREEMENT %-30s against the camera-space normals' CPU result: final max %.4f/255 p99.9 %.4f/255\n",
                name.c_str(), a.maxAbs * 255, a.p999 * 255);
    EXPECT_TRUE(acceptable(a)) << name << " against the camera-space run: max " << a.maxAbs * 255 << "/255, p99.9 "
                               << a.p999 * 255 << "/255";
  }
  // The key (camera-space z) of the raw image is computed identically.
  std::size_t keyMismatch = 0;
  for (std::uint32_t y = 0; y < raw.extent.height; ++y)
    for (std::uint32_t x = 0; x < raw.extent.width; ++x)
      keyMismatch += std::fabs(raw.at(x, y, 1) - ref.aoRaw.at(x, y, 1)) > 1e-5f * std::fabs(ref.aoRaw.at(x, y, 1));
  EXPECT_EQ(keyMismatch, 0u) << name << ": raw keys (camera-space z) differ";
}

// ---- Five scenes x three depth formats, every preset in each.

struct MatrixCase {
  const char* scene;
  GlDepth format;
};
void PrintTo(const MatrixCase& c, std::ostream* os) { *os << std::string(c.scene) + "_" + toString(c.format); }


class Matrix : public GlTest, public ::testing::WithParamInterface<MatrixCase> {};

TEST_P(Matrix, EveryPresetMatchesTheCpuReference) {
  const MatrixCase mc = GetParam();
  const Camera cam = camera(kWidth, kHeight, kGuard);
  const DepthImage depth = test::renderDepth(sceneByName(mc.scene), cam, cpuFormat(mc.format));
  auto effect = makeEffect();
  for (const auto& p : presets()) {
    SCOPED_TRACE(std::string(p.name));
    compareWithCpu(*effect, cam, presetSettings(p.preset), {&depth, nullptr, nullptr, mc.format},
                   std::string(mc.scene) + "_" + std::string(p.name) + "_" + toString(mc.format));
  }
}

std::vector<MatrixCase> matrixCases() {
  std::vector<MatrixCase> v;
  for (const char* s : {"plane", "crease", "sphere", "stairs", "rods"})
    for (GlDepth f : {GlDepth::D16, GlDepth::D24, GlDepth::D32F}) v.push_back({s, f});
  return v;
}

INSTANTIATE_TEST_SUITE_P(ScenesFormats, Matrix, ::testing::ValuesIn(matrixCases()), [](const auto& info) {
  return std::string(info.param.scene) + "_" + toString(info.param.format);
});

// ---- More inputs and conventions (medium and reference presets).

class Variants : public GlTest {
 protected:
  // fadeEnd > 0: the presets with the distance fade from fadeStart to fadeEnd metres on.
  void check(const Camera& cam, GlDepth format, bool normals, bool twoLayer, const std::string& name,
             const char* sceneName = "sphere", float fadeStart = 0.0f, float fadeEnd = 0.0f) {
    const test::Scene scene = sceneByName(sceneName);
    const DepthImage depth = test::renderDepth(scene, cam, cpuFormat(format));
    const DepthImage depth2 = test::renderDepth(scene, cam, cpuFormat(format), 1);
    const FloatImage n = test::renderNormals(scene, cam);
    auto effect = makeEffect();
    Settings flat;  // the reference preset of 2026-12-03 (64 taps, 5-tap blur, full resolution)
    flat.samples = 64;
    flat.blur_radius = 2;
    flat.resolution_divisor = 1;
    flat.use_z_hierarchy = false;  // the Z_HIERARCHY=0 variant
    for (const auto& [label, base] : {std::pair{"medium", presetSettings(Preset::Medium)}, std::pair{"no_hierarchy", flat}}) {
      if (twoLayer && !base.use_z_hierarchy) continue;  // TWO_LAYER needs the z hierarchy
      SCOPED_TRACE(label);
      Settings settings = base;
      settings.fade_start = fadeStart;
      settings.fade_end = fadeEnd;
      compareWithCpu(*effect, cam, settings,
                     {&depth, twoLayer ? &depth2 : nullptr, normals ? &n : nullptr, format}, name + "_" + label);
    }
  }
};

TEST_F(Variants, Depth24Stencil8) { check(camera(kWidth, kHeight, kGuard), GlDepth::D24S8, false, false, "D24S8"); }
TEST_F(Variants, Depth32FStencil8) {
  check(camera(kWidth, kHeight, kGuard), GlDepth::D32FS8, false, false, "D32FS8");
}
TEST_F(Variants, LinearZ) { check(camera(kWidth, kHeight, kGuard), GlDepth::R32F, false, false, "R32F"); }
TEST_F(Variants, SuppliedNormals) { check(camera(kWidth, kHeight, kGuard), GlDepth::D32F, true, false, "normals"); }
TEST_F(Variants, TwoLayers) { check(camera(kWidth, kHeight, kGuard), GlDepth::D32F, false, true, "two_layer"); }
TEST_F(Variants, TwoLayersWithNormals) {
  check(camera(kWidth, kHeight, kGuard), GlDepth::D24, true, true, "two_layer_normals", "rods");
}
TEST_F(Variants, ReversedInfiniteZeroToOne) {
  Camera c = perspectiveCamera(std::numbers::pi / 3.0, kWidth, kHeight, 0.1, std::numeric_limits<double>::infinity(),
                               ClipDepth::ZeroToOne, true);
  c.guardBand = kGuard;
  check(c, GlDepth::D32F, false, false, "reversed_infinite", "stairs");
}
TEST_F(Variants, Orthographic) {
  Camera c = orthographicCamera(2.0, kWidth, kHeight, 0.1, 20.0, ClipDepth::NegativeOneToOne, false);
  c.guardBand = kGuard;
  check(c, GlDepth::D24, false, false, "ortho", "crease");
}
TEST_F(Variants, FlippedRows) {
  Camera c = camera(kWidth, kHeight, kGuard);
  c.flipY = true;
  check(c, GlDepth::D32F, false, false, "flipy", "stairs");
}
TEST_F(Variants, DistanceFade) {
  check(camera(kWidth, kHeight, kGuard), GlDepth::D24, false, false, "fade_3_6", "sphere", 3.0f, 6.0f);
  check(camera(kWidth, kHeight, kGuard), GlDepth::D32F, true, false, "fade_2_4_normals", "stairs", 2.0f, 4.0f);
}
TEST_F(Variants, OddSizeWithoutGuard) { check(camera(97, 61, 0), GlDepth::D24, false, false, "odd_97x61", "rods"); }

// ---- Normals in world space and octahedral (Camera::normalsEncoding): GL agrees with the CPU
// reference on the encoded input and with the CPU's result for the camera-space normals; a
// world-space encoding without a view rotation is refused.

TEST_F(GlTest, EncodedNormalsMatchTheCameraSpaceResult) {
  const Camera base = camera(kWidth, kHeight, kGuard);
  auto effect = makeEffect();
  for (const char* sceneName : {"stairs", "sphere"}) {
    const test::Scene scene = sceneByName(sceneName);
    const DepthImage depth = test::renderDepth(scene, base, cpuFormat(GlDepth::D32F));
    const FloatImage n = test::renderNormals(scene, base);
    cpu::Inputs ci;
    ci.depth = &depth;
    ci.normals = &n;
    cpu::Result cameraSpace;
    ASSERT_TRUE(cpu::run(presetSettings(Preset::Medium), base, ci, {cpu::Precision::Float, 2}, cameraSpace).ok());
    for (NormalsEncoding e :
         {NormalsEncoding::WorldXyz, NormalsEncoding::CameraOctahedral, NormalsEncoding::WorldOctahedral}) {
      Camera cam = base;
      cam.normalsEncoding = e;
      cam.viewRotation = test::viewRotation(0.7, -0.4, 0.25);
      const FloatImage encoded = test::encodeNormals(n, e, *cam.viewRotation);
      SCOPED_TRACE(int(e));
      compareWithCpu(*effect, cam, presetSettings(Preset::Medium), {&depth, nullptr, &encoded, GlDepth::D32F},
                     std::string("normals_enc") + std::to_string(int(e)) + "_" + sceneName, &cameraSpace.ao);
    }
  }
  Camera noRotation = base;
  noRotation.normalsEncoding = NormalsEncoding::WorldXyz;
  const DepthImage depth = test::renderDepth(sceneByName("plane"), base, cpuFormat(GlDepth::D32F));
  const FloatImage n = test::renderNormals(sceneByName("plane"), base);
  const GLuint depthTex = uploadDepth(depth, GlDepth::D32F);
  const GLuint normalTex = uploadNormals(n);
  gl::Inputs gi;
  gi.depth = {depthTex, internalFormat(GlDepth::D32F)};
  gi.normals = normalTex;
  const Status st = effect->render(noRotation, Settings{}, gi);
  EXPECT_EQ(st.code, StatusCode::InvalidCamera) << st.message;
  EXPECT_NE(st.message.find("needs Camera::viewRotation"), std::string::npos) << st.message;
  deleteTexture(depthTex);
  deleteTexture(normalTex);
}

// ---- Octahedral normals in a two-channel texture (the .xy the decode reads): GL_RG16F and
// GL_RG32F holding the same values as the GL_RGBA16F texture's .xy give the same output, bit for bit.

TEST_F(GlTest, TwoChannelOctahedralNormalsMatchFourChannel) {
  Camera cam = camera(kWidth, kHeight, kGuard);
  cam.viewRotation = test::viewRotation(0.7, -0.4, 0.25);
  auto effect = makeEffect();
  const test::Scene scene = sceneByName("stairs");
  const DepthImage depth = test::renderDepth(scene, cam, cpuFormat(GlDepth::D32F));
  const GLuint depthTex = uploadDepth(depth, GlDepth::D32F);
  const FloatImage n = test::renderNormals(scene, cam);
  for (NormalsEncoding e : {NormalsEncoding::CameraOctahedral, NormalsEncoding::WorldOctahedral}) {
    SCOPED_TRACE(int(e));
    cam.normalsEncoding = e;
    const GLuint rgba = uploadNormals(test::encodeNormals(n, e, *cam.viewRotation));  // halves, nearest-even
    const FloatImage xy = readTexture(rgba, 2);  // the very halves, exact in float
    gl::Inputs in;
    in.depth = {depthTex, internalFormat(GlDepth::D32F)};
    in.normals = rgba;
    ASSERT_TRUE(effect->render(cam, presetSettings(Preset::Medium), in).ok());
    const FloatImage four = readTexture(effect->aoTexture(), 1);
    const FloatImage fourRaw = readTexture(effect->texture(gen::ResourceId::ao_raw), 2);
    EXPECT_LT(*std::min_element(four.data.begin(), four.data.end()), 0.5f) << "the scene is occluded somewhere";
    for (GLenum format : {GLenum(GL_RG16F), GLenum(GL_RG32F)}) {
      const GLuint rg = makeTexture(format, xy.extent);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
      glTextureSubImage2D(rg, 0, 0, 0, GLsizei(xy.extent.width), GLsizei(xy.extent.height), GL_RG, GL_FLOAT,
                          xy.data.data());
      EXPECT_TRUE(test::sameBits(readTexture(rg, 2), xy)) << "the two-channel texture holds the same .xy";
      in.normals = rg;
      const Status st = effect->render(cam, presetSettings(Preset::Medium), in);
      ASSERT_TRUE(st.ok()) << st.message;
      EXPECT_TRUE(test::sameBits(readTexture(effect->aoTexture(), 1), four)) << format;
      EXPECT_TRUE(test::sameBits(readTexture(effect->texture(gen::ResourceId::ao_raw), 2), fourRaw)) << format;
      deleteTexture(rg);
    }
    deleteTexture(rgba);
  }
  deleteTexture(depthTex);
}

// ---- Orientation: an occluder only in the top-left darkens the top-left, where the CPU does.

TEST_F(GlTest, OrientationMatchesTheCpuReference) {
  const Camera cam = camera(kWidth, kHeight, kGuard);
  test::Scene scene = test::planeScene(3.0);
  // A sphere just in front of the wall, up and to the left (camera space: -x left, +y up).
  scene.spheres.push_back({{-1.55, 0.75, -2.62}, 0.36});
  const DepthImage depth = test::renderDepth(scene, cam, DepthFormat::D24);
  auto effect = makeEffect();
  const Settings settings = presetSettings(Preset::High);
  compareWithCpu(*effect, cam, settings, {&depth, nullptr, nullptr, GlDepth::D24}, "orientation");
  const FloatImage ao = readTexture(effect->aoTexture(), 1);
  cpu::Result ref;
  ASSERT_TRUE(cpu::run(settings, cam, {&depth}, {cpu::Precision::Float, 2}, ref).ok());

  // Darkness per quadrant. Rows are in GL order: row 0 is the bottom of the screen.
  auto quadrants = [](const FloatImage& img, double q[4], double centroid[2]) {
    const std::uint32_t W = img.extent.width, H = img.extent.height;
    double n[4] = {}, sum = 0, cx = 0, cy = 0;
    q[0] = q[1] = q[2] = q[3] = 0;
    for (std::uint32_t y = 0; y < H; ++y)
      for (std::uint32_t x = 0; x < W; ++x) {
        const double d = 1.0 - img.at(x, y);
        const int i = (x < W / 2 ? 0 : 1) + (y >= H / 2 ? 0 : 2);  // 0 top-left, 1 top-right, 2/3 bottom
        q[i] += d;
        n[i] += 1;
        sum += d;
        cx += d * x;
        cy += d * y;
      }
    for (int i = 0; i < 4; ++i) q[i] /= n[i];
    centroid[0] = cx / sum;
    centroid[1] = cy / sum;
  };
  double g[4], c[4], gc[2], cc[2];
  quadrants(ao, g, gc);
  quadrants(ref.ao, c, cc);
  std::printf("darkness per quadrant (TL TR BL BR): GL %.4f %.4f %.4f %.4f | CPU %.4f %.4f %.4f %.4f\n", g[0], g[1], g[2],
              g[3], c[0], c[1], c[2], c[3]);
  std::printf("darkness centroid: GL (%.2f, %.2f) CPU (%.2f, %.2f) (row 0 = bottom)\n", gc[0], gc[1], cc[0], cc[1]);
  EXPECT_GT(g[0], 0.01) << "the top-left is darkened";
  for (int i = 1; i < 4; ++i) EXPECT_GT(g[0], 10 * g[i]) << "quadrant " << i << " is nearly untouched";
  EXPECT_LT(gc[0], kWidth / 2.0);
  EXPECT_GT(gc[1], kHeight / 2.0);
  EXPECT_NEAR(gc[0], cc[0], 0.5);
  EXPECT_NEAR(gc[1], cc[1], 0.5);
  // The darkest pixel in GL lies where the CPU's darkness is: within the ring around the sphere.
  std::uint32_t bx = 0, by = 0;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x)
      if (ao.at(x, y) < ao.at(bx, by)) bx = x, by = y;
  EXPECT_LT(ref.ao.at(bx, by), 0.9f) << "GL's darkest pixel (" << bx << "," << by << ") is dark in the CPU image too";
}

}  // namespace
}  // namespace sao::gltest
