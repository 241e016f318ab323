// One prepass object across many calls: the mesh cache follows the mesh's contents, sizes /
// formats / layers change freely, results equal a fresh object's, Camera::flipY reverses the rows,
// GL in the caller's context restores the caller's state, and nothing grows over many cycles.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <unistd.h>

#include "prepass_support.h"

#ifdef SAO_PREPASS_HAVE_GL
#include <epoxy/gl.h>
#endif

namespace sao::prepasstest {
namespace {

std::uint64_t residentBytes() {
  std::ifstream f("/proc/self/statm");
  std::uint64_t pages = 0, resident = 0;
  f >> pages >> resident;
  return resident * std::uint64_t(sysconf(_SC_PAGESIZE));
}

// Under AddressSanitizer freed memory sits in the allocator's quarantine, so RSS says nothing
// about leaks there (ASan's leak checker covers them); ci/sanitize.sh sets SAO_SANITIZED too.
bool sanitized() {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#else
  return std::getenv("SAO_SANITIZED") != nullptr;
#endif
}

bool sameResult(const prepass::PrepassResult& a, const prepass::PrepassResult& b) {
  auto same = [](const FloatImage& x, const FloatImage& y) {
    return x.extent == y.extent && x.data.size() == y.data.size() &&
           (x.data.empty() || std::memcmp(x.data.data(), y.data.data(), x.data.size() * sizeof(float)) == 0);
  };
  return a.depth.extent == b.depth.extent && a.depth.format == b.depth.format && a.depth.texels == b.depth.texels &&
         a.depth2.texels == b.depth2.texels && same(a.position, b.position) && same(a.normal, b.normal) &&
         same(a.position2, b.position2) && same(a.normal2, b.normal2);
}

class Reuse : public PrepassTest, public ::testing::WithParamInterface<std::string> {
 protected:
  prepass::Prepass& prepass() { return backend(GetParam()); }
  prepass::PrepassResult render(const scenes::Mesh& mesh, const scenes::View& view, const Camera& camera,
                                const prepass::PrepassOptions& options = {}) {
    prepass::PrepassResult r;
    const Status s = prepass().render(mesh, view, camera, options, r);
    EXPECT_TRUE(s) << s.message;
    return r;
  }
};

TEST_P(Reuse, MeshCacheFollowsContents) {
  const LoadedScene& a = loadScene("crease");
  const LoadedScene& b = loadScene("sphere-plane");
  const scenes::View& view = a.scene.views.front();
  const Camera camera = scenes::makeCamera(view, 96, 54, INFINITY, ClipDepth::ZeroToOne, true, 4);
  const auto first = render(a.scene.mesh, view, camera);
  const auto other = render(b.scene.mesh, view, camera);
  EXPECT_FALSE(sameResult(first, other));
  EXPECT_TRUE(sameResult(first, render(a.scene.mesh, view, camera)));
  // The same object, edited in place (same address, same sizes): uploaded again.
  scenes::Mesh edited = a.scene.mesh;
  const auto before = render(edited, view, camera);
  EXPECT_TRUE(sameResult(first, before));
  for (auto& p : edited.positions) p.y -= 0.5f;
  const auto after = render(edited, view, camera);
  EXPECT_FALSE(sameResult(before, after));
  for (auto& p : edited.positions) p.y += 0.5f;
  EXPECT_TRUE(sameResult(first, render(edited, view, camera)));
}

TEST_P(Reuse, ChangingSizesFormatsAndLayersMatchesAFreshObject) {
  const LoadedScene& s = loadScene("sponza-like");
  const scenes::View& view = s.scene.views.front();
  struct Step {
    std::uint32_t w, h, guard;
    DepthFormat format;
    bool reversed, second;
  };
  const Step steps[] = {{64, 36, 0, DepthFormat::D32F, true, false},  {97, 41, 3, DepthFormat::D16, false, true},
                        {64, 36, 0, DepthFormat::D24, true, true},    {128, 72, 8, DepthFormat::D32F, false, false},
                        {64, 36, 0, DepthFormat::D32F, true, false}};
  std::vector<prepass::PrepassResult> results;
  for (const Step& st : steps) {
    const Camera camera = scenes::makeCamera(view, st.w, st.h, 500.0, ClipDepth::ZeroToOne, st.reversed, st.guard);
    prepass::PrepassOptions o;
    o.format = st.format;
    o.secondLayer = st.second;
    results.push_back(render(s.scene.mesh, view, camera, o));
    EXPECT_EQ(results.back().depth.extent, (Extent{st.w + 2 * st.guard, st.h + 2 * st.guard}));
    EXPECT_EQ(results.back().depth2.texels.empty(), !st.second);
  }
  EXPECT_TRUE(sameResult(results.front(), results.back()));
  // A fresh object renders step 2 the same.
  std::unique_ptr<prepass::Prepass> fresh;
#ifdef SAO_PREPASS_HAVE_GL
  if (GetParam() == "gl") {
    std::unique_ptr<prepass::GlPrepass> g;
    ASSERT_TRUE(prepass::GlPrepass::create(g));
    fresh = std::move(g);
  }
#endif
#ifdef SAO_PREPASS_HAVE_VULKAN
  if (GetParam() == "vulkan") {
    std::unique_ptr<prepass::VkPrepass> v;
    ASSERT_TRUE(prepass::VkPrepass::create(vkPrepass().context(), v));  // on the shared, validated device
    fresh = std::move(v);
  }
#endif
  const Step& st = steps[1];
  const Camera camera = scenes::makeCamera(view, st.w, st.h, 500.0, ClipDepth::ZeroToOne, st.reversed, st.guard);
  prepass::PrepassOptions o;
  o.format = st.format;
  o.secondLayer = st.second;
  prepass::PrepassResult r;
  ASSERT_TRUE(fresh->render(s.scene.mesh, view, camera, o, r));
  EXPECT_TRUE(sameResult(results[1], r));
  fresh.reset();
  // The shared object still works after a fresh one came and went (GL: contexts switched).
  EXPECT_TRUE(sameResult(results[0], render(s.scene.mesh, view, scenes::makeCamera(view, 64, 36, 500.0,
                                                                                  ClipDepth::ZeroToOne, true, 0))));
}

TEST_P(Reuse, FlipYReversesTheRows) {
  const LoadedScene& s = loadScene("sphere-plane");
  const scenes::View& view = s.scene.views.front();
  Camera camera = scenes::makeCamera(view, 80, 45, INFINITY, ClipDepth::ZeroToOne, true, 2);
  prepass::PrepassOptions o;
  o.secondLayer = true;
  const auto up = render(s.scene.mesh, view, camera, o);
  camera.flipY = true;
  const auto down = render(s.scene.mesh, view, camera, o);
  const Extent e = up.depth.extent;
  std::size_t differ = 0;
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x) {
      const std::size_t i = std::size_t(y) * e.width + x, j = std::size_t(e.height - 1 - y) * e.width + x;
      differ += up.depth.texels[i] != down.depth.texels[j] || up.depth2.texels[i] != down.depth2.texels[j] ||
                std::memcmp(&up.position.data[4 * i], &down.position.data[4 * j], 16) != 0;
    }
  EXPECT_EQ(differ, 0u);
  // And it is what the ray cast sees with the flipped camera.
  raytrace::Primary ray;
  ASSERT_TRUE(raytrace::castPrimary(*s.rays, view, camera, DepthFormat::D32F, ray));
  const RayAgreement a = compareWithRayCast(down, ray, camera, DepthFormat::D32F, worldScale(s.scene.mesh, view));
  EXPECT_EQ(a.coverageMismatch, 0u) << describe(a);
  EXPECT_LE(a.zWorstBoundRatio, 1.0) << describe(a);
}

TEST_P(Reuse, ManyCyclesDoNotGrow) {
  const LoadedScene& s = loadScene("crease");
  const scenes::View& view = s.scene.views.front();
  auto cycle = [&](int i) {
    const Camera camera = scenes::makeCamera(view, 64 + 16 * (i % 3), 36 + 8 * (i % 2), INFINITY, ClipDepth::ZeroToOne,
                                             true, std::uint32_t(i % 4));
    prepass::PrepassOptions o;
    o.format = i % 2 ? DepthFormat::D16 : DepthFormat::D32F;
    o.secondLayer = i % 3 == 0;
    (void)render(s.scene.mesh, view, camera, o);
  };
  for (int i = 0; i < 30; ++i) cycle(i);
  const std::uint64_t before = residentBytes();
  for (int i = 0; i < 300; ++i) cycle(i);
  const std::uint64_t after = residentBytes();
  std::printf("%s: resident %.1f MB -> %.1f MB over 300 renders\n", GetParam().c_str(), double(before) / 1e6,
              double(after) / 1e6);
  if (!sanitized()) {
    EXPECT_LT(after, before + 16u * 1024 * 1024);
  }
}

TEST_P(Reuse, CreateAndDestroyCycles) {
  const LoadedScene& s = loadScene("crease");
  const scenes::View& view = s.scene.views.front();
  const Camera camera = scenes::makeCamera(view, 48, 27, INFINITY, ClipDepth::ZeroToOne, true, 0);
  auto once = [&] {
    std::unique_ptr<prepass::Prepass> p;
#ifdef SAO_PREPASS_HAVE_GL
    if (GetParam() == "gl") {
      std::unique_ptr<prepass::GlPrepass> g;
      ASSERT_TRUE(prepass::GlPrepass::create(g));
      p = std::move(g);
    }
#endif
#ifdef SAO_PREPASS_HAVE_VULKAN
    if (GetParam() == "vulkan") {
      std::unique_ptr<prepass::VkPrepass> v;
      ASSERT_TRUE(prepass::VkPrepass::create(vkPrepass().context(), v));
      p = std::move(v);
    }
#endif
    prepass::PrepassOptions o;
    o.secondLayer = true;
    prepass::PrepassResult r;
    ASSERT_TRUE(p->render(s.scene.mesh, view, camera, o, r));
  };
  for (int i = 0; i < 5; ++i) once();
  const std::uint64_t before = residentBytes();
  for (int i = 0; i < 40; ++i) once();
  const std::uint64_t after = residentBytes();
  std::printf("%s: resident %.1f MB -> %.1f MB over 40 create/render/destroy cycles\n", GetParam().c_str(),
              double(before) / 1e6, double(after) / 1e6);
  if (!sanitized()) {
    EXPECT_LT(after, before + 16u * 1024 * 1024);
  }
}

GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(Reuse);  // a build without GL and Vulkan
INSTANTIATE_TEST_SUITE_P(Backends, Reuse, ::testing::ValuesIn(backendNames()),
                         [](const auto& info) { return info.param; });

#ifdef SAO_PREPASS_HAVE_GL
// GlPrepass in the caller's context: same result as with its own context, and every piece of state
// it touches put back.
TEST_F(PrepassTest, GlInTheCallersContextRestoresState) {
  const LoadedScene& s = loadScene("sphere-plane");
  const scenes::View& view = s.scene.views.front();
  const Camera camera = scenes::makeCamera(view, 96, 54, INFINITY, ClipDepth::ZeroToOne, true, 4);
  prepass::PrepassOptions o;
  o.secondLayer = true;
  prepass::PrepassResult reference;
  ASSERT_TRUE(glPrepass().render(s.scene.mesh, view, camera, o, reference));

  std::unique_ptr<gl::HeadlessContext> ctx;
  gl::HeadlessOptions ho;
  ho.major = 4;
  ho.minor = 5;
  ASSERT_TRUE(gl::HeadlessContext::create(ctx, ho));  // current now
  std::unique_ptr<prepass::GlPrepass> inContext;
  prepass::GlPrepassOptions po;
  po.ownContext = false;
  ASSERT_TRUE(prepass::GlPrepass::create(inContext, po));
  EXPECT_EQ(inContext->context(), nullptr);

  // The caller's odd state.
  GLuint fbo = 0, tex = 0, ubo = 0, unit1 = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &tex);
  glTextureStorage2D(tex, 1, GL_RGBA8, 8, 8);
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glCreateTextures(GL_TEXTURE_2D, 1, &unit1);
  glTextureStorage2D(unit1, 1, GL_R8, 4, 4);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, unit1);
  glActiveTexture(GL_TEXTURE3);
  glCreateBuffers(1, &ubo);
  glNamedBufferStorage(ubo, 256, nullptr, 0);
  glBindBufferRange(GL_UNIFORM_BUFFER, 0, ubo, 0, 128);
  glViewport(1, 2, 3, 4);
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 0, 2, 2);
  glEnable(GL_BLEND);
  glEnable(GL_CULL_FACE);
  glEnable(GL_DEPTH_CLAMP);
  glDepthFunc(GL_ALWAYS);
  glDepthMask(GL_FALSE);
  glColorMaski(0, GL_FALSE, GL_TRUE, GL_FALSE, GL_TRUE);
  glClipControl(GL_UPPER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glProvokingVertex(GL_LAST_VERTEX_CONVENTION);
  glPixelStorei(GL_PACK_ALIGNMENT, 8);
  glPixelStorei(GL_PACK_ROW_LENGTH, 7);
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);

  prepass::PrepassResult r;
  const Status st = inContext->render(s.scene.mesh, view, camera, o, r);
  ASSERT_TRUE(st) << st.message;
  EXPECT_TRUE(sameResult(reference, r));

  GLint i = 0, v[4]{};
  GLboolean b[4]{};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &i);
  EXPECT_EQ(GLuint(i), fbo);
  glGetIntegerv(GL_VIEWPORT, v);
  EXPECT_TRUE(v[0] == 1 && v[1] == 2 && v[2] == 3 && v[3] == 4);
  EXPECT_TRUE(glIsEnabled(GL_SCISSOR_TEST) && glIsEnabled(GL_BLEND) && glIsEnabled(GL_CULL_FACE) &&
              glIsEnabled(GL_DEPTH_CLAMP));
  EXPECT_FALSE(glIsEnabled(GL_DEPTH_TEST));
  glGetIntegerv(GL_DEPTH_FUNC, &i);
  EXPECT_EQ(i, GL_ALWAYS);
  glGetBooleanv(GL_DEPTH_WRITEMASK, b);
  EXPECT_EQ(b[0], GL_FALSE);
  glGetBooleani_v(GL_COLOR_WRITEMASK, 0, b);
  EXPECT_TRUE(!b[0] && b[1] && !b[2] && b[3]);
  glGetIntegerv(GL_CLIP_ORIGIN, &i);
  EXPECT_EQ(i, GL_UPPER_LEFT);
  glGetIntegerv(GL_CLIP_DEPTH_MODE, &i);
  EXPECT_EQ(i, GL_NEGATIVE_ONE_TO_ONE);
  glGetIntegerv(GL_PROVOKING_VERTEX, &i);
  EXPECT_EQ(i, GL_LAST_VERTEX_CONVENTION);
  glGetIntegerv(GL_PACK_ALIGNMENT, &i);
  EXPECT_EQ(i, 8);
  glGetIntegerv(GL_PACK_ROW_LENGTH, &i);
  EXPECT_EQ(i, 7);
  glGetIntegerv(GL_POLYGON_MODE, v);
  EXPECT_EQ(v[0], GL_LINE);
  glGetIntegerv(GL_ACTIVE_TEXTURE, &i);
  EXPECT_EQ(i, GL_TEXTURE3);
  glActiveTexture(GL_TEXTURE1);
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &i);
  EXPECT_EQ(GLuint(i), unit1);
  glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, 0, &i);
  EXPECT_EQ(GLuint(i), ubo);
  GLint64 size = 0;
  glGetInteger64i_v(GL_UNIFORM_BUFFER_SIZE, 0, &size);
  EXPECT_EQ(size, 128);
  glGetIntegerv(GL_CURRENT_PROGRAM, &i);
  EXPECT_EQ(i, 0);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &i);
  EXPECT_EQ(i, 0);
  for (const auto& m : ctx->messages())
    if (m.type == GL_DEBUG_TYPE_ERROR || m.type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR)
      ADD_FAILURE() << gl::HeadlessContext::format(m);

  inContext.reset();  // deletes its objects in the current (caller's) context
  glDeleteFramebuffers(1, &fbo);
  const GLuint textures[2] = {tex, unit1};
  glDeleteTextures(2, textures);
  glDeleteBuffers(1, &ubo);
  ctx.reset();
  EXPECT_TRUE(glPrepass().context()->makeCurrent());
}
#endif

}  // namespace
}  // namespace sao::prepasstest
