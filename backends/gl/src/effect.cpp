// sao::gl::Effect: create() checks the context, render() ties the pieces together under a
// StateGuard: inputs -> plan -> resources -> programs -> parameter block -> passes.
#include "sao/gl/effect.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <set>
#include <string>

#include "dispatch.h"
#include "gl_functions.h"
#include "inputs.h"
#include "programs.h"
#include "resources.h"
#include "sao/frame.h"
#include "sao/temporal.h"
#include "state.h"
#include "timing.h"

namespace sao::gl {

using namespace detail;

struct __attribute__((visibility("hidden"))) Effect::Impl {
  GlFunctions gl;
  std::unique_ptr<Programs> programs;
  std::unique_ptr<Resources> resources;
  std::unique_ptr<PassTimer> timer;
  GLuint ubo = 0, nearestSampler = 0, mipSampler = 0;
  GLint maxTextureSize = 0;
  std::vector<GLuint> textureUnits, imageUnits;  // every unit any pass variant binds
  GLuint scratchUnit = 1;
  bool haveParams = false;
  ParamBlock uploaded{};
  // The configuration last rendered, and what was derived from it: render() plans, schedules and
  // prepares programs and images only when settings, camera or inputs change.
  bool planned = false;
  Settings plannedSettings;
  Camera plannedCamera;
  PlanInputs plannedInputs;
  Plan plan;
  Schedule schedule;
  std::vector<GLuint> passPrograms;  // per planned pass
  ParamBlock params{};
  Timings timings;
  Stats stats;
  TemporalHistory temporal;  // the history textures' state (sao/temporal.h)
  GLuint aoTexture = 0;
  std::array<GLuint, gen::kResources.size()> served{};

  ~Impl() {
    timer.reset();
    programs.reset();
    resources.reset();
    if (ubo) gl.DeleteBuffers(1, &ubo);
    if (nearestSampler) gl.DeleteSamplers(1, &nearestSampler);
    if (mipSampler) gl.DeleteSamplers(1, &mipSampler);
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
  return Status::error(StatusCode::DriverError, std::string("sao::gl: ") + name + " is " + std::to_string(have) +
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
        return Status::error(StatusCode::DriverError, "sao::gl: pass '" + std::string(p.name) +
                                                          "' reads one level of a chain above level 0, which this "
                                                          "backend does not bind");
    maxLocalX = std::max(maxLocalX, GLint(p.localX));
    maxLocalY = std::max(maxLocalY, GLint(p.localY));
    maxInvocations = std::max(maxInvocations, GLint(p.localX * p.localY));
    for (const gen::PassVariantInfo& v : p.compiled) {
      maxShared = std::max(maxShared, GLint(v.sharedBytes));
      GLint samplers = 0, images = 0;
      for (const gen::BindingInfo& b : v.bindings)
        for (std::uint32_t slot = 0; slot < b.slots; ++slot) {
          (b.write ? img : tex).insert(b.glUnit + slot);
          ++(b.write ? images : samplers);
        }
      maxSamplersPerPass = std::max(maxSamplersPerPass, samplers);
      maxImagesPerPass = std::max(maxImagesPerPass, images);
    }
  }
  textureUnits.assign(tex.begin(), tex.end());
  imageUnits.assign(img.begin(), img.end());
  if (textureUnits.size() > StateGuard::kMaxUnits || imageUnits.size() > StateGuard::kMaxUnits)
    return Status::error(StatusCode::DriverError, "sao::gl: the effect binds more units than the state guard saves (" +
                                                      std::to_string(StateGuard::kMaxUnits) + ")");
  if (textureUnits.empty()) textureUnits.push_back(1);
  scratchUnit = textureUnits.front();
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
  maxTextureSize = getInt(gl, GL_MAX_TEXTURE_SIZE);
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
    return Status::error(StatusCode::DriverError, std::string("sao::gl: create failed: ") + e.what());
  }
}

Status Effect::createImpl(GetProcAddressFn getProcAddress, std::unique_ptr<Effect>& out, int headerVersion) {
  if (headerVersion != SAO_VERSION) {
    auto v = [](int x) {
      return std::to_string((x >> 16) & 0xff) + "." + std::to_string((x >> 8) & 0xff) + "." + std::to_string(x & 0xff);
    };
    return Status::error(StatusCode::VersionMismatch, "sao::gl: the headers are version " + v(headerVersion) +
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
  gl.GenBuffers(1, &impl->ubo);
  gl.BindBuffer(GL_UNIFORM_BUFFER, impl->ubo);
  gl.BufferData(GL_UNIFORM_BUFFER, sizeof(ParamBlock), nullptr, GL_DYNAMIC_DRAW);
  gl.BindBuffer(GL_UNIFORM_BUFFER, GLuint(previousUbo));
  gl.ObjectLabel(GL_BUFFER, impl->ubo, -1, "sao SaoParams");

  GLuint samplers[2] = {};
  gl.GenSamplers(2, samplers);
  impl->nearestSampler = samplers[0];
  impl->mipSampler = samplers[1];
  for (GLuint s : samplers) {
    gl.SamplerParameteri(s, GL_TEXTURE_MIN_FILTER, s == impl->mipSampler ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
    gl.SamplerParameteri(s, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.SamplerParameteri(s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.SamplerParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.SamplerParameteri(s, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  }
  gl.ObjectLabel(GL_SAMPLER, impl->nearestSampler, -1, "sao nearest");
  gl.ObjectLabel(GL_SAMPLER, impl->mipSampler, -1, "sao nearest mip");
  if (!impl->ubo || !impl->nearestSampler || !impl->mipSampler)
    return Status::error(StatusCode::DriverError, "sao::gl: could not create the parameter buffer or samplers");

  impl->programs = std::make_unique<Programs>(gl);
  impl->resources = std::make_unique<Resources>(gl);
  impl->timer = std::make_unique<PassTimer>(gl);
  out.reset(new Effect(std::move(impl)));
  return Status::success();
}

Status Effect::Impl::render(const Camera& camera, const Settings& settings, const Inputs& inputs,
                            const RenderOptions& options) {
  StateGuard guard(gl, textureUnits, imageUnits, scratchUnit);

  CheckedInputs checked(gl);
  if (Status st = checkInputs(gl, scratchUnit, inputs, camera.normalsEncoding, checked); !st) return st;
  // A new configuration is planned into these (and committed at the end); an unchanged one
  // reuses what the last render derived, so a steady frame allocates nothing.
  const bool replan = !planned || !(settings == plannedSettings) || !(checked.planInputs == plannedInputs) ||
                      (!(camera == plannedCamera) && !cameraKeepsPlan(settings, plannedCamera, camera));
  Plan newPlan;
  Schedule newSchedule;
  std::vector<GLuint> newPrograms;
  if (replan) {
    planned = false;  // until the new configuration is committed: images may change on the way
    if (Status st = sao::plan(settings, camera, checked.planInputs, newPlan); !st) return st;
    newSchedule = makeSchedule(newPlan);
  }
  const Plan& p = replan ? newPlan : plan;
  const Schedule& s = replan ? newSchedule : schedule;
  if (Status st = checkSupplied(p, supplied(checked), checked.planInputs.userOutput, "sao::gl"); !st) return st;
  // checkSupplied put the region inside the textures, whose sides GL keeps far below 2^31.
  const FrameValues frame{checked.region.value_or(Offset{}), inputs.frameIndex, inputs.outputChannels,
                          inputs.outputBlend};
  if (Status st = checkFrameOutput(p, checked.planInputs, frame, "sao::gl"); !st) return st;
  ParamBlock block{};
  if (Status st = frameConstants(settings, camera, checked.planInputs, frame, block); !st) return st;
  if (settings.temporal) {
    if (inputs.layer != 0)
      return Status::error(StatusCode::InvalidInput, "sao::gl: temporal accumulation keeps one view's history: render "
                                                     "each layer (eye) with its own effect (Inputs::layer must be 0)");
    // A new plan (a resize, new settings, other inputs) has new history textures: start again.
    if (Status st = prepareTemporalFrame(temporal, settings, camera, inputs.previousCamera,
                                         inputs.resetHistory || replan, block);
        !st)
      return st;
  }
  if (replan) {
    if (p.inputExtent.width > std::uint32_t(maxTextureSize) || p.inputExtent.height > std::uint32_t(maxTextureSize))
      return Status::error(StatusCode::InvalidExtent, "sao::gl: the depth input " + std::to_string(p.inputExtent.width) +
                                                          "x" + std::to_string(p.inputExtent.height) +
                                                          " exceeds GL_MAX_TEXTURE_SIZE " + std::to_string(maxTextureSize));
    if (Status st = preparePrograms(*programs, p, newPrograms, stats.programsCompiled); !st) return st;
    if (Status st = resources->update(p, scratchUnit, maxTextureSize, stats.textureAllocations); !st) return st;
  }
  const std::vector<GLuint>& programsOfPlan = replan ? newPrograms : passPrograms;

  // Texture parameters of the caller's textures that would change what texelFetch returns or
  // whether an image store lands (restored before the StateGuard restores the bindings).
  TextureParamGuard depthParams, depth2Params, normalParams, motionParams, outputParams;
  depthParams.apply(gl, scratchUnit, checked.depth.texture, checked.depth.target, true, checked.depth.hasStencil);
  if (checked.depth2.texture)
    depth2Params.apply(gl, scratchUnit, checked.depth2.texture, GL_TEXTURE_2D, true, checked.depth2.hasStencil);
  if (checked.normals.texture) normalParams.apply(gl, scratchUnit, checked.normals.texture, GL_TEXTURE_2D, false, false);
  if (checked.motion.texture) motionParams.apply(gl, scratchUnit, checked.motion.texture, GL_TEXTURE_2D, false, false);
  if (checked.output.texture) outputParams.apply(gl, scratchUnit, checked.output.texture, GL_TEXTURE_2D, false, false);

  gl.BindBuffer(GL_UNIFORM_BUFFER, ubo);
  if (!haveParams || std::memcmp(&uploaded, &block, sizeof block) != 0) {
    gl.BufferSubData(GL_UNIFORM_BUFFER, 0, sizeof block, &block);
    uploaded = block;
    haveParams = true;
  }
  gl.BindBufferBase(GL_UNIFORM_BUFFER, gen::kParamBlockBinding, ubo);

  PassResources r{resources.get(), &checked, nearestSampler, mipSampler, temporal.parity};
  timer->beginFrame(options.measureTime);
  runSchedule(gl, p, s, programsOfPlan, r, *timer);
  if (!timer->endFrame(timings)) {  // GPU timers saw nothing: measure the same work again by clock
    timer->beginFrame(true);
    runSchedule(gl, p, s, programsOfPlan, r, *timer);
    timer->endFrame(timings);
  }

  for (std::size_t i = 0; i < served.size(); ++i) {
    const auto id = static_cast<gen::ResourceId>(i);
    const auto kind = gen::kResources[i].kind;
    served[i] = kind == gen::ResourceKind::Input ? 0 : textureFor(r, id);
  }
  aoTexture = textureFor(r, gen::ResourceId::ao);
  if (settings.temporal) finishTemporalFrame(temporal, settings, camera);
  else temporal.holdsFrame = false;
  if (replan) {
    plan = std::move(newPlan);
    schedule = std::move(newSchedule);
    passPrograms = std::move(newPrograms);
    plannedSettings = settings;
    plannedCamera = camera;
    plannedInputs = checked.planInputs;
    planned = true;
    ++stats.plans;
  }
  params = block;
  ++stats.renders;
  return Status::success();
}

Status Effect::render(const Camera& camera, const Settings& settings, const Inputs& inputs,
                      const RenderOptions& options) {
  try {
    return impl_->render(camera, settings, inputs, options);  // the StateGuard also restores on unwinding
  } catch (const std::exception& e) {
    return Status::error(StatusCode::DriverError, std::string("sao::gl: render failed: ") + e.what());
  }
}

std::uint32_t Effect::aoTexture() const { return impl_->aoTexture; }
std::uint64_t Effect::outputGeneration() const { return impl_->resources->outputGeneration(); }
std::uint32_t Effect::texture(gen::ResourceId resource) const {
  const auto i = static_cast<std::size_t>(resource);
  return i < impl_->served.size() ? impl_->served[i] : 0;
}
const Plan& Effect::plan() const { return impl_->plan; }
const ParamBlock& Effect::params() const { return impl_->params; }
const Timings& Effect::timings() const { return impl_->timings; }
const Stats& Effect::stats() const { return impl_->stats; }

}  // namespace sao::gl
