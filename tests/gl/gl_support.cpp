#include "gl_support.h"

#include <epoxy/gl.h>

#include <cstdio>
#include <cstdlib>

namespace sao::gltest {

std::uint32_t uploadDepth(const DepthImage& depth, GlDepth format) {
  std::uint32_t t = 0;
  const Status st = gl::uploadDepth(depth, format, t);
  EXPECT_TRUE(st.ok()) << st.message;
  return t;
}

std::uint32_t uploadNormals(const FloatImage& normals) {
  std::uint32_t t = 0;
  const Status st = gl::uploadNormals(normals, t);
  EXPECT_TRUE(st.ok()) << st.message;
  return t;
}

std::uint32_t makeTextureArray(std::uint32_t internalFormat, Extent extent, std::uint32_t layers) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &t);
  glTextureStorage3D(t, 1, GLenum(internalFormat), GLsizei(extent.width), GLsizei(extent.height), GLsizei(layers));
  return t;
}

std::uint32_t uploadDepthArray(std::uint32_t internalFormat, const std::vector<const DepthImage*>& layers) {
  const Extent e = layers.front()->extent;
  const GLuint t = makeTextureArray(internalFormat, e, std::uint32_t(layers.size()));
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (std::size_t l = 0; l < layers.size(); ++l) {
    std::vector<float> values(layers[l]->texels.size());
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = float(decodeDepth(layers[l]->format, layers[l]->texels[i]));
    glTextureSubImage3D(t, 0, 0, 0, GLint(l), GLsizei(e.width), GLsizei(e.height), 1, GL_DEPTH_COMPONENT, GL_FLOAT,
                        values.data());
  }
  return t;
}

gl::HeadlessContext& context() {
  static std::unique_ptr<gl::HeadlessContext> ctx = [] {
    std::unique_ptr<gl::HeadlessContext> c;
    const Status st = gl::HeadlessContext::create(c);
    if (!st) {
      std::fprintf(stderr, "no headless GL context: %s\n", st.message.c_str());
      std::abort();
    }
    std::printf("GL context: %s\n", c->description().c_str());
    return c;
  }();
  return *ctx;
}

void GlTest::SetUp() { context().clearMessages(); }

void GlTest::TearDown() {
  for (const auto& m : context().errors()) ADD_FAILURE() << "GL debug message: " << gl::HeadlessContext::format(m);
  context().clearMessages();
}

std::unique_ptr<gl::Effect> GlTest::makeEffect() {
  std::unique_ptr<gl::Effect> e;
  const Status st = gl::Effect::create(gl::HeadlessContext::getProcAddress(), e);
  EXPECT_TRUE(st.ok()) << st.message;
  return e;
}

std::string failureDir() { return SAO_GL_TEST_FAILURE_DIR; }

test::Scene sceneByName(const std::string& name) {
  if (name == "plane") return test::planeScene(3.0);
  if (name == "crease") return test::creaseScene(2.0);
  if (name == "sphere") return test::sphereOnPlaneScene();
  if (name == "stairs") return test::stairsScene();
  return test::rodsScene();
}

}  // namespace sao::gltest
