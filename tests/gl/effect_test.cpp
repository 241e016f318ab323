// sao::gl::Effect, what only GL has: create() and its loader, GL texture names, targets and
// internal formats, an input also passed as the output, aoTexture(), the texture names a
// reallocation keeps, timing. What every API shares (bad settings, cameras and sizes, sky, every
// depth format, resize, reallocation counts, the caller's output) is tests/executors/effect_test.cpp.
#include <epoxy/gl.h>

#include "analytic_scenes.h"
#include "gl_support.h"
#include "image_compare.h"
#include "untuned_settings.h"

namespace sao::gltest {
namespace {

using test::renderDepth;
using test::sameBits;

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
  Frame(std::uint32_t w, std::uint32_t h, GlDepth format, const test::Scene& scene)
      : camera(gltest::camera(w, h, 8)),
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

TEST_F(Inputs, UnsupportedNormalsFormat) {
  gl::Inputs in = good();
  const GLuint rgba8 = makeTexture(GL_RGBA8, frame->depth.extent);
  in.normals = rgba8;
  const Status st = render(in);
  EXPECT_EQ(st.code, StatusCode::UnsupportedFormat) << st.message;
  deleteTexture(rgba8);
}

TEST_F(Inputs, MixedDepthLayers) {
  gl::Inputs in = good();
  const GLuint linear = makeTexture(GL_R32F, frame->depth.extent);
  in.depth2 = {linear, 0};
  const Status st = render(in);
  EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
  deleteTexture(linear);
}

// ---- Texture names: aoTexture() is the owned texture, then the caller's; a reallocation keeps the
// textures of the images it does not change (the counts: Reallocation.OnlyWhatChanged in
// tests/executors/effect_test.cpp).

class Textures : public GlTest {};

TEST_F(Textures, AoTextureIsTheOwnedOutputThenTheCallers) {
  auto e = makeEffect();
  Frame f(160, 90, GlDepth::D24, test::stairsScene());
  gl::Inputs in;
  in.depth = {f.texture, gl::kDepthComponent24};
  ASSERT_TRUE(e->render(f.camera, Settings{}, in).ok());
  EXPECT_EQ(e->texture(gen::ResourceId::ao), e->aoTexture());
  const GLuint mine = makeTexture(GL_R16F, {160, 90});
  in.output = mine;
  ASSERT_TRUE(e->render(f.camera, Settings{}, in).ok());
  EXPECT_EQ(e->aoTexture(), mine);
  EXPECT_EQ(e->texture(gen::ResourceId::ao), mine);
  deleteTexture(mine);
}

TEST_F(Textures, ReallocationKeepsTheTexturesOfUnchangedImages) {
  auto e = makeEffect();
  Frame f(160, 90, GlDepth::D32F, test::sphereOnPlaneScene());
  gl::Inputs in;
  in.depth = {f.texture, gl::kDepthComponent32F};
  Settings s = test::untunedDefaults();  // full resolution with a blur: csz, ao_raw, ao_low, ao
  ASSERT_TRUE(e->render(f.camera, s, in).ok());
  const GLuint csz = e->texture(gen::ResourceId::csz), ao = e->texture(gen::ResourceId::ao);
  s.samples = 20;  // parameters only
  s.blur_radius = 6;
  ASSERT_TRUE(e->render(f.camera, s, in).ok());
  EXPECT_EQ(e->texture(gen::ResourceId::csz), csz);
  s.blur_radius = 0;  // nothing follows the AO: ao_sample_output, so ao_low and ao_raw are deleted
  ASSERT_TRUE(e->render(f.camera, s, in).ok());
  EXPECT_EQ(e->texture(gen::ResourceId::ao_low), 0u);
  EXPECT_EQ(e->texture(gen::ResourceId::ao_raw), 0u);
  EXPECT_EQ(e->texture(gen::ResourceId::ao), ao);
  s.blur_radius = 4;  // back: ao_raw and ao_low made again
  ASSERT_TRUE(e->render(f.camera, s, in).ok());
  EXPECT_NE(e->texture(gen::ResourceId::ao_low), 0u);
  const GLuint raw = e->texture(gen::ResourceId::ao_raw);
  EXPECT_NE(raw, 0u);
  s.radius = 0.05f;  // fewer csz levels: only csz made again
  ASSERT_TRUE(e->render(f.camera, s, in).ok());
  EXPECT_EQ(e->texture(gen::ResourceId::ao_raw), raw);
  EXPECT_EQ(e->texture(gen::ResourceId::ao), ao);
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
