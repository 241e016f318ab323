// sao::gl::Effect: create(), bad inputs, sky, resize, reallocation, user output, timing.
#include <epoxy/gl.h>

#include <bit>
#include <cmath>
#include <limits>

#include "image_compare.h"
#include "untuned_settings.h"
#include "analytic_scenes.h"
#include <ostream>

#include "gl_support.h"
#include "sao/presets.h"

namespace sao::gltest {
namespace {

using test::renderDepth;

constexpr double kInf = std::numeric_limits<double>::infinity();

using test::sameBits;

std::size_t countNonFinite(const FloatImage& img) {
  std::size_t n = 0;
  for (float v : img.data) n += !std::isfinite(v);
  return n;
}

// ---- create()

class Create : public GlTest {};

TEST_F(Create, Succeeds) {
  auto e = makeEffect();
  ASSERT_TRUE(e);
  EXPECT_EQ(e->aoTexture(), 0u);
  EXPECT_EQ(e->stats().renders, 0u);
}

TEST_F(Create, RejectsAnotherHeaderVersion) {
  std::unique_ptr<gl::Effect> e;
  const Status st = gl::Effect::create(gl::HeadlessContext::getProcAddress(), e, SAO_VERSION + 1);
  EXPECT_EQ(st.code, StatusCode::VersionMismatch) << st.message;
  EXPECT_FALSE(e);
  EXPECT_NE(st.message.find("0.1.1"), std::string::npos) << st.message;
}

TEST_F(Create, RejectsANullLoader) {
  std::unique_ptr<gl::Effect> e;
  const Status st = gl::Effect::create(nullptr, e);
  EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
  EXPECT_FALSE(e);
}

gl::ProcAddress nullLoader(const char*) { return nullptr; }

TEST_F(Create, ReportsAMissingEntryPoint) {
  std::unique_ptr<gl::Effect> e;
  const Status st = gl::Effect::create(&nullLoader, e);
  EXPECT_EQ(st.code, StatusCode::DriverError) << st.message;
  EXPECT_NE(st.message.find("glGetString"), std::string::npos) << st.message;
}

TEST_F(Create, FailsCleanlyWithoutACurrentContext) {
  ASSERT_TRUE(context().releaseCurrent().ok());
  std::unique_ptr<gl::Effect> e;
  const Status st = gl::Effect::create(gl::HeadlessContext::getProcAddress(), e);
  ASSERT_TRUE(context().makeCurrent().ok());
  EXPECT_EQ(st.code, StatusCode::DriverError) << st.message;
  EXPECT_NE(st.message.find("4.3"), std::string::npos) << st.message;
  EXPECT_FALSE(e);
}

// ---- A small frame for the input checks.

struct Frame {
  Camera camera;
  DepthImage depth;
  GLuint texture = 0;
  Frame(std::uint32_t w, std::uint32_t h, GlDepth format, const test::Scene& scene, double farDistance = 1000.0,
        bool reversed = false)
      : camera(gltest::camera(w, h, 8, farDistance, reversed)),
        depth(renderDepth(scene, camera, cpuFormat(format))),
        texture(uploadDepth(depth, format)) {}
  ~Frame() { deleteTexture(texture); }
};

class Inputs : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    effect = makeEffect();
    frame = std::make_unique<Frame>(64, 36, GlDepth::D24, test::sphereOnPlaneScene());
  }
  void TearDown() override {
    frame.reset();
    effect.reset();
    GlTest::TearDown();
  }
  Status render(const gl::Inputs& in, const Settings& s = {}) { return effect->render(frame->camera, s, in); }
  gl::Inputs good() const {
    gl::Inputs in;
    in.depth = {frame->texture, gl::kDepthComponent24};
    return in;
  }
  std::unique_ptr<gl::Effect> effect;
  std::unique_ptr<Frame> frame;
};

TEST_F(Inputs, GoodInputsRender) {
  const Status st = render(good());
  ASSERT_TRUE(st.ok()) << st.message;
  EXPECT_NE(effect->aoTexture(), 0u);
  EXPECT_EQ(effect->stats().renders, 1u);
}

TEST_F(Inputs, DepthTextureZero) {
  gl::Inputs in = good();
  in.depth.texture = 0;
  const Status st = render(in);
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("depth texture is 0"), std::string::npos) << st.message;
}

TEST_F(Inputs, NotATexture) {
  gl::Inputs in = good();
  in.depth.texture = 123456;
  const Status st = render(in);
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("not a texture"), std::string::npos) << st.message;
}

TEST_F(Inputs, NotATexture2D) {
  GLuint t = 0;
  glGenTextures(1, &t);
  glBindTexture(GL_TEXTURE_3D, t);
  glTexStorage3D(GL_TEXTURE_3D, 1, GL_R32F, 80, 52, 2);
  glBindTexture(GL_TEXTURE_3D, 0);
  gl::Inputs in;
  in.depth = {t, 0};
  const Status st = render(in);
  glDeleteTextures(1, &t);
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("GL_TEXTURE_3D"), std::string::npos) << st.message;
}

TEST_F(Inputs, UnsupportedDepthFormat) {
  const GLuint t = makeTexture(GL_RGBA8, frame->depth.extent);
  gl::Inputs in;
  in.depth = {t, 0};
  const Status st = render(in);
  deleteTexture(t);
  EXPECT_EQ(st.code, StatusCode::UnsupportedFormat);
  EXPECT_NE(st.message.find("GL_RGBA8"), std::string::npos) << st.message;
}

TEST_F(Inputs, DeclaredFormatIsChecked) {
  gl::Inputs in = good();
  in.depth.internalFormat = gl::kDepthComponent32F;  // the texture is really D24
  const Status st = render(in);
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("GL_DEPTH_COMPONENT32F"), std::string::npos) << st.message;
  EXPECT_NE(st.message.find("GL_DEPTH_COMPONENT24"), std::string::npos) << st.message;
  in.depth.internalFormat = 0;  // 0: whatever the texture holds
  const Status ok = render(in);
  EXPECT_TRUE(ok.ok()) << ok.message;
}

TEST_F(Inputs, DepthSizeMustBeViewportPlusGuard) {
  Camera c = frame->camera;
  c.guardBand = 0;  // the texture holds a guard band the camera does not declare
  Status st = effect->render(c, Settings{}, good());
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("80x52"), std::string::npos) << st.message;
  EXPECT_NE(st.message.find("64x36"), std::string::npos) << st.message;
  EXPECT_NE(st.message.find("set Inputs::region"), std::string::npos) << st.message;
  c.guardBand = 9;  // needs 82x54: too large for the texture, with or without a region
  st = effect->render(c, Settings{}, good());
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("82x54"), std::string::npos) << st.message;
}

TEST_F(Inputs, DepthAlsoPassedAsOutput) {
  gl::Inputs in = good();
  in.output = frame->texture;
  const Status st = render(in);
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("both as the output and as the depth"), std::string::npos) << st.message;
}

TEST_F(Inputs, OutputFormatAndSize) {
  gl::Inputs in = good();
  const GLuint rgba = makeTexture(GL_RG16F, {64, 36});  // not an output format (sao/output.h)
  in.output = rgba;
  Status st = render(in);
  EXPECT_EQ(st.code, StatusCode::UnsupportedFormat) << st.message;
  EXPECT_NE(st.message.find("GL_RG16F"), std::string::npos) << st.message;
  const GLuint small = makeTexture(GL_R16F, {32, 36});
  in.output = small;
  st = render(in);
  EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
  EXPECT_NE(st.message.find("32x36"), std::string::npos) << st.message;
  deleteTexture(rgba);
  deleteTexture(small);
}

TEST_F(Inputs, NormalsFormatAndSize) {
  gl::Inputs in = good();
  const GLuint rgba8 = makeTexture(GL_RGBA8, frame->depth.extent);
  in.normals = rgba8;
  Status st = render(in);
  EXPECT_EQ(st.code, StatusCode::UnsupportedFormat) << st.message;
  const GLuint wrongSize = makeTexture(GL_RGBA16F, {64, 36});
  in.normals = wrongSize;
  st = render(in);
  EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
  deleteTexture(rgba8);
  deleteTexture(wrongSize);
}

TEST_F(Inputs, BadSettingsAndCamera) {
  Settings s;
  s.samples = 0;
  Status st = render(good(), s);
  EXPECT_EQ(st.code, StatusCode::InvalidSetting) << st.message;
  Camera c = frame->camera;
  c.projection[11] = 0.0;  // not a perspective projection any more
  st = effect->render(c, Settings{}, good());
  EXPECT_EQ(st.code, StatusCode::InvalidCamera) << st.message;
}

TEST_F(Inputs, MixedDepthLayers) {
  gl::Inputs in = good();
  const GLuint linear = makeTexture(GL_R32F, frame->depth.extent);
  in.depth2 = {linear, 0};
  const Status st = render(in);
  EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
  deleteTexture(linear);
}

// ---- Sky: depth = far everywhere gives A = 1 and no NaN / Inf in any image.

struct SkyCase {
  GlDepth format;
  bool infinite, reversed;
};
void PrintTo(const SkyCase& c, std::ostream* os) { *os << std::string(toString(c.format)) + (c.infinite ? " infinite" : " finite") + (c.reversed ? " reversed" : ""); }


class Sky : public GlTest, public ::testing::WithParamInterface<SkyCase> {};

TEST_P(Sky, IsUnoccludedAndFinite) {
  const SkyCase c = GetParam();
  auto effect = makeEffect();
  Frame f(160, 90, c.format, test::skyScene(), c.infinite ? kInf : 100.0, c.reversed);
  for (const auto& preset : presets()) {
    SCOPED_TRACE(std::string(preset.name));
    gl::Inputs in;
    in.depth = {f.texture, internalFormat(c.format)};
    const Status st = effect->render(f.camera, presetSettings(preset.preset), in);
    ASSERT_TRUE(st.ok()) << st.message;
    const FloatImage ao = readTexture(effect->aoTexture(), 1);
    const FloatImage raw = readTexture(effect->texture(gen::ResourceId::ao_raw), 2);
    EXPECT_EQ(countNonFinite(ao), 0u);
    EXPECT_EQ(countNonFinite(raw), 0u);
    for (float a : ao.data) ASSERT_EQ(a, 1.0f);
    for (std::size_t i = 0; i < raw.data.size(); i += 2) {
      ASSERT_EQ(raw.data[i], 1.0f);
      ASSERT_EQ(std::bit_cast<std::uint32_t>(raw.data[i + 1]), 0u) << "the key of sky is +0.0";
    }
    if (const GLuint low = effect->texture(gen::ResourceId::ao_low)) {
      EXPECT_EQ(countNonFinite(readTexture(low, 2)), 0u);
    }
    const GLuint csz = effect->texture(gen::ResourceId::csz);
    for (std::uint32_t m = 0; m < effect->plan().cszLevels; ++m) {
      const FloatImage z = readTextureLevel(csz, m);
      for (float v : z.data) ASSERT_EQ(std::bit_cast<std::uint32_t>(v), 0u) << "csz level " << m << " is +0.0 (sky)";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, Sky,
                         ::testing::Values(SkyCase{GlDepth::D24, true, false}, SkyCase{GlDepth::D32F, true, false},
                                           SkyCase{GlDepth::D16, true, false}, SkyCase{GlDepth::D32F, true, true},
                                           SkyCase{GlDepth::D24S8, false, false}, SkyCase{GlDepth::R32F, true, false}),
                         [](const auto& info) {
                           return std::string(toString(info.param.format)) +
                                  (info.param.infinite ? "_infinite" : "_finite") +
                                  (info.param.reversed ? "_reversed" : "");
                         });

// ---- Resize: 640x360 -> 1281x721 -> 640x360 equals a fresh effect at each size.

class Resize : public GlTest {};

TEST_F(Resize, MatchesAFreshEffectAtEachSize) {
  auto reused = makeEffect();
  const std::pair<std::uint32_t, std::uint32_t> sizes[] = {{640, 360}, {1281, 721}, {640, 360}};
  const Settings settings = presetSettings(Preset::Medium);
  for (const auto& [w, h] : sizes) {
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
    Frame f(w, h, GlDepth::D24, test::sphereOnPlaneScene());
    gl::Inputs in;
    in.depth = {f.texture, gl::kDepthComponent24};
    ASSERT_TRUE(reused->render(f.camera, settings, in).ok());
    auto fresh = makeEffect();
    ASSERT_TRUE(fresh->render(f.camera, settings, in).ok());
    EXPECT_EQ(reused->plan().aoExtent, (Extent{w, h}));
    EXPECT_EQ(reused->plan().cszLevels, fresh->plan().cszLevels);
    const FloatImage a = readTexture(reused->aoTexture(), 1), b = readTexture(fresh->aoTexture(), 1);
    EXPECT_EQ(a.extent, (Extent{w, h}));
    EXPECT_TRUE(sameBits(a, b)) << "final AO differs from a fresh effect's";
    EXPECT_TRUE(sameBits(readTexture(reused->texture(gen::ResourceId::ao_raw), 2),
                         readTexture(fresh->texture(gen::ResourceId::ao_raw), 2)))
        << "raw AO differs from a fresh effect's";
    double mean = 0;
    for (float v : a.data) mean += v;
    mean /= double(a.data.size());
    EXPECT_LT(mean, 0.999) << "the scene should show some obscurance";
    EXPECT_GT(mean, 0.5);
  }
}

// ---- Reallocation follows the plan: only what changed.

class Reallocation : public GlTest {};

TEST_F(Reallocation, OnlyWhatChanged) {
  auto e = makeEffect();
  Frame f(160, 90, GlDepth::D32F, test::sphereOnPlaneScene());
  gl::Inputs in;
  in.depth = {f.texture, gl::kDepthComponent32F};
  Settings s = test::untunedDefaults();  // full resolution with a blur: the four images below
  ASSERT_TRUE(e->render(f.camera, s, in).ok());
  const auto allocs0 = e->stats().textureAllocations;
  EXPECT_EQ(allocs0, 4u);  // csz, ao_raw, ao_low, ao
  const GLuint csz = e->texture(gen::ResourceId::csz), raw = e->texture(gen::ResourceId::ao_raw);
  const GLuint low = e->texture(gen::ResourceId::ao_low), ao = e->texture(gen::ResourceId::ao);
  const std::uint32_t levels = e->plan().cszLevels;

  s.samples = 20;  // parameters only: nothing reallocated
  s.blur_radius = 6;
  ASSERT_TRUE(e->render(f.camera, s, in).ok());
  EXPECT_EQ(e->stats().textureAllocations, allocs0);
  EXPECT_EQ(e->texture(gen::ResourceId::csz), csz);

  s.blur_radius = 0;  // nothing follows the AO: ao_sample_output, so ao_low and ao_raw are freed
  ASSERT_TRUE(e->render(f.camera, s, in).ok());
  EXPECT_EQ(e->texture(gen::ResourceId::ao_low), 0u);
  EXPECT_EQ(e->texture(gen::ResourceId::ao_raw), 0u);
  EXPECT_EQ(e->stats().textureAllocations, allocs0);
  EXPECT_EQ(e->texture(gen::ResourceId::ao), ao);
  (void)raw;

  s.blur_radius = 4;  // back: ao_raw and ao_low allocated again
  ASSERT_TRUE(e->render(f.camera, s, in).ok());
  EXPECT_EQ(e->stats().textureAllocations, allocs0 + 2);
  EXPECT_NE(e->texture(gen::ResourceId::ao_low), 0u);
  const GLuint raw2 = e->texture(gen::ResourceId::ao_raw);
  EXPECT_NE(raw2, 0u);
  (void)low;

  s.radius = 0.05f;  // fewer csz levels: only csz is reallocated
  ASSERT_TRUE(e->render(f.camera, s, in).ok());
  EXPECT_LT(e->plan().cszLevels, levels);
  EXPECT_EQ(e->stats().textureAllocations, allocs0 + 3);
  EXPECT_EQ(e->texture(gen::ResourceId::ao_raw), raw2);
  EXPECT_EQ(e->texture(gen::ResourceId::ao), ao);

  s.use_z_hierarchy = false;  // one level
  ASSERT_TRUE(e->render(f.camera, s, in).ok());
  EXPECT_EQ(e->plan().cszLevels, 1u);
  EXPECT_EQ(e->stats().textureAllocations, allocs0 + 4);
}

// ---- The caller's output texture.

class Output : public GlTest {};

TEST_F(Output, UserTextureReceivesTheSameImage) {
  auto e = makeEffect();
  Frame f(160, 90, GlDepth::D24, test::stairsScene());
  gl::Inputs in;
  in.depth = {f.texture, gl::kDepthComponent24};
  ASSERT_TRUE(e->render(f.camera, Settings{}, in).ok());
  const FloatImage owned = readTexture(e->aoTexture(), 1);
  const GLuint owndTex = e->aoTexture();
  EXPECT_EQ(e->texture(gen::ResourceId::ao), owndTex);

  const GLuint mine = makeTexture(GL_R16F, {160, 90});
  in.output = mine;
  ASSERT_TRUE(e->render(f.camera, Settings{}, in).ok());
  EXPECT_EQ(e->aoTexture(), mine);
  EXPECT_EQ(e->texture(gen::ResourceId::ao), mine);
  EXPECT_TRUE(sameBits(readTexture(mine, 1), owned));
  EXPECT_FALSE(e->plan().image(gen::ResourceId::ao)) << "no owned output when the caller gives one";
  deleteTexture(mine);
}

// ---- Timing.

class Timing : public GlTest {};

TEST_F(Timing, ReportsEveryPlannedPassAndTheMethod) {
  auto e = makeEffect();
  Frame f(160, 90, GlDepth::D24, test::sphereOnPlaneScene());
  gl::Inputs in;
  in.depth = {f.texture, gl::kDepthComponent24};
  ASSERT_TRUE(e->render(f.camera, Settings{}, in).ok());
  EXPECT_EQ(e->timings().method, TimingMethod::None);
  EXPECT_TRUE(e->timings().passes.empty());
  const FloatImage untimed = readTexture(e->aoTexture(), 1);
  // llvmpipe's GL_TIME_ELAPSED does not see compute work (it reports ~1 ns): the effect must
  // notice and time by glFinish + clock. Elsewhere either method may be reported.
  const std::string renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const bool llvmpipe = renderer.find("llvmpipe") != std::string::npos;

  for (int frame = 0; frame < 3; ++frame) {
    ASSERT_TRUE(e->render(f.camera, Settings{}, in, {true}).ok());
    const Timings& t = e->timings();
    if (llvmpipe) EXPECT_EQ(t.method, TimingMethod::FinishAndClock) << renderer;
    else EXPECT_TRUE(t.method == TimingMethod::GpuTimestamps || t.method == TimingMethod::FinishAndClock);
    ASSERT_EQ(t.passes.size(), e->plan().passes.size());
    for (std::size_t i = 0; i < t.passes.size(); ++i) {
      EXPECT_EQ(t.passes[i].pass, gen::pass(e->plan().passes[i].pass).name);
      // Either method: a real duration (timer-query results are at least the 100 ns plausibility floor).
      EXPECT_GT(t.passes[i].milliseconds, 0.0) << t.passes[i].pass << " by " << toString(t.method);
      if (t.method == TimingMethod::GpuTimestamps) {
        EXPECT_GE(t.passes[i].milliseconds, 1e-4) << t.passes[i].pass;
      }
    }
    std::printf("frame %d, %s, method %s:", frame, renderer.c_str(), toString(t.method));
    for (const auto& p : t.passes) std::printf(" %s %.3f ms", p.pass.c_str(), p.milliseconds);
    std::printf("\n");
  }
  EXPECT_TRUE(sameBits(readTexture(e->aoTexture(), 1), untimed)) << "timing changes nothing in the result";
}

TEST_F(Timing, CallersTimerQueryMayBeRunning) {
  auto e = makeEffect();
  Frame f(64, 36, GlDepth::D24, test::sphereOnPlaneScene());
  gl::Inputs in;
  in.depth = {f.texture, gl::kDepthComponent24};
  GLuint q = 0;
  glGenQueries(1, &q);
  glBeginQuery(GL_TIME_ELAPSED, q);
  const Status st = e->render(f.camera, Settings{}, in, {true});
  glEndQuery(GL_TIME_ELAPSED);
  glDeleteQueries(1, &q);
  ASSERT_TRUE(st.ok()) << st.message;
  EXPECT_EQ(e->timings().method, TimingMethod::FinishAndClock);
}

}  // namespace
}  // namespace sao::gltest
