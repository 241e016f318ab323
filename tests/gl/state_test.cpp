// State hygiene: a broad snapshot of GL state is identical before and after render(), and the
// caller's texture parameters (compare mode, base/max level, depth-stencil texture mode, swizzle,
// filters) do not change the result.
#include <epoxy/gl.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <sstream>

#include "analytic_scenes.h"
#include <ostream>

#include "gl_support.h"
#include "sao/presets.h"

namespace sao::gltest {
namespace {

using Snapshot = std::map<std::string, std::vector<long long>>;

std::vector<long long> ints(GLenum pname, int count = 1) {
  std::vector<GLint64> v(std::size_t(std::max(count, 16)), 0);
  glGetInteger64v(pname, v.data());
  return {v.begin(), v.begin() + count};
}

long long intAt(GLenum pname, GLuint index) {
  GLint64 v = 0;
  glGetInteger64i_v(pname, index, &v);
  return v;
}

std::string hex(GLenum e) {
  std::ostringstream s;
  s << "0x" << std::hex << e;
  return s.str();
}

// Texture parameters through DSA (no binding changes while snapshotting).
void textureParams(Snapshot& s, const std::string& name, GLuint tex) {
  const GLenum params[] = {GL_TEXTURE_BASE_LEVEL,   GL_TEXTURE_MAX_LEVEL,  GL_TEXTURE_COMPARE_MODE,
                           GL_TEXTURE_COMPARE_FUNC, GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER,
                           GL_TEXTURE_SWIZZLE_R,    GL_TEXTURE_SWIZZLE_G,  GL_TEXTURE_SWIZZLE_B,
                           GL_TEXTURE_SWIZZLE_A,    GL_TEXTURE_WRAP_S,     GL_TEXTURE_WRAP_T,
                           GL_DEPTH_STENCIL_TEXTURE_MODE};
  for (GLenum p : params) {
    GLint v = 0;
    glGetTextureParameteriv(tex, p, &v);
    s[name + " param " + hex(p)] = {v};
  }
  GLfloat lod[2] = {};
  glGetTextureParameterfv(tex, GL_TEXTURE_MIN_LOD, &lod[0]);
  glGetTextureParameterfv(tex, GL_TEXTURE_MAX_LOD, &lod[1]);
  s[name + " lod"] = {std::bit_cast<std::int32_t>(lod[0]), std::bit_cast<std::int32_t>(lod[1])};
}

Snapshot snapshot(const std::vector<std::pair<std::string, GLuint>>& textures) {
  Snapshot s;
  const GLenum single[] = {
      GL_CURRENT_PROGRAM, GL_ACTIVE_TEXTURE, GL_PROGRAM_PIPELINE_BINDING, GL_VERTEX_ARRAY_BINDING,
      GL_ARRAY_BUFFER_BINDING, GL_ELEMENT_ARRAY_BUFFER_BINDING, GL_COPY_READ_BUFFER_BINDING,
      GL_COPY_WRITE_BUFFER_BINDING, GL_PIXEL_PACK_BUFFER_BINDING, GL_PIXEL_UNPACK_BUFFER_BINDING,
      GL_DISPATCH_INDIRECT_BUFFER_BINDING, GL_DRAW_INDIRECT_BUFFER_BINDING, GL_QUERY_BUFFER_BINDING,
      GL_UNIFORM_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_BINDING, GL_ATOMIC_COUNTER_BUFFER_BINDING,
      GL_TRANSFORM_FEEDBACK_BUFFER_BINDING, GL_TRANSFORM_FEEDBACK_BINDING, GL_DRAW_FRAMEBUFFER_BINDING,
      GL_READ_FRAMEBUFFER_BINDING, GL_RENDERBUFFER_BINDING, GL_READ_BUFFER, GL_DRAW_BUFFER0,
      GL_PACK_ALIGNMENT, GL_UNPACK_ALIGNMENT, GL_PACK_ROW_LENGTH, GL_UNPACK_ROW_LENGTH, GL_PACK_SKIP_ROWS,
      GL_UNPACK_SKIP_ROWS, GL_PACK_SKIP_PIXELS, GL_UNPACK_SKIP_PIXELS, GL_PACK_IMAGE_HEIGHT,
      GL_UNPACK_IMAGE_HEIGHT, GL_PACK_SWAP_BYTES, GL_UNPACK_SWAP_BYTES, GL_DEPTH_WRITEMASK, GL_DEPTH_FUNC,
      GL_STENCIL_WRITEMASK, GL_CULL_FACE_MODE, GL_FRONT_FACE, GL_BLEND_SRC_RGB, GL_BLEND_DST_RGB,
      GL_BLEND_EQUATION_RGB, GL_POLYGON_MODE, GL_PATCH_VERTICES, GL_PROVOKING_VERTEX,
  };
  for (GLenum p : single) s["get " + hex(p)] = ints(p, p == GL_POLYGON_MODE ? 2 : 1);
  s["viewport"] = ints(GL_VIEWPORT, 4);
  s["scissor box"] = ints(GL_SCISSOR_BOX, 4);
  s["color writemask"] = ints(GL_COLOR_WRITEMASK, 4);
  s["depth range"] = ints(GL_DEPTH_RANGE, 2);
  const GLenum caps[] = {GL_SCISSOR_TEST,      GL_DEPTH_TEST,         GL_BLEND,
                         GL_CULL_FACE,         GL_STENCIL_TEST,       GL_RASTERIZER_DISCARD,
                         GL_FRAMEBUFFER_SRGB,  GL_DEBUG_OUTPUT,       GL_DEBUG_OUTPUT_SYNCHRONOUS,
                         GL_PRIMITIVE_RESTART, GL_PROGRAM_POINT_SIZE, GL_TEXTURE_CUBE_MAP_SEAMLESS,
                         GL_POLYGON_OFFSET_FILL, GL_MULTISAMPLE,      GL_DITHER};
  for (GLenum c : caps) s["enabled " + hex(c)] = {glIsEnabled(c)};
  // Texture units: every target's binding and the sampler (the snapshot restores the active unit).
  GLint active = 0, units = 0;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &units);
  const GLenum targets[] = {GL_TEXTURE_BINDING_1D,
                            GL_TEXTURE_BINDING_2D,
                            GL_TEXTURE_BINDING_3D,
                            GL_TEXTURE_BINDING_1D_ARRAY,
                            GL_TEXTURE_BINDING_2D_ARRAY,
                            GL_TEXTURE_BINDING_RECTANGLE,
                            GL_TEXTURE_BINDING_CUBE_MAP,
                            GL_TEXTURE_BINDING_CUBE_MAP_ARRAY,
                            GL_TEXTURE_BINDING_BUFFER,
                            GL_TEXTURE_BINDING_2D_MULTISAMPLE,
                            GL_TEXTURE_BINDING_2D_MULTISAMPLE_ARRAY,
                            GL_SAMPLER_BINDING};
  for (GLint u = 0; u < std::min(units, 32); ++u) {
    glActiveTexture(GLenum(GL_TEXTURE0 + u));
    std::vector<long long> v;
    for (GLenum t : targets) v.push_back(ints(t)[0]);
    s["texture unit " + std::to_string(u)] = v;
  }
  glActiveTexture(GLenum(active));
  GLint imageUnits = 0;
  glGetIntegerv(GL_MAX_IMAGE_UNITS, &imageUnits);
  for (GLint u = 0; u < imageUnits; ++u)
    s["image unit " + std::to_string(u)] = {intAt(GL_IMAGE_BINDING_NAME, GLuint(u)),
                                            intAt(GL_IMAGE_BINDING_LEVEL, GLuint(u)),
                                            intAt(GL_IMAGE_BINDING_LAYERED, GLuint(u)),
                                            intAt(GL_IMAGE_BINDING_LAYER, GLuint(u)),
                                            intAt(GL_IMAGE_BINDING_ACCESS, GLuint(u)),
                                            intAt(GL_IMAGE_BINDING_FORMAT, GLuint(u))};
  struct Indexed {
    const char* name;
    GLenum max, binding, start, size;
  };
  const Indexed indexed[] = {
      {"ubo", GL_MAX_UNIFORM_BUFFER_BINDINGS, GL_UNIFORM_BUFFER_BINDING, GL_UNIFORM_BUFFER_START,
       GL_UNIFORM_BUFFER_SIZE},
      {"ssbo", GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, GL_SHADER_STORAGE_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_START,
       GL_SHADER_STORAGE_BUFFER_SIZE},
      {"atomic", GL_MAX_ATOMIC_COUNTER_BUFFER_BINDINGS, GL_ATOMIC_COUNTER_BUFFER_BINDING,
       GL_ATOMIC_COUNTER_BUFFER_START, GL_ATOMIC_COUNTER_BUFFER_SIZE},
      {"xfb", GL_MAX_TRANSFORM_FEEDBACK_BUFFERS, GL_TRANSFORM_FEEDBACK_BUFFER_BINDING,
       GL_TRANSFORM_FEEDBACK_BUFFER_START, GL_TRANSFORM_FEEDBACK_BUFFER_SIZE},
  };
  for (const Indexed& ix : indexed) {
    GLint n = 0;
    glGetIntegerv(ix.max, &n);
    for (GLint i = 0; i < std::min(n, 32); ++i)
      s[std::string(ix.name) + " " + std::to_string(i)] = {intAt(ix.binding, GLuint(i)), intAt(ix.start, GLuint(i)),
                                                           intAt(ix.size, GLuint(i))};
  }
  const GLenum queryTargets[] = {GL_TIME_ELAPSED, GL_SAMPLES_PASSED, GL_ANY_SAMPLES_PASSED, GL_PRIMITIVES_GENERATED};
  for (GLenum q : queryTargets) {
    GLint v = 0;
    glGetQueryiv(q, GL_CURRENT_QUERY, &v);
    s["current query " + hex(q)] = {v};
  }
  for (const auto& [name, tex] : textures) textureParams(s, name, tex);
  return s;
}

std::string differences(const Snapshot& a, const Snapshot& b) {
  std::ostringstream out;
  for (const auto& [k, v] : a) {
    auto it = b.find(k);
    if (it == b.end() || it->second != v) {
      out << "  " << k << ": before {";
      for (auto x : v) out << " " << x;
      out << " } after {";
      if (it != b.end())
        for (auto x : it->second) out << " " << x;
      out << " }\n";
    }
  }
  return out.str();
}

GLuint makeBuffer(GLsizeiptr size) {
  GLuint b = 0;
  glCreateBuffers(1, &b);
  glNamedBufferData(b, size, nullptr, GL_DYNAMIC_DRAW);
  return b;
}

GLuint makeTex(GLenum target, GLenum format, int levels, int w, int h, int d = 1) {
  GLuint t = 0;
  glCreateTextures(target, 1, &t);
  if (target == GL_TEXTURE_2D_ARRAY || target == GL_TEXTURE_3D) glTextureStorage3D(t, levels, format, w, h, d);
  else glTextureStorage2D(t, levels, format, w, h);
  return t;
}

class State : public GlTest {};

// The caller's state is busy: every kind of binding the effect might touch holds something else.
TEST_F(State, RenderRestoresEverything) {
  const Camera cam = camera(160, 90, 8);
  const DepthImage depth = test::renderDepth(test::sphereOnPlaneScene(), cam, DepthFormat::D24);
  const GLuint depthTex = uploadDepth(depth, GlDepth::D24S8);
  const GLuint normalTex = uploadNormals(test::renderNormals(test::sphereOnPlaneScene(), cam));
  const GLuint outTex = makeTexture(GL_R16F, {160, 90});

  // A program of the caller's.
  const char* src = "#version 430\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
  const GLuint sh = glCreateShader(GL_COMPUTE_SHADER);
  glShaderSource(sh, 1, &src, nullptr);
  glCompileShader(sh);
  const GLuint prog = glCreateProgram();
  glAttachShader(prog, sh);
  glLinkProgram(prog);
  glDeleteShader(sh);
  glUseProgram(prog);

  // Textures and samplers on the first 16 units, several targets each.
  std::vector<GLuint> texs, samplers;
  for (int u = 0; u < 16; ++u) {
    const GLuint t2 = makeTex(GL_TEXTURE_2D, GL_RGBA8, 3, 8, 8);
    const GLuint ta = makeTex(GL_TEXTURE_2D_ARRAY, GL_RGBA8, 1, 4, 4, 2);
    const GLuint tc = makeTex(GL_TEXTURE_CUBE_MAP, GL_RGBA8, 1, 4, 4);
    GLuint smp = 0;
    glCreateSamplers(1, &smp);
    glActiveTexture(GLenum(GL_TEXTURE0 + u));
    glBindTexture(GL_TEXTURE_2D, t2);
    glBindTexture(GL_TEXTURE_2D_ARRAY, ta);
    glBindTexture(GL_TEXTURE_CUBE_MAP, tc);
    glBindSampler(GLuint(u), smp);
    texs.insert(texs.end(), {t2, ta, tc});
    samplers.push_back(smp);
  }
  glActiveTexture(GL_TEXTURE5);
  // Image units with various levels, layers, access and formats.
  GLint imageUnits = 0;
  glGetIntegerv(GL_MAX_IMAGE_UNITS, &imageUnits);
  for (GLint u = 0; u < std::min(imageUnits, 8); ++u) {
    const GLuint t = makeTex(GL_TEXTURE_2D_ARRAY, GL_RGBA16F, 2, 8, 8, 3);
    texs.push_back(t);
    glBindImageTexture(GLuint(u), t, u % 2, u % 3 == 0 ? GL_TRUE : GL_FALSE, u % 3, u % 2 ? GL_READ_WRITE : GL_READ_ONLY,
                       u % 2 ? GL_RGBA16F : GL_RG32F);
  }
  // Buffers: generic and indexed uniform / storage / atomic bindings, with ranges.
  GLint uboAlign = 256, ssboAlign = 256;
  glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &uboAlign);
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &ssboAlign);
  std::vector<GLuint> bufs;
  for (int i = 0; i < 10; ++i) bufs.push_back(makeBuffer(4096));
  glBindBufferRange(GL_UNIFORM_BUFFER, 0, bufs[0], uboAlign, 512);
  glBindBufferBase(GL_UNIFORM_BUFFER, 1, bufs[1]);
  glBindBufferRange(GL_UNIFORM_BUFFER, 3, bufs[2], 0, 256);
  glBindBuffer(GL_UNIFORM_BUFFER, bufs[3]);
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, bufs[4], ssboAlign, 1024);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, bufs[5]);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, bufs[6]);
  glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 0, bufs[7]);
  glBindBuffer(GL_QUERY_BUFFER, bufs[8]);  // would catch query results read into "pointers"
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, bufs[9]);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, bufs[9]);
  glBindBuffer(GL_COPY_WRITE_BUFFER, bufs[2]);
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  glBindVertexArray(vao);
  // Framebuffers, viewport, scissor, pixel store, capabilities.
  GLuint fbo[2] = {}, rb = 0;
  glCreateFramebuffers(2, fbo);
  glCreateRenderbuffers(1, &rb);
  glNamedRenderbufferStorage(rb, GL_RGBA8, 32, 32);
  glNamedFramebufferRenderbuffer(fbo[0], GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo[0]);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo[1]);
  glBindRenderbuffer(GL_RENDERBUFFER, rb);
  glViewport(3, 4, 50, 60);
  glScissor(1, 2, 30, 40);
  glEnable(GL_SCISSOR_TEST);
  glEnable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GEQUAL);
  glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 7);
  glPixelStorei(GL_PACK_SKIP_ROWS, 3);
  // The caller's parameters on its depth texture.
  glTextureParameteri(depthTex, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTextureParameteri(depthTex, GL_TEXTURE_COMPARE_FUNC, GL_NEVER);
  glTextureParameteri(depthTex, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
  glTextureParameteri(depthTex, GL_TEXTURE_SWIZZLE_R, GL_ZERO);
  glTextureParameteri(depthTex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(depthTex, GL_TEXTURE_MAX_LEVEL, 5);

  const std::vector<std::pair<std::string, GLuint>> watched = {
      {"depth", depthTex}, {"normals", normalTex}, {"output", outTex}, {"unit-2 texture", texs[3]}};
  auto e = makeEffect();
  gl::Inputs in;
  in.depth = {depthTex, gl::kDepth24Stencil8};
  in.normals = normalTex;
  const Snapshot before = snapshot(watched);

  // Owned output, then the caller's; timed (the first timed frame tries GPU queries) and not.
  for (int round = 0; round < 4; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    in.output = round >= 2 ? outTex : 0;
    Settings s = presetSettings(round % 2 ? Preset::Reference : Preset::High);
    const Status st = e->render(cam, s, in, {round < 3});
    ASSERT_TRUE(st.ok()) << st.message;
    const Snapshot after = snapshot(watched);
    EXPECT_EQ(before.size(), after.size());
    const std::string diff = differences(before, after);
    EXPECT_TRUE(diff.empty()) << "GL state changed by render():\n" << diff;
  }
  // An RGBA8 output keeping channels: its image unit is bound GL_READ_WRITE, and restored too.
  {
    gl::Inputs packed = in;
    packed.output = makeTexture(GL_RGBA8, {160, 90});
    packed.outputChannels = kChannelA;
    const Status st = e->render(cam, presetSettings(Preset::High), packed);
    EXPECT_TRUE(st.ok()) << st.message;
    deleteTexture(packed.output);
    const std::string diff = differences(before, snapshot(watched));
    EXPECT_TRUE(diff.empty()) << "GL state changed by a read-modify-write render():\n" << diff;
  }
  // A failing render restores the state too (it fails after binding textures for inspection).
  {
    gl::Inputs bad = in;
    bad.output = makeTexture(GL_RG16F, {160, 90});  // not an output format
    const Status st = e->render(cam, Settings{}, bad);
    EXPECT_EQ(st.code, StatusCode::UnsupportedFormat);
    deleteTexture(bad.output);
    const std::string diff = differences(before, snapshot(watched));
    EXPECT_TRUE(diff.empty()) << "GL state changed by a failing render():\n" << diff;
  }
  // The output is still right with all that state around (compare with a clean render).
  const FloatImage busy = readTexture(outTex, 1);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glUseProgram(0);
  glBindVertexArray(0);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  glBindBuffer(GL_QUERY_BUFFER, 0);
  for (auto t : texs) glDeleteTextures(1, &t);
  for (auto smp : samplers) glDeleteSamplers(1, &smp);
  for (auto b : bufs) glDeleteBuffers(1, &b);
  glDeleteFramebuffers(2, fbo);
  glDeleteRenderbuffers(1, &rb);
  glDeleteVertexArrays(1, &vao);
  glDeleteProgram(prog);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glPixelStorei(GL_PACK_SKIP_ROWS, 0);
  const GLuint cleanDepth = uploadDepth(depth, GlDepth::D24S8);
  auto clean = makeEffect();
  gl::Inputs cin;
  cin.depth = {cleanDepth, 0};
  cin.normals = normalTex;
  ASSERT_TRUE(clean->render(cam, presetSettings(Preset::Reference), cin).ok());
  const FloatImage expected = readTexture(clean->aoTexture(), 1);
  EXPECT_EQ(busy.data, expected.data);
  deleteTexture(cleanDepth);
  deleteTexture(depthTex);
  deleteTexture(normalTex);
  deleteTexture(outTex);
}

// ---- The caller's texture parameters do not change the result.

// The caller left the effect's own output bound (texture and image unit) and the next render()
// reallocates it for a new size: the restore must not bind the deleted name again (a GL error);
// the units end up as GL leaves a unit whose texture was deleted, empty. Found by the windowed
// integration example (samples/integration/gl_glfw_window.cpp).
TEST_F(State, TheEffectsOldOutputLeftBoundSurvivesAResize) {
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  Settings s = presetSettings(Preset::Low);
  for (const auto& [w, h] : {std::pair{96u, 64u}, std::pair{128u, 72u}}) {
    const Camera cam = camera(w, h, 0);
    const GLuint depthTex = uploadDepth(test::renderDepth(test::sphereOnPlaneScene(), cam, DepthFormat::D24), GlDepth::D24S8);
    gl::Inputs in;
    in.depth = {depthTex, gl::kDepth24Stencil8};
    const GLuint before = effect->aoTexture();
    ASSERT_TRUE(effect->render(cam, s, in).ok());
    deleteTexture(depthTex);
    if (before == 0) {  // first frame: bind its output everywhere the effect binds things
      for (GLuint u = 0; u < 8; ++u) {
        glActiveTexture(GL_TEXTURE0 + u);
        glBindTexture(GL_TEXTURE_2D, effect->aoTexture());
        glBindImageTexture(u, effect->aoTexture(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R16F);
      }
      glActiveTexture(GL_TEXTURE0);
      continue;
    }
    ASSERT_NE(effect->aoTexture(), before) << "the resize did not reallocate the output";
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    for (GLuint u = 0; u < 8; ++u) {
      GLint texture = -1, image = -1;
      glActiveTexture(GL_TEXTURE0 + u);
      glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture);
      glGetIntegeri_v(GL_IMAGE_BINDING_NAME, u, &image);
      EXPECT_EQ(texture, 0) << "texture unit " << u;
      EXPECT_EQ(image, 0) << "image unit " << u;
    }
    glActiveTexture(GL_TEXTURE0);
  }
}

struct ParamCase {
  const char* name;
  GlDepth format;
  GLenum pname;
  GLint value;
};
void PrintTo(const ParamCase& c, std::ostream* os) { *os << c.name; }


class TextureParams : public GlTest, public ::testing::WithParamInterface<ParamCase> {};

TEST_P(TextureParams, DoNotChangeTheResult) {
  const ParamCase pc = GetParam();
  const Camera cam = camera(160, 90, 8);
  const DepthImage depth = test::renderDepth(test::stairsScene(), cam, cpuFormat(pc.format));
  auto e = makeEffect();
  const Settings settings = presetSettings(Preset::Medium);

  const GLuint plain = uploadDepth(depth, pc.format);
  gl::Inputs in;
  in.depth = {plain, internalFormat(pc.format)};
  ASSERT_TRUE(e->render(cam, settings, in).ok());
  const FloatImage expected = readTexture(e->aoTexture(), 1);
  const FloatImage expectedRaw = readTexture(e->texture(gen::ResourceId::ao_raw), 2);

  // The same texels in a texture with two levels (level 1 holds something else: depth 0.5).
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 2, internalFormat(pc.format), GLsizei(depth.extent.width), GLsizei(depth.extent.height));
  glCopyImageSubData(plain, GL_TEXTURE_2D, 0, 0, 0, 0, t, GL_TEXTURE_2D, 0, 0, 0, 0, GLsizei(depth.extent.width),
                     GLsizei(depth.extent.height), 1);
  {
    const std::uint32_t w1 = depth.extent.width / 2, h1 = depth.extent.height / 2;
    std::vector<float> half(std::size_t(w1) * h1, 0.5f);
    if (pc.format == GlDepth::R32F) {
      glTextureSubImage2D(t, 1, 0, 0, GLsizei(w1), GLsizei(h1), GL_RED, GL_FLOAT, half.data());
    } else if (pc.format == GlDepth::D24S8 || pc.format == GlDepth::D32FS8) {
      // Fill level 1 through a framebuffer clear (depth-stencil uploads need packed types).
      GLuint fb = 0;
      glCreateFramebuffers(1, &fb);
      glNamedFramebufferTexture(fb, GL_DEPTH_STENCIL_ATTACHMENT, t, 1);
      glClearNamedFramebufferfi(fb, GL_DEPTH_STENCIL, 0, 0.5f, 7);
      glDeleteFramebuffers(1, &fb);
    } else {
      glTextureSubImage2D(t, 1, 0, 0, GLsizei(w1), GLsizei(h1), GL_DEPTH_COMPONENT, GL_FLOAT, half.data());
    }
  }
  glTextureParameteri(t, pc.pname, pc.value);
  if (pc.pname == GL_TEXTURE_BASE_LEVEL) glTextureParameteri(t, GL_TEXTURE_MAX_LEVEL, 1);
  GLint before = 0;
  glGetTextureParameteriv(t, pc.pname, &before);
  ASSERT_EQ(before, pc.value);
  in.depth = {t, internalFormat(pc.format)};
  ASSERT_TRUE(e->render(cam, settings, in).ok());
  EXPECT_EQ(readTexture(e->aoTexture(), 1).data, expected.data) << pc.name << " changed the final AO";
  EXPECT_EQ(readTexture(e->texture(gen::ResourceId::ao_raw), 2).data, expectedRaw.data)
      << pc.name << " changed the raw AO";
  GLint after = 0;
  glGetTextureParameteriv(t, pc.pname, &after);
  EXPECT_EQ(after, pc.value) << "the parameter was not restored";
  deleteTexture(t);
  deleteTexture(plain);
}

INSTANTIATE_TEST_SUITE_P(
    Params, TextureParams,
    ::testing::Values(
        ParamCase{"CompareModeD24", GlDepth::D24, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE},
        ParamCase{"CompareModeD32F", GlDepth::D32F, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE},
        ParamCase{"CompareFuncNeverD16", GlDepth::D16, GL_TEXTURE_COMPARE_FUNC, GL_NEVER},
        ParamCase{"BaseLevel1D24", GlDepth::D24, GL_TEXTURE_BASE_LEVEL, 1},
        ParamCase{"BaseLevel1R32F", GlDepth::R32F, GL_TEXTURE_BASE_LEVEL, 1},
        ParamCase{"BaseLevel1D24S8", GlDepth::D24S8, GL_TEXTURE_BASE_LEVEL, 1},
        ParamCase{"MaxLevel0D32F", GlDepth::D32F, GL_TEXTURE_MAX_LEVEL, 0},
        ParamCase{"StencilModeD24S8", GlDepth::D24S8, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX},
        ParamCase{"StencilModeD32FS8", GlDepth::D32FS8, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX},
        ParamCase{"SwizzleRD32F", GlDepth::D32F, GL_TEXTURE_SWIZZLE_R, GL_ONE},
        ParamCase{"MinFilterLinearMipmapD24", GlDepth::D24, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR},
        ParamCase{"MagFilterLinearD16", GlDepth::D16, GL_TEXTURE_MAG_FILTER, GL_LINEAR}),
    [](const auto& info) { return std::string(info.param.name); });

// A mutable texture (glTexImage2D) with only level 0 and the default GL_NEAREST_MIPMAP_LINEAR
// filter is mipmap-incomplete by its own state: read through the effect's GL_NEAREST sampler it
// is complete, and unsized GL_DEPTH_COMPONENT / GL_DEPTH_STENCIL are accepted.
TEST_F(GlTest, MutableIncompleteDepthTexture) {
  const Camera cam = camera(160, 90, 8);
  const DepthImage depth = test::renderDepth(test::stairsScene(), cam, DepthFormat::D32F);
  auto e = makeEffect();
  const GLuint plain = uploadDepth(depth, GlDepth::D32F);
  gl::Inputs in;
  in.depth = {plain, gl::kDepthComponent32F};
  ASSERT_TRUE(e->render(cam, Settings{}, in).ok());
  const FloatImage expected = readTexture(e->aoTexture(), 1);

  for (GLenum internal : {GLenum(GL_DEPTH_COMPONENT32F), GLenum(GL_DEPTH_COMPONENT)}) {
    GLuint t = 0;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GLint(internal), GLsizei(depth.extent.width), GLsizei(depth.extent.height), 0,
                 GL_DEPTH_COMPONENT, GL_FLOAT, depth.texels.data());
    glBindTexture(GL_TEXTURE_2D, 0);
    in.depth = {t, 0};
    const Status st = e->render(cam, Settings{}, in);
    ASSERT_TRUE(st.ok()) << st.message;
    if (internal == GL_DEPTH_COMPONENT32F) {
      EXPECT_EQ(readTexture(e->aoTexture(), 1).data, expected.data);
    } else {  // the driver picks the precision of an unsized format: only check it is read as depth
      const FloatImage ao = readTexture(e->aoTexture(), 1);
      double diff = 0;
      for (std::size_t i = 0; i < ao.data.size(); ++i) diff = std::max(diff, double(std::fabs(ao.data[i] - expected.data[i])));
      EXPECT_LT(diff, 4.0 / 255.0);
    }
    deleteTexture(t);
  }
  deleteTexture(plain);
}

}  // namespace
}  // namespace sao::gltest
