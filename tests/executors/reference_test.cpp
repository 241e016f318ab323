// Each API against the CPU reference (float mode) on analytic scenes at 160x90 + guard 8: every
// agreement configuration (every preset, the z hierarchy off, the untuned defaults) x D16 / D24 /
// D32F (each under its own depth convention) x five scenes; more inputs and conventions; encoded
// normals; the orientation of an asymmetric scene. Final and raw AO within the agreement bounds.
#include <cstring>
#include <limits>
#include <numbers>

#include "harness.h"
#include "normal_encodings.h"
#include "sao/presets.h"
#include "untuned_settings.h"

namespace sao::exectest {
namespace {

constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8;

// One run on the executor and on the CPU reference; their agreement.
void expectAgreement(Executor& e, const Frame& frame, const std::string& name) {
  const Status st = e.render(frame);
  ASSERT_TRUE(st.ok()) << name << ": " << st.message;
  cpu::Result ref;
  const Status cs = runCpu(frame, ref);
  ASSERT_TRUE(cs.ok()) << cs.message;
  expectAgreesWithCpu(e, ref, name);
}

// ---- The matrix. Each format also runs under its own depth convention, so all are covered.
Camera cameraFor(Depth f) {
  switch (f) {
    case Depth::D16: return test::vulkanCamera(kW, kH, kGuard, 100.0);                 // [0,1], standard
    case Depth::D24: return test::openglCamera(kW, kH, kGuard, 100.0);                 // [-1,1], standard
    default: return test::vulkanCamera(kW, kH, kGuard, INFINITY, /*reversedZ=*/true);  // [0,1], reversed, infinite
  }
}

struct MatrixCase {
  std::size_t settings;  // index into test::agreementSettings()
  Depth format;
};
std::string caseName(const MatrixCase& c) {
  return test::agreementSettings()[c.settings].name + "_" + toString(c.format);
}
std::vector<MatrixCase> matrixCases() {
  std::vector<MatrixCase> v;
  for (std::size_t i = 0; i < test::agreementSettings().size(); ++i)
    for (Depth f : {Depth::D16, Depth::D24, Depth::D32F}) v.push_back({i, f});
  return v;
}

using Matrix = ApiCaseTest<MatrixCase>;
TEST_P(Matrix, FinalAndRawAoAgreeOnEveryScene) {
  auto e = make();
  Frame f;
  f.settings = test::agreementSettings()[param().settings].settings;
  f.camera = cameraFor(param().format);
  f.format = param().format;
  for (const char* scene : {"plane", "crease", "sphere", "stairs", "rods"}) {
    SCOPED_TRACE(scene);
    const DepthImage depth = test::renderDepth(sceneByName(scene), f.camera, cpuFormat(f.format));
    f.depth = &depth;
    expectAgreement(*e, f, caseName(param()) + "_" + scene);
  }
}
SAO_INSTANTIATE_API_CASES(Matrix, matrixCases());

// ---- More inputs and conventions, each with the default settings, the medium preset and the z
// hierarchy off (the reference preset of 2026-12-03: 64 taps, 5-tap blur, full resolution).
struct VariantCase {
  std::string name;
  Camera camera;
  Depth format = Depth::D32F;
  bool normals = false, twoLayer = false;
  const char* scene = "sphere";
  float fadeStart = 0, fadeEnd = 0;
  int divisor = 0;  // 0: the settings' own
};
std::string caseName(const VariantCase& c) { return c.name; }

std::vector<VariantCase> variantCases() {
  const Camera cam = test::openglCamera(kW, kH, kGuard);
  Camera reversed = perspectiveCamera(std::numbers::pi / 3.0, kW, kH, 0.1, std::numeric_limits<double>::infinity(),
                                      ClipDepth::ZeroToOne, true);
  reversed.guardBand = kGuard;
  Camera ortho = orthographicCamera(2.0, kW, kH, 0.1, 20.0, ClipDepth::NegativeOneToOne, false);
  ortho.guardBand = kGuard;
  Camera flipped = cam;
  flipped.flipY = true;
  return {
      {"D24S8", cam, Depth::D24S8},
      {"D32FS8", cam, Depth::D32FS8},
      {"LinearZ", cam, Depth::R32F},
      {"LinearZStairs", test::vulkanCamera(kW, kH, kGuard, 100.0), Depth::R32F, false, false, "stairs"},
      {"SuppliedNormals", cam, Depth::D32F, true},
      {"TwoLayers", cam, Depth::D32F, false, true},
      {"TwoLayersWithNormals", cam, Depth::D24, true, true, "rods"},
      {"ReversedInfiniteZeroToOne", reversed, Depth::D32F, false, false, "stairs"},
      {"Orthographic", ortho, Depth::D24, false, false, "crease"},
      {"FlippedRows", flipped, Depth::D32F, false, false, "stairs"},
      {"DistanceFade", cam, Depth::D24, false, false, "sphere", 3.0f, 6.0f},
      {"DistanceFadeNormals", cam, Depth::D32F, true, false, "stairs", 2.0f, 4.0f},
      {"DistanceFadeHalfResolution", test::vulkanCamera(kW, kH, kGuard, 100.0), Depth::D32F, false, false, "stairs",
       3.0f, 6.0f, 2},
      {"OddSizeWithoutGuard", test::openglCamera(97, 61, 0), Depth::D24, false, false, "rods"},
  };
}

using Variants = ApiCaseTest<VariantCase>;
TEST_P(Variants, AgreeWithTheCpuReference) {
  const VariantCase& c = param();
  const test::Scene scene = sceneByName(c.scene);
  const DepthImage depth = test::renderDepth(scene, c.camera, cpuFormat(c.format));
  const DepthImage depth2 = test::renderDepth(scene, c.camera, cpuFormat(c.format), 1);
  const FloatImage normals = test::renderNormals(scene, c.camera);
  Settings flat;
  flat.samples = 64;
  flat.blur_radius = 2;
  flat.resolution_divisor = 1;
  flat.use_z_hierarchy = false;  // the Z_HIERARCHY=0 variant
  auto e = make();
  for (const auto& [label, base] : {std::pair{"default", Settings{}}, std::pair{"medium", presetSettings(Preset::Medium)},
                                    std::pair{"no_hierarchy", flat}}) {
    if (c.twoLayer && !base.use_z_hierarchy) continue;  // TWO_LAYER needs the z hierarchy
    SCOPED_TRACE(label);
    Frame f;
    f.settings = base;
    f.settings.fade_start = c.fadeStart;
    f.settings.fade_end = c.fadeEnd;
    if (c.divisor) f.settings.resolution_divisor = c.divisor;
    f.camera = c.camera;
    f.depth = &depth;
    f.format = c.format;
    f.depth2 = c.twoLayer ? &depth2 : nullptr;
    f.normals = c.normals ? &normals : nullptr;
    expectAgreement(*e, f, c.name + "_" + label);
  }
}
SAO_INSTANTIATE_API_CASES(Variants, variantCases());

// ---- Normals in world space and octahedral (Camera::normalsEncoding): each API agrees with the
// CPU reference on the encoded input and with the CPU's result for the camera-space normals; a
// world-space encoding without a view rotation is refused.
using Normals = ApiTest;
TEST_P(Normals, EncodedNormalsMatchTheCameraSpaceResult) {
  const Camera base = test::vulkanCamera(kW, kH, kGuard, 100.0);
  auto e = make();
  for (const char* sceneName : {"stairs", "sphere"}) {
    const test::Scene scene = sceneByName(sceneName);
    const DepthImage depth = test::renderDepth(scene, base, DepthFormat::D32F);
    const FloatImage n = test::renderNormals(scene, base);
    Frame f;
    f.settings = presetSettings(Preset::Medium);
    f.camera = base;
    f.depth = &depth;
    f.normals = &n;
    cpu::Result cameraSpace;
    ASSERT_TRUE(runCpu(f, cameraSpace).ok());
    for (NormalsEncoding enc :
         {NormalsEncoding::WorldXyz, NormalsEncoding::CameraOctahedral, NormalsEncoding::WorldOctahedral}) {
      SCOPED_TRACE(std::string(sceneName) + " encoding " + std::to_string(int(enc)));
      f.camera.normalsEncoding = enc;
      f.camera.viewRotation = test::viewRotation(0.7, -0.4, 0.25);
      const FloatImage encoded = test::encodeNormals(n, enc, *f.camera.viewRotation);
      f.normals = &encoded;
      const std::string name = "normals_enc" + std::to_string(int(enc)) + "_" + sceneName;
      expectAgreement(*e, f, name);
      const Agreement c = compare(api(), e->output(), cameraSpace.ao, 0, kWithin, kNever, name + "_vs_camera_space");
      std::printf("%s against the camera-space normals' CPU result: final max %.4f/255 p99.9 %.4f/255\n", name.c_str(),
                  c.maxAbs * 255, c.p999 * 255);
      EXPECT_TRUE(acceptable(c)) << "against the camera-space run: max " << c.maxAbs * 255 << "/255";
    }
  }
  const DepthImage depth = test::renderDepth(sceneByName("plane"), base, DepthFormat::D32F);
  const FloatImage n = test::renderNormals(sceneByName("plane"), base);
  for (NormalsEncoding enc : {NormalsEncoding::WorldXyz, NormalsEncoding::WorldOctahedral}) {
    Frame f;
    f.camera = base;
    f.camera.normalsEncoding = enc;
    f.depth = &depth;
    f.normals = &n;
    const Status st = e->render(f);
    EXPECT_EQ(st.code, StatusCode::InvalidCamera) << st.message;
    EXPECT_NE(st.message.find("needs Camera::viewRotation"), std::string::npos) << st.message;
  }
}

// Octahedral normals in a two-channel image (the .xy the decode reads): RG16F and RG32F holding the
// same halves as the RGBA16F image's .xy give the same output, bit for bit.
TEST_P(Normals, TwoChannelOctahedralNormalsMatchFourChannel) {
  Frame f;
  f.settings = presetSettings(Preset::Medium);
  f.camera = test::vulkanCamera(kW, kH, kGuard, 100.0);
  f.camera.viewRotation = test::viewRotation(0.7, -0.4, 0.25);
  const test::Scene scene = sceneByName("stairs");
  const DepthImage depth = test::renderDepth(scene, f.camera, DepthFormat::D32F);
  const FloatImage n = test::renderNormals(scene, f.camera);
  f.depth = &depth;
  auto e = make();
  for (NormalsEncoding enc : {NormalsEncoding::CameraOctahedral, NormalsEncoding::WorldOctahedral}) {
    SCOPED_TRACE(int(enc));
    f.camera.normalsEncoding = enc;
    FloatImage halves = test::encodeNormals(n, enc, *f.camera.viewRotation);
    for (float& v : halves.data) v = cpu::quantizeHalf(v);  // what RGBA16F holds, exact in RG32F
    f.normals = &halves;
    f.normalsTexels = Texels::RGBA16F;
    ASSERT_TRUE(e->render(f).ok());
    const FloatImage four = e->output(), fourRaw = e->image(gen::ResourceId::ao_raw);
    EXPECT_LT(*std::min_element(four.data.begin(), four.data.end()), 0.5f) << "the scene is occluded somewhere";
    for (Texels t : {Texels::RG16F, Texels::RG32F}) {
      f.normalsTexels = t;
      const Status st = e->render(f);
      ASSERT_TRUE(st.ok()) << st.message;
      EXPECT_TRUE(test::sameBits(e->output(), four)) << int(t);
      EXPECT_TRUE(test::sameBits(e->image(gen::ResourceId::ao_raw), fourRaw)) << int(t);
    }
  }
}
SAO_INSTANTIATE_APIS(Normals);

// ---- Orientation: a box against a wall, only in the camera's top-left. With a flipped viewport
// (Camera::flipY) or a projection with a negative y scale, row 0 of the depth image is the top of
// the screen, and the darkening must appear in the top-left of the result, where the CPU reference
// puts it. With neither (GL's usual convention), row 0 is the bottom and the effect must follow.
test::Scene boxInTopLeft() {
  test::Scene s;
  s.name = "box_top_left";
  s.planes.push_back({{0, 0, -4}, {0, 0, 1}, {}});
  s.boxes.push_back({{-3.4, 1.0, -4.0}, {-2.4, 1.9, -3.6}});
  return s;
}

struct Darkness {
  double quadrant[2][2] = {};  // [row < H/2][x < W/2], memory order
  double cx = 0, cy = 0, total = 0;
};

Darkness darkness(const FloatImage& ao) {
  Darkness d;
  for (std::uint32_t y = 0; y < ao.extent.height; ++y)
    for (std::uint32_t x = 0; x < ao.extent.width; ++x) {
      const double v = std::max(0.0, 1.0 - double(ao.at(x, y)));
      d.quadrant[y < ao.extent.height / 2 ? 0 : 1][x < ao.extent.width / 2 ? 0 : 1] += v;
      d.cx += v * x;
      d.cy += v * y;
      d.total += v;
    }
  if (d.total > 0) d.cx /= d.total, d.cy /= d.total;
  return d;
}

struct OrientationCase {
  std::string name;
  Camera camera;
  bool row0IsTop;
};
std::string caseName(const OrientationCase& c) { return c.name; }
std::vector<OrientationCase> orientationCases() {
  Camera negative = test::vulkanCamera(kW, kH, kGuard, 100.0);
  negative.projection[5] = -negative.projection[5];  // GLM's proj[1][1] *= -1, the common Vulkan idiom
  return {{"flipY", test::vulkanCamera(kW, kH, kGuard, 100.0, false, /*flipY=*/true), true},
          {"negative_p11", negative, true},
          {"unflipped", test::vulkanCamera(kW, kH, kGuard, 100.0), false},
          {"opengl", test::openglCamera(kW, kH, kGuard), false}};
}

using Orientation = ApiCaseTest<OrientationCase>;
TEST_P(Orientation, DarkeningWhereTheCpuReferencePutsIt) {
  const OrientationCase& c = param();
  const DepthImage depth = test::renderDepth(boxInTopLeft(), c.camera, DepthFormat::D32F);
  auto e = make();
  Frame f;
  f.camera = c.camera;
  f.depth = &depth;
  ASSERT_TRUE(e->render(f).ok());
  cpu::Result ref;
  ASSERT_TRUE(runCpu(f, ref).ok());
  const FloatImage ao = e->output();
  const Darkness v = darkness(ao), r = darkness(ref.ao);
  const int row = c.row0IsTop ? 0 : 1;  // the memory half that is the screen's top
  std::printf("%s %s: darkness in the screen's top-left quadrant %.1f of %.1f, centroid (%.2f, %.2f) in memory rows; "
              "CPU (%.2f, %.2f)\n",
              toString(api()), c.name.c_str(), v.quadrant[row][0], v.total, v.cx, v.cy, r.cx, r.cy);
  ASSERT_GT(v.total, 5.0) << "the box must occlude the wall around it";
  EXPECT_GT(v.quadrant[row][0], 0.95 * v.total) << "the darkening is in the top-left of the screen";
  EXPECT_LT(v.cx, kW / 2.0);
  EXPECT_TRUE(c.row0IsTop ? v.cy < kH / 2.0 : v.cy > kH / 2.0);
  EXPECT_NEAR(v.cx, r.cx, 0.25) << "the same place as the CPU reference";
  EXPECT_NEAR(v.cy, r.cy, 0.25) << "the same place as the CPU reference";
  // The darkest pixel lies where the CPU's darkness is.
  const auto darkest = std::size_t(std::min_element(ao.data.begin(), ao.data.end()) - ao.data.begin());
  EXPECT_LT(ref.ao.data[darkest], 0.9f) << "the darkest pixel is dark in the CPU image too";
  EXPECT_TRUE(acceptable(compare(api(), ao, ref.ao, 0, kWithin, kNever, "orientation_" + c.name)));
}
SAO_INSTANTIATE_API_CASES(Orientation, orientationCases());

}  // namespace
}  // namespace sao::exectest
