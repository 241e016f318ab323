#include "sao/prepass/gl_prepass.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "frame.h"
#include "gl_state.h"
#include "prepass_glsl.h"
#include "sao/gl/program_build.h"

namespace sao::prepass {

struct GlPrepass::Objects {
  GLuint layerProgram = 0, peelProgram = 0, vao = 0, vbo = 0, ubo = 0;
  GLsizei vertexCount = 0;
  std::uint64_t meshDigest = 0;
  bool haveMesh = false;
  struct Layer {
    GLuint fbo = 0, depth = 0, position = 0, normal = 0;
  } layers[2];
  Extent extent;
  DepthFormat format = DepthFormat::D32F;
  bool targetsMade = false, secondLayer = false;
  GLint maxTexture = 0, maxFbWidth = 0, maxFbHeight = 0, maxViewport[2]{};

  void deleteLayer(Layer& l) {
    if (l.fbo) glDeleteFramebuffers(1, &l.fbo);
    const GLuint t[3] = {l.depth, l.position, l.normal};
    glDeleteTextures(3, t);
    l = Layer{};
  }
  void deleteAll() {
    for (Layer& l : layers) deleteLayer(l);
    if (layerProgram) glDeleteProgram(layerProgram);
    if (peelProgram) glDeleteProgram(peelProgram);
    if (vao) glDeleteVertexArrays(1, &vao);
    const GLuint b[2] = {vbo, ubo};
    glDeleteBuffers(2, b);
    *this = Objects{};
  }
};

namespace {

// The source with `define` lines inserted after its #version line (kept as the first line).
std::string withDefines(std::string_view source, std::string_view defines) {
  const auto eol = source.find('\n');
  if (eol == std::string_view::npos) return std::string(source);
  return std::string(source.substr(0, eol + 1)) + std::string(defines) + "#line 2\n" + std::string(source.substr(eol + 1));
}

Status link(std::string_view defines, const char* name, GLuint& out) {
  return gl::buildProgram({{GL_VERTEX_SHADER, withDefines(glsl::kPrepassVert, ""), "prepass.vert"},
                           {GL_FRAGMENT_SHADER, withDefines(glsl::kPrepassFrag, defines), name}},
                          "prepass", out);
}

GLenum internalFormat(DepthFormat f) {
  switch (f) {
    case DepthFormat::D16: return GL_DEPTH_COMPONENT16;
    case DepthFormat::D24: return GL_DEPTH_COMPONENT24;
    default: return GL_DEPTH_COMPONENT32F;
  }
}

GLuint makeTexture(GLenum format, Extent e) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, format, GLsizei(e.width), GLsizei(e.height));
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

// The exact stored texels: D16 as 16-bit integers, D24 as the top 24 bits of the 32-bit unsigned
// normalised read-back, D32F as the float bits.
void readDepth(GLuint texture, DepthFormat format, Extent e, DepthImage& out) {
  const std::size_t n = std::size_t(e.width) * e.height;
  out.extent = e;
  out.format = format;
  out.texels.assign(n, 0);
  if (format == DepthFormat::D16) {
    std::vector<std::uint16_t> v(n);
    glGetTextureImage(texture, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT, GLsizei(n * 2), v.data());
    for (std::size_t i = 0; i < n; ++i) out.texels[i] = v[i];
  } else if (format == DepthFormat::D24) {
    glGetTextureImage(texture, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, GLsizei(n * 4), out.texels.data());
    for (auto& t : out.texels) t >>= 8;
  } else {
    glGetTextureImage(texture, 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(n * 4), out.texels.data());
  }
}

void readColor(GLuint texture, Extent e, FloatImage& out) {
  out = FloatImage(e, 4);
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(out.data.size() * sizeof(float)), out.data.data());
}

// With its own context, a call makes that context current and afterwards puts back the EGL context
// that was current on the thread (or none), so that the caller's context is left as it was.
class OwnContextScope {
 public:
  explicit OwnContextScope(gl::HeadlessContext* own) : own_(own) {
    if (!own_) return;
    display_ = eglGetCurrentDisplay();
    context_ = eglGetCurrentContext();
    draw_ = eglGetCurrentSurface(EGL_DRAW);
    read_ = eglGetCurrentSurface(EGL_READ);
    status_ = own_->makeCurrent();
  }
  ~OwnContextScope() {
    if (!own_) return;
    if (context_ == EGL_NO_CONTEXT) (void)own_->releaseCurrent();
    else eglMakeCurrent(display_, draw_, read_, context_);
  }
  OwnContextScope(const OwnContextScope&) = delete;
  OwnContextScope& operator=(const OwnContextScope&) = delete;
  const Status& status() const { return status_; }

 private:
  gl::HeadlessContext* own_;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLSurface draw_ = EGL_NO_SURFACE, read_ = EGL_NO_SURFACE;
  Status status_;
};

}  // namespace

Status GlPrepass::create(std::unique_ptr<GlPrepass>& out, const GlPrepassOptions& options) {
  out.reset();
  std::unique_ptr<GlPrepass> p(new GlPrepass());
  if (options.ownContext) {
    gl::HeadlessOptions ho;
    ho.major = 4;
    ho.minor = 5;
    ho.debug = options.debug;
    if (Status s = gl::HeadlessContext::create(p->context_, ho); !s) return s;
  }
  if (Status s = p->init(); !s) return s;
  out = std::move(p);
  return Status::success();
}

Status GlPrepass::init() {
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  if (!version) return Status::error(StatusCode::DriverError, "prepass: no current OpenGL context");
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major < 4 || (major == 4 && minor < 5))
    return Status::error(StatusCode::DriverError, std::string("prepass: needs OpenGL 4.5 (direct state access, "
                                                              "glClipControl); the context is ") + version);
  description_ = context_ ? context_->description()
                          : std::string(version) + " | " + reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  gl_ = std::make_unique<Objects>();
  Objects& o = *gl_;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &o.maxTexture);
  glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &o.maxFbWidth);
  glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &o.maxFbHeight);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, o.maxViewport);
  if (Status s = link("", "prepass.frag", o.layerProgram); !s) return s;
  if (Status s = link("#define SAO_PREPASS_PEEL 1\n", "prepass.frag (peel)", o.peelProgram); !s) return s;
  glCreateVertexArrays(1, &o.vao);
  glCreateBuffers(1, &o.vbo);
  glCreateBuffers(1, &o.ubo);
  glNamedBufferStorage(o.ubo, sizeof(detail::Uniforms), nullptr, GL_DYNAMIC_STORAGE_BIT);
  glVertexArrayVertexBuffer(o.vao, 0, o.vbo, 0, GLsizei(detail::kVertexFloats * sizeof(float)));
  for (GLuint a = 0; a < 2; ++a) {
    glEnableVertexArrayAttrib(o.vao, a);
    glVertexArrayAttribFormat(o.vao, a, 3, GL_FLOAT, GL_FALSE, a * 3 * sizeof(float));
    glVertexArrayAttribBinding(o.vao, a, 0);
  }
  if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "prepass: GL error 0x%04X while setting up", e);
    return Status::error(StatusCode::DriverError, buf);
  }
  return Status::success();
}

GlPrepass::~GlPrepass() {
  if (!gl_) return;
  {
    OwnContextScope scope(context_.get());
    if (scope.status()) gl_->deleteAll();  // otherwise the objects die with the context
  }
  gl_.reset();
}

Status GlPrepass::uploadMesh(const scenes::Mesh& mesh, std::uint64_t digest) {
  Objects& o = *gl_;
  if (o.haveMesh && o.meshDigest == digest) return Status::success();
  const std::vector<float> v = detail::expandMesh(mesh);
  // A new buffer object each time: immutable storage of the right size.
  glDeleteBuffers(1, &o.vbo);
  glCreateBuffers(1, &o.vbo);
  glNamedBufferStorage(o.vbo, GLsizeiptr(v.size() * sizeof(float)), v.data(), 0);
  glVertexArrayVertexBuffer(o.vao, 0, o.vbo, 0, GLsizei(detail::kVertexFloats * sizeof(float)));
  o.vertexCount = GLsizei(v.size() / detail::kVertexFloats);
  o.meshDigest = digest;
  o.haveMesh = true;
  return Status::success();
}

Status GlPrepass::ensureTargets(Extent e, DepthFormat format, bool secondLayer) {
  Objects& o = *gl_;
  if (o.targetsMade && o.extent == e && o.format == format && o.secondLayer == secondLayer) return Status::success();
  for (auto& l : o.layers) o.deleteLayer(l);
  o.targetsMade = false;
  for (int i = 0; i < (secondLayer ? 2 : 1); ++i) {
    auto& l = o.layers[i];
    l.depth = makeTexture(internalFormat(format), e);
    l.position = makeTexture(GL_RGBA32F, e);
    l.normal = makeTexture(GL_RGBA32F, e);
    glCreateFramebuffers(1, &l.fbo);
    glNamedFramebufferTexture(l.fbo, GL_DEPTH_ATTACHMENT, l.depth, 0);
    glNamedFramebufferTexture(l.fbo, GL_COLOR_ATTACHMENT0, l.position, 0);
    glNamedFramebufferTexture(l.fbo, GL_COLOR_ATTACHMENT1, l.normal, 0);
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(l.fbo, 2, buffers);
    glNamedFramebufferReadBuffer(l.fbo, GL_COLOR_ATTACHMENT0);
    const GLenum status = glCheckNamedFramebufferStatus(l.fbo, GL_DRAW_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      for (auto& m : o.layers) o.deleteLayer(m);
      char buf[160];
      std::snprintf(buf, sizeof buf, "prepass: the %s framebuffer is incomplete (0x%04X)", detail::formatName(format),
                    status);
      return Status::error(status == GL_FRAMEBUFFER_UNSUPPORTED ? StatusCode::UnsupportedFormat : StatusCode::DriverError,
                           buf);
    }
  }
  o.extent = e;
  o.format = format;
  o.secondLayer = secondLayer;
  o.targetsMade = true;
  return Status::success();
}

Status GlPrepass::render(const scenes::Mesh& mesh, const scenes::View& view, const Camera& camera,
                         const PrepassOptions& options, PrepassResult& out) {
  out = PrepassResult{};
  detail::Frame frame;
  if (Status s = detail::prepareFrame(mesh, view, camera, options, frame); !s) return s;
  std::uint64_t digest = 0;
  if (Status s = detail::checkMesh(mesh, digest); !s) return s;
  OwnContextScope scope(context_.get());
  if (!scope.status()) return scope.status();
  Objects& o = *gl_;
  const Extent e = frame.extent;
  const std::uint64_t maxW = std::uint64_t(std::min<GLint>({o.maxTexture, o.maxFbWidth, o.maxViewport[0]}));
  const std::uint64_t maxH = std::uint64_t(std::min<GLint>({o.maxTexture, o.maxFbHeight, o.maxViewport[1]}));
  if (e.width > maxW || e.height > maxH)
    return Status::error(StatusCode::InvalidExtent,
                         "prepass: the image is " + std::to_string(e.width) + "x" + std::to_string(e.height) +
                             " (viewport + 2 x guard band); this GL renders at most " + std::to_string(maxW) + "x" +
                             std::to_string(maxH));

  detail::GlStateGuard guard;
  if (Status s = uploadMesh(mesh, digest); !s) return s;
  if (Status s = ensureTargets(e, options.format, options.secondLayer); !s) return s;
  glNamedBufferSubData(o.ubo, 0, sizeof(detail::Uniforms), &frame.uniforms);
  glClipControl(GL_LOWER_LEFT, frame.zeroToOneClip ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
  glViewport(0, 0, GLsizei(e.width), GLsizei(e.height));
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(frame.reversedZ ? GL_GREATER : GL_LESS);
  glBindVertexArray(o.vao);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, o.ubo);
  const float zero[4] = {0, 0, 0, 0};
  const float clearDepth = float(frame.clearDepth);
  for (int i = 0; i < (options.secondLayer ? 2 : 1); ++i) {
    const auto& l = o.layers[i];
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, l.fbo);
    glClearNamedFramebufferfv(l.fbo, GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(l.fbo, GL_COLOR, 1, zero);
    glClearNamedFramebufferfv(l.fbo, GL_DEPTH, 0, &clearDepth);
    glUseProgram(i == 0 ? o.layerProgram : o.peelProgram);
    if (i == 1) {
      glActiveTexture(GL_TEXTURE1);
      glBindTexture(GL_TEXTURE_2D, o.layers[0].depth);
    }
    glDrawArrays(GL_TRIANGLES, 0, o.vertexCount);
  }

  readDepth(o.layers[0].depth, options.format, e, out.depth);
  readColor(o.layers[0].position, e, out.position);
  readColor(o.layers[0].normal, e, out.normal);
  if (options.secondLayer) {
    readDepth(o.layers[1].depth, options.format, e, out.depth2);
    readColor(o.layers[1].position, e, out.position2);
    readColor(o.layers[1].normal, e, out.normal2);
  }
  if (const GLenum err = glGetError(); err != GL_NO_ERROR) {
    out = PrepassResult{};
    char buf[64];
    std::snprintf(buf, sizeof buf, "prepass: GL error 0x%04X while rendering", err);
    return Status::error(StatusCode::DriverError, buf);
  }
  if (frame.flipY) {
    for (DepthImage* d : {&out.depth, &out.depth2})
      if (!d->texels.empty()) detail::flipRows(d->texels, e);
    for (FloatImage* f : {&out.position, &out.normal, &out.position2, &out.normal2})
      if (!f->data.empty()) detail::flipRows(*f);
  }
  return Status::success();
}

}  // namespace sao::prepass
