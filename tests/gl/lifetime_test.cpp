// 1,000 create -> render -> resize (render at another size) -> destroy cycles of sao::gl::Effect
// in one context (docs/ROBUSTNESS.md). Checked:
//  * GL objects: every texture, buffer, sampler, program, shader, query, framebuffer and vertex
//    array alive in the context is counted (glIs* over every name ever handed out), and the counts
//    are back at the baseline after the first cycles and every 100th;
//  * the effect's own counters: each cycle allocates the same number of textures;
//  * the process RSS after a warm-up (not under the sanitizers, whose allocator quarantine keeps
//    freed memory resident): at most kAllowedGrowth over the measured cycles.
// Sizes are small (the point is the object lifetime, not the pixels) so that the test runs in
// seconds on llvmpipe.
#include <epoxy/gl.h>
#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <fstream>

#include "analytic_scenes.h"
#include "gl_support.h"

namespace sao::gltest {
namespace {

constexpr int kWarmup = 100;
constexpr std::uint64_t kAllowedGrowth = 4ull << 20;  // over 900 cycles: < 5 KB a cycle, far below any texture

bool sanitized() {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#else
  return std::getenv("SAO_SANITIZED") != nullptr;
#endif
}

std::uint64_t residentBytes() {
  malloc_trim(0);
  std::ifstream f("/proc/self/statm");
  std::uint64_t size = 0, resident = 0;
  f >> size >> resident;
  return resident * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
}

// Live GL objects of each kind. Mesa does not reuse names (each glGen* returns a name above every
// one used so far), so the range to scan is found by generating (and deleting) one name of each
// kind: every live object of that kind has a smaller name.
using Census = std::array<std::uint32_t, 8>;
Census census() {
  GLuint high[8] = {};
  glGenTextures(1, &high[0]);
  glGenBuffers(1, &high[1]);
  glGenSamplers(1, &high[2]);
  high[3] = glCreateProgram();
  high[4] = glCreateShader(GL_COMPUTE_SHADER);
  glGenQueries(1, &high[5]);
  glGenFramebuffers(1, &high[6]);
  glGenVertexArrays(1, &high[7]);
  const GLuint limit = *std::max_element(std::begin(high), std::end(high));
  glDeleteTextures(1, &high[0]);
  glDeleteBuffers(1, &high[1]);
  glDeleteSamplers(1, &high[2]);
  glDeleteProgram(high[3]);
  glDeleteShader(high[4]);
  glDeleteQueries(1, &high[5]);
  glDeleteFramebuffers(1, &high[6]);
  glDeleteVertexArrays(1, &high[7]);
  Census c{};
  for (GLuint n = 1; n < limit; ++n) {
    c[0] += glIsTexture(n);
    c[1] += glIsBuffer(n);
    c[2] += glIsSampler(n);
    c[3] += glIsProgram(n);
    c[4] += glIsShader(n);
    c[5] += glIsQuery(n);
    c[6] += glIsFramebuffer(n);
    c[7] += glIsVertexArray(n);
  }
  return c;
}

std::string describe(const Census& c) {
  static const char* kinds[] = {"textures", "buffers", "samplers", "programs", "shaders", "queries", "framebuffers",
                                "vertex arrays"};
  std::string s;
  for (std::size_t i = 0; i < c.size(); ++i) s += (s.empty() ? "" : ", ") + std::to_string(c[i]) + " " + kinds[i];
  return s;
}

struct Frame {
  Camera camera;
  DepthImage depth;
  GLuint texture = 0;
  Frame(std::uint32_t w, std::uint32_t h)
      : camera(gltest::camera(w, h, 2)),
        depth(test::renderDepth(test::sphereOnPlaneScene(), camera, DepthFormat::D24)),
        texture(uploadDepth(depth, GlDepth::D24)) {}
  ~Frame() { deleteTexture(texture); }
  gl::Inputs inputs() const {
    gl::Inputs in;
    in.depth = {texture, gl::kDepthComponent24};
    return in;
  }
};

class Lifetime : public GlTest {};

TEST_F(Lifetime, CreateRenderResizeDestroy1000Times) {
  // Under the sanitizers RSS is not checked (see sanitized()), so past the exact census the cycles
  // only cost time there: 250 keep every check of the loop (census, allocations, debug messages).
  const int cycles = sanitized() ? 250 : 1000;
  const Frame a(32, 18), b(40, 24);
  const Settings settings;  // defaults: the z hierarchy, both blurs, every pass
  const Census baseline = census();
  std::printf("live GL objects before: %s\n", describe(baseline).c_str());

  std::uint64_t rssWarm = 0, allocationsPerCycle = 0;
  GLuint highestName = 0;
  for (int i = 0; i < cycles; ++i) {
    {
      auto e = makeEffect();
      ASSERT_TRUE(e);
      Status st = e->render(a.camera, settings, a.inputs());
      ASSERT_TRUE(st.ok()) << "cycle " << i << ": " << st.message;
      st = e->render(b.camera, settings, b.inputs());  // the resize
      ASSERT_TRUE(st.ok()) << "cycle " << i << ": " << st.message;
      ASSERT_EQ(e->plan().aoExtent, (Extent{40, 24}));
      if (i == 0) allocationsPerCycle = e->stats().textureAllocations;
      ASSERT_EQ(e->stats().textureAllocations, allocationsPerCycle) << "cycle " << i;
      for (std::size_t r = 0; r < gen::kResources.size(); ++r)
        highestName = std::max(highestName, GLuint(e->texture(static_cast<gen::ResourceId>(r))));
      if (i == 0) {  // the census sees the effect's objects while it lives
        const Census inside = census();
        std::printf("live GL objects with an effect: %s\n", describe(inside).c_str());
        EXPECT_GT(inside[0], baseline[0]);  // its textures and views
        EXPECT_GT(inside[1], baseline[1]);  // the parameter buffer
        EXPECT_GT(inside[2], baseline[2]);  // its samplers
        EXPECT_GT(inside[3], baseline[3]);  // its programs
      }
    }
    if (i % 100 == 99 || i < 3) {
      const Census now = census();
      ASSERT_EQ(now, baseline) << "after cycle " << i << ": " << describe(now);
    }
    if (i == kWarmup - 1) rssWarm = residentBytes();
    if (i % 250 == 249) {
      for (const auto& m : context().errors()) ADD_FAILURE() << "by cycle " << i << ": " << gl::HeadlessContext::format(m);
      context().clearMessages();
    }
  }
  const std::uint64_t rssEnd = residentBytes();
  const double growth = double(rssEnd) - double(rssWarm);
  std::printf("%d create/render/resize/destroy cycles: %llu effect textures a cycle (texture names reached %u: Mesa does not reuse names); "
              "live GL objects back to the baseline (%s); RSS growth over cycles %d..%d %+.3f MiB%s\n",
              cycles, (unsigned long long)allocationsPerCycle, highestName, describe(census()).c_str(), kWarmup,
              cycles, growth / 1048576.0, sanitized() ? " (not checked under the sanitizers)" : "");
  if (!sanitized()) {
    EXPECT_LE(growth, double(kAllowedGrowth)) << "host memory grows with create/destroy cycles";
  }
}

}  // namespace
}  // namespace sao::gltest
