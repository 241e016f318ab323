// A windowed OpenGL engine with SAO: GLFW, GL 4.5 core. The engine draws its own scene (boxes on
// a floor) into its own FBO with a depth texture; sao::gl::Effect turns that depth into AO and
// multiplies it into the FBO's colour (the apply step: Inputs::output with OutputBlend::Multiply,
// no composite pass of the engine's own); the engine blits the colour to the window. A resize
// recreates the FBO and the effect follows the camera's new size.
// Uses only the installed sao::gl, GLFW and the GL header (tests/package builds it against the
// package).
//   sao-example-gl-window [--frames N] [--resize WxH]
//   --frames N: exit after N frames (default: until the window is closed); then the last frame's
//               colour is read back before and after the apply, and their ratio (A) must show open
//               floor (A near 1) and contact shadow (A below 0.8).
//   --resize WxH: resize the window to WxH after a third of the frames (or after 100 frames);
//                 with --frames it must have taken effect by the last frame.
// Exit status 1 on any failure, a GL debug message of type error included.
#define GLFW_INCLUDE_NONE
#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include "sao/gl/effect.h"
#include "sao/presets.h"

// The engine's GL entry points, loaded through glfwGetProcAddress (like the effect's).
#define SAO_EXAMPLE_GL(X)                                                                       \
  X(PFNGLCREATESHADERPROC, glCreateShader) X(PFNGLSHADERSOURCEPROC, glShaderSource)             \
  X(PFNGLCOMPILESHADERPROC, glCompileShader) X(PFNGLGETSHADERIVPROC, glGetShaderiv)             \
  X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog) X(PFNGLDELETESHADERPROC, glDeleteShader)     \
  X(PFNGLCREATEPROGRAMPROC, glCreateProgram) X(PFNGLATTACHSHADERPROC, glAttachShader)           \
  X(PFNGLLINKPROGRAMPROC, glLinkProgram) X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)               \
  X(PFNGLDELETEPROGRAMPROC, glDeleteProgram) X(PFNGLUSEPROGRAMPROC, glUseProgram)               \
  X(PFNGLUNIFORMMATRIX4FVPROC, glUniformMatrix4fv) X(PFNGLCREATEBUFFERSPROC, glCreateBuffers)   \
  X(PFNGLNAMEDBUFFERSTORAGEPROC, glNamedBufferStorage)                                          \
  X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers)                                                    \
  X(PFNGLCREATEVERTEXARRAYSPROC, glCreateVertexArrays)                                          \
  X(PFNGLDELETEVERTEXARRAYSPROC, glDeleteVertexArrays)                                          \
  X(PFNGLVERTEXARRAYVERTEXBUFFERPROC, glVertexArrayVertexBuffer)                                \
  X(PFNGLENABLEVERTEXARRAYATTRIBPROC, glEnableVertexArrayAttrib)                                \
  X(PFNGLVERTEXARRAYATTRIBFORMATPROC, glVertexArrayAttribFormat)                                \
  X(PFNGLVERTEXARRAYATTRIBBINDINGPROC, glVertexArrayAttribBinding)                              \
  X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray) X(PFNGLCREATETEXTURESPROC, glCreateTextures)   \
  X(PFNGLTEXTURESTORAGE2DPROC, glTextureStorage2D) X(PFNGLDELETETEXTURESPROC, glDeleteTextures) \
  X(PFNGLGETTEXTUREIMAGEPROC, glGetTextureImage)                                                \
  X(PFNGLCREATEFRAMEBUFFERSPROC, glCreateFramebuffers)                                          \
  X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, glNamedFramebufferTexture)                                \
  X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, glCheckNamedFramebufferStatus)                        \
  X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers)                                          \
  X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                                                \
  X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, glClearNamedFramebufferfv)                                \
  X(PFNGLVIEWPORTPROC, glViewport) X(PFNGLENABLEPROC, glEnable) X(PFNGLDISABLEPROC, glDisable)  \
  X(PFNGLDRAWARRAYSPROC, glDrawArrays) X(PFNGLDEBUGMESSAGECALLBACKPROC, glDebugMessageCallback) \
  X(PFNGLBLITNAMEDFRAMEBUFFERPROC, glBlitNamedFramebuffer)
#define SAO_EXAMPLE_GL_DECLARE(type, name) static type name;
SAO_EXAMPLE_GL(SAO_EXAMPLE_GL_DECLARE)

namespace {

const char* const kSceneVertex = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 0) uniform mat4 viewProjection;
out vec3 worldNormal;
void main() { worldNormal = normal; gl_Position = viewProjection * vec4(position, 1.0); })";
const char* const kSceneFragment = R"(#version 450 core
in vec3 worldNormal;
out vec4 colour;
void main() {
  float sun = max(dot(normalize(worldNormal), normalize(vec3(0.4, 1.0, 0.3))), 0.0);
  colour = vec4(vec3(0.75, 0.7, 0.6) * (0.45 + 0.55 * sun), 1.0);
})";
GLuint compile(const char* vertex, const char* fragment) {
  const GLuint program = glCreateProgram();
  for (auto [type, source] : {std::pair{GL_VERTEX_SHADER, vertex}, std::pair{GL_FRAGMENT_SHADER, fragment}}) {
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[1024] = {};
      glGetShaderInfoLog(shader, sizeof log, nullptr, log);
      std::fprintf(stderr, "shader: %s\n", log);
    }
    glAttachShader(program, shader);
    glDeleteShader(shader);
  }
  glLinkProgram(program);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  if (!linked) std::fprintf(stderr, "a program of the example did not link\n");
  return linked ? program : (glDeleteProgram(program), 0);
}

// The scene: a 10 m floor and three 1 m boxes standing on it, as position + normal triangles.
std::vector<float> sceneTriangles() {
  std::vector<float> v;
  auto quad = [&](const float (&c)[4][3], const float (&n)[3]) {
    for (int i : {0, 1, 2, 0, 2, 3}) v.insert(v.end(), {c[i][0], c[i][1], c[i][2], n[0], n[1], n[2]});
  };
  quad({{-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5}}, {0, 1, 0});
  for (const float x : {-1.6f, 0.0f, 1.6f}) {
    const float a = x - 0.5f, b = x + 0.5f, h = 1.0f, f = 0.5f, k = -0.5f;  // x range, height, z range
    quad({{a, h, f}, {b, h, f}, {b, h, k}, {a, h, k}}, {0, 1, 0});
    quad({{a, 0, f}, {b, 0, f}, {b, h, f}, {a, h, f}}, {0, 0, 1});
    quad({{b, 0, k}, {a, 0, k}, {a, h, k}, {b, h, k}}, {0, 0, -1});
    quad({{b, 0, f}, {b, 0, k}, {b, h, k}, {b, h, f}}, {1, 0, 0});
    quad({{a, 0, k}, {a, 0, f}, {a, h, f}, {a, h, k}}, {-1, 0, 0});
  }
  return v;
}

// projection * view for an eye at (0, 2.5, 4.5) looking at (0, 0.3, 0), column-major.
std::array<float, 16> viewProjection(const sao::Camera& camera) {
  const float eye[3] = {0, 2.5f, 4.5f}, at[3] = {0, 0.3f, 0};
  float z[3] = {eye[0] - at[0], eye[1] - at[1], eye[2] - at[2]};
  const float zl = std::sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
  for (float& c : z) c /= zl;
  float x[3] = {z[2], 0, -z[0]};  // up (0, 1, 0) cross z
  const float xl = std::sqrt(x[0] * x[0] + x[2] * x[2]);
  x[0] /= xl, x[2] /= xl;
  const float y[3] = {z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]};
  float view[16] = {x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0, 0, 0, 0, 1};
  for (int r = 0; r < 3; ++r) {
    const float* axis = r == 0 ? x : r == 1 ? y : z;
    view[12 + r] = -(axis[0] * eye[0] + axis[1] * eye[1] + axis[2] * eye[2]);
  }
  std::array<float, 16> m{};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      for (int k = 0; k < 4; ++k) m[c * 4 + r] += float(camera.projection[k * 4 + r]) * view[c * 4 + k];
  return m;
}

// The engine's render target: colour and a depth texture SAO reads.
struct Target {
  int width = 0, height = 0;
  GLuint fbo = 0, colour = 0, depth = 0;
  void release() {
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &colour);
    glDeleteTextures(1, &depth);
    *this = {};
  }
  bool create(int w, int h) {
    release();
    width = w, height = h;
    glCreateTextures(GL_TEXTURE_2D, 1, &colour);
    glTextureStorage2D(colour, 1, GL_RGBA8, w, h);
    glCreateTextures(GL_TEXTURE_2D, 1, &depth);
    glTextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, w, h);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, colour, 0);
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth, 0);
    return glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  }
};

int glErrors = 0;
void GLAPIENTRY onDebugMessage(GLenum, GLenum type, GLuint, GLenum, GLsizei, const GLchar* message, const void*) {
  if (type == GL_DEBUG_TYPE_ERROR) ++glErrors, std::fprintf(stderr, "GL error: %s\n", message);
}

std::vector<float> readRed(GLuint texture, int width, int height) {
  std::vector<float> red(std::size_t(width) * height);
  glGetTextureImage(texture, 0, GL_RED, GL_FLOAT, GLsizei(red.size() * sizeof(float)), red.data());
  return red;
}

// The last frame's AO, as the applied colour over the colour before: both open floor and contact
// shadow (sky and dark texels, below 0.2, say nothing).
bool aoLooksRight(const std::vector<float>& before, const std::vector<float>& after) {
  std::size_t open = 0, shadowed = 0, lit = 0;
  for (std::size_t i = 0; i < before.size(); ++i) {
    if (before[i] < 0.2f) continue;
    const float a = after[i] / before[i];
    ++lit, open += a > 0.97f, shadowed += a < 0.8f;
  }
  std::printf("AO over %zu lit texels: %.1f%% above 0.97, %.1f%% below 0.8\n", lit, 100.0 * open / lit,
              100.0 * shadowed / lit);
  return lit > before.size() / 4 && open > lit / 10 && shadowed > lit / 100;
}

}  // namespace

int main(int argc, char** argv) {
  long frames = -1;
  int resizeWidth = 0, resizeHeight = 0;
  for (int i = 1; i < argc; i += 2) {
    const char* value = i + 1 < argc ? argv[i + 1] : "";
    if (!std::strcmp(argv[i], "--frames") && (frames = std::atol(value)) > 0) continue;
    if (!std::strcmp(argv[i], "--resize") && std::sscanf(value, "%dx%d", &resizeWidth, &resizeHeight) == 2 &&
        resizeWidth > 0 && resizeHeight > 0)
      continue;
    return std::fprintf(stderr, "usage: %s [--frames N (> 0)] [--resize WxH]\n", argv[0]), 2;
  }
  const long resizeFrame = frames > 0 ? frames / 3 : 100;
  if (!glfwInit()) return std::fprintf(stderr, "glfwInit failed\n"), 1;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(640, 400, "sao: GLFW integration", nullptr, nullptr);
  if (!window) return std::fprintf(stderr, "no GL 4.5 core window\n"), glfwTerminate(), 1;
  glfwMakeContextCurrent(window);
  glfwSwapInterval(0);
  bool loaded = true;
#define SAO_EXAMPLE_GL_LOAD(type, name) loaded &= (name = reinterpret_cast<type>(glfwGetProcAddress(#name))) != nullptr;
  SAO_EXAMPLE_GL(SAO_EXAMPLE_GL_LOAD)
  if (!loaded) return std::fprintf(stderr, "missing GL 4.5 entry points\n"), glfwTerminate(), 1;
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(onDebugMessage, nullptr);

  const GLuint sceneProgram = compile(kSceneVertex, kSceneFragment);
  const std::vector<float> triangles = sceneTriangles();
  GLuint vertexBuffer = 0, sceneVao = 0;
  glCreateBuffers(1, &vertexBuffer);
  glNamedBufferStorage(vertexBuffer, GLsizeiptr(triangles.size() * sizeof(float)), triangles.data(), 0);
  glCreateVertexArrays(1, &sceneVao);
  glVertexArrayVertexBuffer(sceneVao, 0, vertexBuffer, 0, 6 * sizeof(float));
  for (GLuint attribute : {0u, 1u}) {
    glEnableVertexArrayAttrib(sceneVao, attribute);
    glVertexArrayAttribFormat(sceneVao, attribute, 3, GL_FLOAT, GL_FALSE, attribute * 3 * sizeof(float));
    glVertexArrayAttribBinding(sceneVao, attribute, 0);
  }

  // The integration proper: create once, render from the engine's depth every frame.
  std::unique_ptr<sao::gl::Effect> ao;
  sao::Status status = sao::gl::Effect::create(glfwGetProcAddress, ao);
  sao::Settings settings = sao::presetSettings(sao::Preset::Medium);
  settings.radius = 0.5f;  // metres

  Target target;
  sao::Camera camera;
  bool ok = sceneProgram && status;
  long frame = 0;
  for (; ok && !glfwWindowShouldClose(window) && frame != frames; ++frame) {
    if (frame == resizeFrame && resizeWidth > 0) glfwSetWindowSize(window, resizeWidth, resizeHeight);
    glfwPollEvents();
    int width = 0, height = 0;
    glfwGetFramebufferSize(window, &width, &height);
    if (width == 0 || height == 0) continue;  // minimised
    if (width != target.width || height != target.height) {
      if (!(ok = target.create(width, height))) break;
      camera = sao::perspectiveCamera(std::numbers::pi / 3, width, height, 0.1, 100.0,
                                      sao::ClipDepth::NegativeOneToOne, /*reversedZ=*/false);
      std::printf("framebuffer %dx%d\n", width, height);
    }
    // The engine's scene into its FBO.
    const float sky[4] = {0.55f, 0.7f, 0.9f, 1.0f}, farDepth = 1.0f;
    glClearNamedFramebufferfv(target.fbo, GL_COLOR, 0, sky);
    glClearNamedFramebufferfv(target.fbo, GL_DEPTH, 0, &farDepth);
    glBindFramebuffer(GL_FRAMEBUFFER, target.fbo);
    glViewport(0, 0, width, height);
    glEnable(GL_DEPTH_TEST);
    glUseProgram(sceneProgram);
    glUniformMatrix4fv(0, 1, GL_FALSE, viewProjection(camera).data());
    glBindVertexArray(sceneVao);
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(triangles.size() / 6));
    glDisable(GL_DEPTH_TEST);

    const bool last = frame + 1 == frames;
    std::vector<float> before;
    if (last) before = readRed(target.colour, width, height);

    // SAO from its depth texture, multiplied into the colour's RGB (the effect follows the
    // camera's size: a resize reallocates).
    sao::gl::Inputs inputs;
    inputs.depth = {target.depth, sao::gl::kDepthComponent32F};
    inputs.output = target.colour;
    inputs.outputChannels = sao::kChannelR | sao::kChannelG | sao::kChannelB;
    inputs.outputBlend = sao::OutputBlend::Multiply;
    if (!(status = ao->render(camera, settings, inputs))) break;

    // The colour onto the window.
    glBlitNamedFramebuffer(target.fbo, 0, 0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glfwSwapBuffers(window);
    if (last) {
      ok = aoLooksRight(before, readRed(target.colour, width, height));
      if (resizeWidth > 0 && (width != resizeWidth || height != resizeHeight))
        ok = false, std::fprintf(stderr, "the window never became %dx%d\n", resizeWidth, resizeHeight);
    }
  }
  if (!status) std::fprintf(stderr, "sao: %s\n", status.message.c_str());
  ao.reset();
  target.release();
  glDeleteVertexArrays(1, &sceneVao);
  glDeleteBuffers(1, &vertexBuffer);
  glDeleteProgram(sceneProgram);
  glfwDestroyWindow(window);
  glfwTerminate();
  std::printf("%ld frames, %d GL errors\n", frame, glErrors);
  return ok && status && glErrors == 0 ? 0 : 1;
}
