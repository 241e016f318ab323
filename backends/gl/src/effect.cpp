// sao::gl::Effect: create() checks the context, render() checks the caller's textures and hands
// the frame to core's FrameState (sao/executor.h), which drives the GL executor (executor.h),
// all under a StateGuard.
#include "api.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <set>
#include <string>

#include "executor.h"
#include "gl_functions.h"
#include "inputs.h"
#include "programs.h"
#include "resources.h"
#include "sao/executor.h"
#include "sao/inputs.h"
#include "state.h"
#include "timing.h"

namespace sao::SAO_GL_NS {

using namespace detail;

struct __attribute__((visibility("hidden"))) Effect::Impl {
  GlFunctions gl;
  std::unique_ptr<Programs> programs;
  std::unique_ptr<Resources> resources;
  std::unique_ptr<PassTimer> timer;
  std::unique_ptr<GlExecutor> executor;
  GlObjects objects;
  std::vector<GLuint> textureUnits, imageUnits;  // every unit any pass variant binds
  // The plan, the schedule, the images kept, the block and the history: core's (sao/executor.h).
  FrameState frame{kApiName};
  Timings timings;
  Stats stats;
  GLuint aoTexture = 0;
  std::array<GLuint, gen::kResources.size()> served{};

  ~Impl() {
    executor.reset();
    timer.reset();
    programs.reset();
    resources.reset();
    if (objects.ubo) gl.DeleteBuffers(1, &objects.ubo);
    if (objects.nearestSampler) gl.DeleteSamplers(1, &objects.nearestSampler);
    if (objects.mipSampler) gl.DeleteSamplers(1, &objects.mipSampler);
  }

  Status checkLimits();
  Status render(const Camera& camera, const Settings& settings, const Inputs& inputs, const RenderOptions& options);
};

namespace {

GLint getInt(const GlFunctions& gl, GLenum pname) {
  GLint v = 0;
  gl.GetIntegerv(pname, &v);
  return v;
}

GLint getIntIndexed(const GlFunctions& gl, GLenum pname, GLuint index) {
  GLint v = 0;
  gl.GetIntegeri_v(pname, index, &v);
  return v;
}

Status limitError(const char* name, GLint have, GLint need) {
  return Status::error(StatusCode::DriverError, (std::string(kApiName) + ": ") + name + " is " + std::to_string(have) +
                                                    ", the effect needs " + std::to_string(need));
}

}  // namespace

Status Effect::Impl::checkLimits() {
  std::set<GLuint> tex, img;
  GLint maxLocalX = 0, maxLocalY = 0, maxInvocations = 0, maxSamplersPerPass = 0, maxImagesPerPass = 0, maxShared = 0;
  for (const gen::PassInfo& p : gen::passes()) {
    // levels=A..B with A > 0 reads level A - 1 of a chain it writes alone: no pass of the effect
    // does, and this backend binds whole textures (no single-level views).
    for (gen::ResourceId w : p.writes)
      if (p.levelSlots > 0 && p.firstLevel > 0 && std::find(p.reads.begin(), p.reads.end(), w) != p.reads.end())
        return Status::error(StatusCode::DriverError, std::string(kApiName) + ": pass '" + std::string(p.name) +
                                                          "' reads one level of a chain above level 0, which this "
                                                          "backend does not bind");
    maxLocalX = std::max(maxLocalX, GLint(p.localX));
    maxLocalY = std::max(maxLocalY, GLint(p.localY));
    maxInvocations = std::max(maxInvocations, GLint(p.localX * p.localY));
    for (const gen::PassVariantInfo& v : p.compiled) {
      if (kEs && v.esslBlob < 0) continue;  // no GLES form (a refused format): never bound here
      maxShared = std::max(maxShared, GLint(v.sharedBytes));
      GLint samplers = 0, images = 0;
      for (const gen::BindingInfo& b : v.bindings) {
        for (std::uint32_t slot = 0; slot < b.slots; ++slot) {
          (b.write ? img : tex).insert(b.glUnit + slot);
          ++(b.write ? images : samplers);
        }
        if (kEs && b.esKeptUnit >= 0) {  // the texture an ES pass reads its output's kept texels through
          tex.insert(GLuint(b.esKeptUnit));
          ++samplers;
        }
      }
      maxSamplersPerPass = std::max(maxSamplersPerPass, samplers);
      maxImagesPerPass = std::max(maxImagesPerPass, images);
    }
  }
  textureUnits.assign(tex.begin(), tex.end());
  imageUnits.assign(img.begin(), img.end());
  if (textureUnits.size() > StateGuard::kMaxUnits || imageUnits.size() > StateGuard::kMaxUnits)
    return Status::error(StatusCode::DriverError, std::string(kApiName) + ": the effect binds more units than the state guard saves (" +
                                                      std::to_string(StateGuard::kMaxUnits) + ")");
  if (textureUnits.empty()) textureUnits.push_back(1);
  objects.scratchUnit = textureUnits.front();
  const GLint highestTexture = GLint(*std::max_element(textureUnits.begin(), textureUnits.end()));
  const GLint highestImage = imageUnits.empty() ? 0 : GLint(*std::max_element(imageUnits.begin(), imageUnits.end()));

  struct Check {
    const char* name;
    GLint have, need;
  };
  const Check checks[] = {
      {"GL_MAX_COMPUTE_WORK_GROUP_SIZE.x", getIntIndexed(gl, GL_MAX_COMPUTE_WORK_GROUP_SIZE, 0), maxLocalX},
      {"GL_MAX_COMPUTE_WORK_GROUP_SIZE.y", getIntIndexed(gl, GL_MAX_COMPUTE_WORK_GROUP_SIZE, 1), maxLocalY},
      {"GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS", getInt(gl, GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS), maxInvocations},
      {"GL_MAX_COMPUTE_WORK_GROUP_COUNT.x", getIntIndexed(gl, GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0),
       GLint(kMaxImageSide / std::max(1, maxLocalX))},
      {"GL_MAX_COMPUTE_WORK_GROUP_COUNT.y", getIntIndexed(gl, GL_MAX_COMPUTE_WORK_GROUP_COUNT, 1),
       GLint(kMaxImageSide / std::max(1, maxLocalY))},
      {"GL_MAX_COMPUTE_SHARED_MEMORY_SIZE", getInt(gl, GL_MAX_COMPUTE_SHARED_MEMORY_SIZE), maxShared},
      {"GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS", getInt(gl, GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS), highestTexture + 1},
      {"GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS", getInt(gl, GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS), highestTexture + 1},
      {"GL_MAX_COMPUTE_IMAGE_UNIFORMS", getInt(gl, GL_MAX_COMPUTE_IMAGE_UNIFORMS), maxImagesPerPass},
      {"GL_MAX_IMAGE_UNITS", getInt(gl, GL_MAX_IMAGE_UNITS), highestImage + 1},
      {"GL_MAX_COMPUTE_UNIFORM_BLOCKS", getInt(gl, GL_MAX_COMPUTE_UNIFORM_BLOCKS), 1},
      {"GL_MAX_UNIFORM_BLOCK_SIZE", getInt(gl, GL_MAX_UNIFORM_BLOCK_SIZE), GLint(sizeof(ParamBlock))},
      {"GL_MAX_UNIFORM_BUFFER_BINDINGS", getInt(gl, GL_MAX_UNIFORM_BUFFER_BINDINGS), GLint(gen::kParamBlockBinding) + 1},
  };
  for (const Check& c : checks)
    if (c.have < c.need) return limitError(c.name, c.have, c.need);
  objects.maxTextureSize = getInt(gl, GL_MAX_TEXTURE_SIZE);
  return Status::success();
}

Effect::Effect(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Effect::~Effect() = default;

Status Effect::create(GetProcAddressFn getProcAddress, std::unique_ptr<Effect>& out, int headerVersion) {
  out.reset();
  try {
    return createImpl(getProcAddress, out, headerVersion);
  } catch (const std::exception& e) {
    out.reset();
    return Status::error(StatusCode::DriverError, std::string(std::string(kApiName) + ": create failed: ") + e.what());
  }
}

Status Effect::createImpl(GetProcAddressFn getProcAddress, std::unique_ptr<Effect>& out, int headerVersion) {
  if (headerVersion != SAO_VERSION) {
    auto v = [](int x) {
      return std::to_string((x >> 16) & 0xff) + "." + std::to_string((x >> 8) & 0xff) + "." + std::to_string(x & 0xff);
    };
    return Status::error(StatusCode::VersionMismatch, std::string(kApiName) + ": the headers are version " + v(headerVersion) +
                                                          " but the library is " + v(SAO_VERSION) +
                                                          "; rebuild against the installed headers");
  }
  auto impl = std::make_unique<Impl>();
  if (Status st = impl->gl.load(getProcAddress); !st) return st;
  if (Status st = impl->checkLimits(); !st) return st;
  GlFunctions& gl = impl->gl;

  // Parameter block: one std140 buffer at binding 0 (the generated struct is copied as is).
  GLint previousUbo = 0;
  gl.GetIntegerv(GL_UNIFORM_BUFFER_BINDING, &previousUbo);
  GlObjects& objects = impl->objects;
  gl.GenBuffers(1, &objects.ubo);
  gl.BindBuffer(GL_UNIFORM_BUFFER, objects.ubo);
  gl.BufferData(GL_UNIFORM_BUFFER, sizeof(ParamBlock), nullptr, GL_DYNAMIC_DRAW);
  gl.BindBuffer(GL_UNIFORM_BUFFER, GLuint(previousUbo));
  gl.label(GL_BUFFER, objects.ubo, "sao SaoParams");

  GLuint samplers[2] = {};
  gl.GenSamplers(2, samplers);
  objects.nearestSampler = samplers[0];
  objects.mipSampler = samplers[1];
  for (GLuint s : samplers) {
    gl.SamplerParameteri(s, GL_TEXTURE_MIN_FILTER, s == objects.mipSampler ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
    gl.SamplerParameteri(s, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.SamplerParameteri(s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.SamplerParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.SamplerParameteri(s, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  }
  gl.label(GL_SAMPLER, objects.nearestSampler, "sao nearest");
  gl.label(GL_SAMPLER, objects.mipSampler, "sao nearest mip");
  if (!objects.ubo || !objects.nearestSampler || !objects.mipSampler)
    return Status::error(StatusCode::DriverError, std::string(kApiName) + ": could not create the parameter buffer or samplers");

  impl->programs = std::make_unique<Programs>(gl);
  impl->resources = std::make_unique<Resources>(gl);
  impl->timer = std::make_unique<PassTimer>(gl);
  impl->executor = std::make_unique<GlExecutor>(gl, impl->objects, *impl->resources, *impl->programs, *impl->timer,
                                                impl->stats, impl->timings);
  out.reset(new Effect(std::move(impl)));
  return Status::success();
}

Status Effect::Impl::render(const Camera& camera, const Settings& settings, const Inputs& inputs,
                            const RenderOptions& options) {
  StateGuard guard(gl, textureUnits, imageUnits, objects.scratchUnit);

  CheckedInputs checked(gl);
  if (Status st = checkInputs(gl, objects.scratchUnit, inputs, camera, checked); !st) return st;
  if (settings.temporal && inputs.layer != 0)
    return Status::error(StatusCode::InvalidInput, std::string(kApiName) + ": temporal accumulation keeps one view's history: render "
                                                   "each layer (eye) with its own effect (Inputs::layer must be 0)");
  const SuppliedImages images = supplied(checked);
  FrameInputs frameInputs;
  frameInputs.previousCamera = inputs.previousCamera;
  frameInputs.resetHistory = inputs.resetHistory;
  // checkSupplied (in FrameState) puts the region inside the textures, whose sides GL keeps far below 2^31.
  frameInputs.values = {checked.region.value_or(Offset{}), inputs.frameIndex, inputs.outputChannels, inputs.outputBlend};
  frameInputs.images = &images;

  // Texture parameters of the caller's textures that would change what texelFetch returns or
  // whether an image store lands (restored before the StateGuard restores the bindings).
  std::array<TextureParamGuard, gen::kInputIds.size() + 1> params;  // the inputs', then the output's
  const GLuint unit = objects.scratchUnit;
  for (std::size_t i = 0; i < gen::kInputIds.size(); ++i)
    if (const TextureInfo& t = checked.inputs[gen::kInputIds[i]]; t.texture)
      params[i].apply(gl, unit, t.texture, t.target, isDepthInput(gen::kInputIds[i]), t.hasStencil);
  if (checked.output.texture) params.back().apply(gl, unit, checked.output.texture, GL_TEXTURE_2D, false, false);

  executor->setFrame(&checked, options.measureTime);
  // The caller's textures are this render's only: the executor forgets them on every way out.
  struct Forget {
    GlExecutor& e;
    ~Forget() { e.setFrame(nullptr, false); }
  } forget{*executor};
  if (Status st = frame.render(settings, camera, checked.planInputs, frameInputs, *executor); !st) return st;
  if (executor->measureAgain())  // GPU timers saw nothing: measure the same work again by clock
    if (Status st = frame.repeat(*executor); !st) return st;

  for (std::size_t i = 0; i < served.size(); ++i) {
    const auto id = static_cast<gen::ResourceId>(i);
    served[i] = gen::kResources[i].kind == gen::ResourceKind::Input ? 0 : executor->textureFor(id);
  }
  aoTexture = executor->textureFor(gen::ResourceId::ao);
  stats.plans = frame.plans();
  ++stats.renders;
  return Status::success();
}

Status Effect::render(const Camera& camera, const Settings& settings, const Inputs& inputs,
                      const RenderOptions& options) {
  try {
    return impl_->render(camera, settings, inputs, options);  // the StateGuard also restores on unwinding
  } catch (const std::exception& e) {
    return Status::error(StatusCode::DriverError, std::string(std::string(kApiName) + ": render failed: ") + e.what());
  }
}

std::uint32_t Effect::aoTexture() const { return impl_->aoTexture; }
std::uint64_t Effect::outputGeneration() const { return impl_->resources->outputGeneration(); }
std::uint32_t Effect::texture(gen::ResourceId resource) const {
  const auto i = static_cast<std::size_t>(resource);
  return i < impl_->served.size() ? impl_->served[i] : 0;
}
const Plan& Effect::plan() const { return impl_->frame.plan(); }
const ParamBlock& Effect::params() const { return impl_->frame.block(); }
const Timings& Effect::timings() const { return impl_->timings; }
const Stats& Effect::stats() const { return impl_->stats; }

}  // namespace sao::SAO_GL_NS
