#include "per_tap_ladder.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <chrono>
#include <string>

#include "sao/gl/headless.h"
#include "sao/gl/program_build.h"
#include "sao/gl/texture_io.h"

namespace sao::bench {
namespace {

// Puts back the EGL context that was current on the thread (or none) when it ends, so that the
// ladder leaves the gl backend's and the prepass's contexts as it found them.
class RestoreContext {
 public:
  RestoreContext()
      : display_(eglGetCurrentDisplay()),
        context_(eglGetCurrentContext()),
        draw_(eglGetCurrentSurface(EGL_DRAW)),
        read_(eglGetCurrentSurface(EGL_READ)) {}
  ~RestoreContext() {
    if (context_ != EGL_NO_CONTEXT) eglMakeCurrent(display_, draw_, read_, context_);
    else if (EGLDisplay d = eglGetCurrentDisplay(); d != EGL_NO_DISPLAY)
      eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  RestoreContext(const RestoreContext&) = delete;
  RestoreContext& operator=(const RestoreContext&) = delete;

 private:
  EGLDisplay display_;
  EGLContext context_;
  EGLSurface draw_, read_;
};

// The rung's program: the full-screen triangle and its fragment shader, or its compute shader.
Status link(const LadderStep& step, int samples, int turns, GLuint& out) {
  std::vector<gl::ShaderStage> stages;
  if (step.fragment) stages.push_back({GL_VERTEX_SHADER, kLadderVertexShader, "vertex shader"});
  stages.push_back({step.fragment ? GLenum(GL_FRAGMENT_SHADER) : GLenum(GL_COMPUTE_SHADER),
                    ladderShader(step, samples, turns), step.fragment ? "fragment shader" : "compute shader"});
  return gl::buildProgram(stages, std::string(step.name) + " at s=" + std::to_string(samples), out);
}

// The block's values as the rungs' uniforms; names a rung does not use are inactive (location -1)
// and skipped.
void setUniforms(GLuint program, const ParamBlock& b) {
  auto loc = [program](const char* name) { return glGetUniformLocation(program, name); };
  auto f1 = [&](const char* name, float v) {
    if (GLint l = loc(name); l >= 0) glProgramUniform1f(program, l, v);
  };
  auto i1 = [&](const char* name, int v) {
    if (GLint l = loc(name); l >= 0) glProgramUniform1i(program, l, v);
  };
  auto i2 = [&](const char* name, gen::Int2 v) {
    if (GLint l = loc(name); l >= 0) glProgramUniform2i(program, l, v.x, v.y);
  };
  if (GLint l = loc("proj_info"); l >= 0)
    glProgramUniform4f(program, l, b.proj_info.x, b.proj_info.y, b.proj_info.z, b.proj_info.w);
  i2("guard", b.guard);
  i2("ao_size", b.ao_size);
  f1("radius_px", b.radius * b.proj_scale);
  f1("radius2", b.radius2);
  f1("bias", b.bias);
  f1("epsilon", b.epsilon);
  f1("intensity_div_s", b.intensity_div_s);
  f1("contrast", b.contrast);
  i1("log_q", b.log_q);
  i1("max_mip", b.max_mip);
  f1("quad_threshold", b.quad_edge_threshold);
  i1("samples", b.samples);
  i1("spiral_turns", b.spiral_turns);
  f1("inv_samples", b.inv_samples);
  if (GLint l = loc("turn_table"); l >= 0) {
    const std::vector<unsigned> turns = spiralTurnTable(b.samples, b.spiral_turns);
    glProgramUniform1uiv(program, l, GLsizei(turns.size()), turns.data());
  }
}

}  // namespace

Status PerTapLadder::create(const std::vector<FloatImage>& csz, const FloatImage& normals, Extent viewport,
                            std::unique_ptr<PerTapLadder>& out) {
  out.reset();
  if (csz.empty() || csz[0].channels != 1 || normals.channels != 4 || normals.extent != csz[0].extent)
    return Status::error(StatusCode::InvalidInput,
                         "per_tap ladder: needs csz levels (1 channel) and normals of level 0's size");
  const RestoreContext restore;
  std::unique_ptr<PerTapLadder> l(new PerTapLadder());
  gl::HeadlessOptions ho;
  ho.minor = 5;  // direct state access
  if (Status s = gl::HeadlessContext::create(l->context_, ho); !s) return s;
  l->viewport_ = viewport;
  l->cszLevels_ = std::uint32_t(csz.size());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  auto upload = [](GLuint t, std::uint32_t level, const FloatImage& img) {
    glTextureSubImage2D(t, GLint(level), 0, 0, GLsizei(img.extent.width), GLsizei(img.extent.height), GL_RED, GL_FLOAT,
                        img.data.data());
  };
  const Extent e0 = csz[0].extent;
  l->z0_ = gl::makeTexture(GL_R32F, e0);
  upload(l->z0_, 0, csz[0]);
  GLuint mips = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &mips);
  l->zMips_ = mips;
  glTextureStorage2D(mips, GLsizei(csz.size()), GL_R32F, GLsizei(e0.width), GLsizei(e0.height));
  for (std::uint32_t m = 0; m < csz.size(); ++m) {
    if (csz[m].extent != levelExtent(e0, m) || csz[m].channels != 1)
      return Status::error(StatusCode::InvalidInput,
                           "per_tap ladder: csz level " + std::to_string(m) + " has the wrong size");
    upload(mips, m, csz[m]);
  }
  glTextureParameteri(mips, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
  glTextureParameteri(mips, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  for (GLuint t : {l->z0_}) {
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  if (Status s = gl::uploadNormals(normals, l->normals_); !s) return s;
  l->output_ = gl::makeTexture(GL_R16F, viewport);
  GLuint fbo = 0, vao = 0;
  glCreateFramebuffers(1, &fbo);
  l->fbo_ = fbo;
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, l->output_, 0);
  if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    return Status::error(StatusCode::DriverError, "per_tap ladder: the r16f target is not a complete framebuffer");
  glCreateVertexArrays(1, &vao);
  l->vao_ = vao;
  if (Status s = l->checkErrors("setting up"); !s) return s;
  out = std::move(l);
  return Status::success();
}

PerTapLadder::~PerTapLadder() {
  const RestoreContext restore;
  if (!context_ || !context_->makeCurrent()) return;  // the objects die with the context
  for (std::uint32_t t : {z0_, zMips_, normals_, output_}) gl::deleteTexture(t);
  const GLuint fbo = fbo_, vao = vao_;
  if (fbo) glDeleteFramebuffers(1, &fbo);
  if (vao) glDeleteVertexArrays(1, &vao);
}

std::string PerTapLadder::description() const { return context_->description(); }

Status PerTapLadder::checkErrors(const char* what) {
  const auto errors = context_->errors();
  context_->clearMessages();
  if (errors.empty()) return Status::success();
  return Status::error(StatusCode::DriverError, std::string("per_tap ladder: GL reported while ") + what + ": " +
                                                    gl::HeadlessContext::format(errors[0]));
}

Status PerTapLadder::measure(const LadderStep& step, const ParamBlock& block, int runs, std::vector<double>& clockMs,
                             std::vector<double>& gpuMs, FloatImage& ao) {
  clockMs.clear();
  gpuMs.clear();
  const RestoreContext restore;
  if (Status s = context_->makeCurrent(); !s) return s;
  GLuint program = 0;
  if (Status s = link(step, block.samples, block.spiral_turns, program); !s) return s;
  setUniforms(program, block);
  glUseProgram(program);
  glBindTextureUnit(0, z0_);
  glBindTextureUnit(1, zMips_);
  glBindTextureUnit(2, normals_);
  if (step.imageLoad) glBindImageTexture(1, z0_, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
  if (step.fragment) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glViewport(0, 0, GLsizei(viewport_.width), GLsizei(viewport_.height));
    glBindVertexArray(vao_);
  } else {
    glBindImageTexture(0, output_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
  }
  GLuint query = 0;
  glCreateQueries(GL_TIME_ELAPSED, 1, &query);
  // A pass never takes less than this: smaller results (llvmpipe's 1 ns) mean the query does not see it.
  constexpr GLuint64 kLeastPlausibleNs = 100;
  bool gpuSees = true;
  for (int r = -1; r < runs; ++r) {  // the first run compiles llvmpipe's variant
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    glBeginQuery(GL_TIME_ELAPSED, query);
    if (step.fragment) glDrawArrays(GL_TRIANGLES, 0, 3);
    else glDispatchCompute((viewport_.width + 7) / 8, (viewport_.height + 7) / 8, 1);
    glEndQuery(GL_TIME_ELAPSED);
    glFinish();
    const auto end = std::chrono::steady_clock::now();
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
    if (r < 0) continue;
    clockMs.push_back(std::chrono::duration<double, std::milli>(end - start).count());
    gpuMs.push_back(double(ns) * 1e-6);
    gpuSees = gpuSees && ns >= kLeastPlausibleNs;
  }
  glDeleteQueries(1, &query);
  if (!gpuSees) gpuMs.clear();
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  ao = gl::readTexture(output_, 1);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindVertexArray(0);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
  glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
  glUseProgram(0);
  glDeleteProgram(program);
  return checkErrors(step.name);
}

}  // namespace sao::bench
