// sao::cpu::run — the CPU reference as an executor of core's frame (sao/executor.h): FrameState
// plans, checks the frame and fills the block; the executor runs the schedule's dispatches in
// order, each by the effect's CPU pass (its C++ oracle, beside its GLSL in effect/cpu/), on arrays
// allocated from the plan. Nothing here names a pass or an effect-owned image except to fill
// Result's named fields.
#include "sao/cpu/reference.h"

#include "sao/inputs.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <new>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sao/cpu/parallel.h"
#include "sao/executor.h"

// The effect's CPU passes: the header that sao_generate_effect(... CPU_PASSES <header>) names, as
// the effect target's compile definition. It defines sao::cpu::runEffectPass and PassContext.
#ifndef SAO_CPU_PASSES_HEADER
#error "SAO_CPU_PASSES_HEADER is not defined: the effect target gives none; call sao_generate_effect with CPU_PASSES <header>"
#endif
#include SAO_CPU_PASSES_HEADER

namespace sao::cpu {

using namespace detail;

namespace {

std::string extentText(Extent e) { return std::to_string(e.width) + "x" + std::to_string(e.height); }

Status invalid(std::string message) { return Status::error(StatusCode::InvalidInput, std::move(message)); }

bool knownFormat(DepthFormat f) {
  switch (f) {
    case DepthFormat::D16:
    case DepthFormat::D24:
    case DepthFormat::D32F:
    case DepthFormat::LinearZ: return true;
  }
  return false;
}

std::string expectedText(const Camera& camera, Extent expected) {
  return extentText(expected) + " (viewport " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
         " + 2 * guard band " + std::to_string(camera.guardBand) + ")";
}

std::string regionText(const Camera& camera, Extent expected, const std::optional<Offset>& region) {
  if (!region) return expectedText(camera, expected) + "; to read a region of a larger image, set Inputs::region";
  return expectedText(camera, expected) + " at offset (" + std::to_string(region->x) + ", " +
         std::to_string(region->y) + "), which ends at (" + std::to_string(std::uint64_t(region->x) + expected.width) +
         ", " + std::to_string(std::uint64_t(region->y) + expected.height) + "): the region must lie inside the image";
}

Status checkDepth(const char* name, const DepthImage& d, const Camera& camera, Extent expected,
                  const std::optional<Offset>& region) {
  if (d.extent.width == 0 || d.extent.height == 0)
    return invalid(std::string(name) + " is empty (" + extentText(d.extent) + "); expected " +
                   expectedText(camera, expected));
  if (!holdsInput(d.extent, region, expected))
    return invalid(std::string(name) + " is " + extentText(d.extent) + ", but the plan expects " +
                   regionText(camera, expected, region));
  if (d.samples == 0) return invalid(std::string(name) + " has 0 samples per texel (1: single-sample)");
  const std::size_t texels = std::size_t(d.extent.width) * d.extent.height * d.samples;
  if (d.texels.size() != texels)
    return invalid(std::string(name) + " holds " + std::to_string(d.texels.size()) + " texels, but its extent " +
                   extentText(d.extent) +
                   (d.samples > 1 ? " with " + std::to_string(d.samples) + " samples per texel" : std::string()) +
                   " needs " + std::to_string(texels));
  return Status::success();
}

Status checkNormals(const FloatImage& n, const Camera& camera, Extent expected, const std::optional<Offset>& region) {
  if (n.channels != 4)
    return Status::error(StatusCode::UnsupportedFormat,
                         "normals have " + std::to_string(n.channels) +
                             " channels; 4 are expected (rgba16f: the normal in .xyz, or octahedral in .xy, per Camera::normalsEncoding)");
  if (n.extent.width == 0 || n.extent.height == 0)
    return invalid("normals are empty (" + extentText(n.extent) + "); expected " + expectedText(camera, expected));
  if (!holdsInput(n.extent, region, expected))
    return invalid("normals are " + extentText(n.extent) + ", but the plan expects " +
                   regionText(camera, expected, region));
  const std::size_t values = std::size_t(n.extent.width) * n.extent.height * 4;
  if (n.data.size() != values)
    return invalid("normals hold " + std::to_string(n.data.size()) + " floats, but their extent " +
                   extentText(n.extent) + " with 4 channels needs " + std::to_string(values));
  return Status::success();
}

// Motion vectors: two or more channels (.xy read), the depth's region.
Status checkMotion(const FloatImage& m, const Camera& camera, Extent expected, const std::optional<Offset>& region) {
  if (m.channels < 2)
    return Status::error(StatusCode::UnsupportedFormat,
                         "motion vectors have " + std::to_string(m.channels) + " channel(s); .xy are read (rg16f)");
  if (!holdsInput(m.extent, region, expected))
    return invalid("motion vectors are " + extentText(m.extent) + ", but the plan expects " +
                   regionText(camera, expected, region));
  const std::size_t values = std::size_t(m.extent.width) * m.extent.height * m.channels;
  if (m.data.size() != values)
    return invalid("motion vectors hold " + std::to_string(m.data.size()) + " floats, but their extent " +
                   extentText(m.extent) + " with " + std::to_string(m.channels) + " channels needs " +
                   std::to_string(values));
  return Status::success();
}

// Another colour input (Inputs::moreInputs): its format='s channels or more, the depth's region.
Status checkMoreInput(const gen::ResourceInfo& r, const FloatImage& m, const Camera& camera, Extent expected,
                      const std::optional<Offset>& region) {
  const std::string name(r.name);
  const std::uint32_t channels = gen::formatInfo(r.format).channels;
  if (m.channels < channels)
    return Status::error(StatusCode::UnsupportedFormat, name + " has " + std::to_string(m.channels) +
                                                            " channel(s); its format " + std::string(gen::formatInfo(r.format).name) +
                                                            " has " + std::to_string(channels));
  if (!holdsInput(m.extent, region, expected))
    return invalid(name + " is " + extentText(m.extent) + ", but the plan expects " + regionText(camera, expected, region));
  if (m.data.size() != std::size_t(m.extent.width) * m.extent.height * m.channels)
    return invalid(name + " holds " + std::to_string(m.data.size()) + " floats, but its extent " + extentText(m.extent) +
                   " with " + std::to_string(m.channels) + " channels needs " +
                   std::to_string(std::size_t(m.extent.width) * m.extent.height * m.channels));
  return Status::success();
}

template <typename T>
FloatImage toFloatImage(const Image<T>& src) {
  FloatImage out(Extent{std::uint32_t(src.w), std::uint32_t(src.h)}, std::uint32_t(src.ch));
  for (std::size_t i = 0; i < src.v.size(); ++i) out.data[i] = static_cast<float>(src.v[i]);
  return out;
}

template <typename T>
std::vector<FloatImage> toFloatImages(const std::vector<Image<T>>& levels) {
  std::vector<FloatImage> out;
  for (const auto& level : levels) out.push_back(toFloatImage(level));
  return out;
}

std::string resourceName(gen::ResourceId id) {
  return std::string(gen::kResources[static_cast<std::size_t>(id)].name);
}

// Channels of an image in `format` as the CPU reference holds it; 0 when it cannot (depth).
int channelsOf(gen::Format format) {
  const gen::FormatInfo& f = gen::formatInfo(format);
  return f.colour ? int(f.channels) : 0;
}

// ------------------------------------------------------------------------------------------------
// The CPU executor of core's frame (sao/executor.h): FrameState plans and fills the block; the
// images are plain arrays allocated when the frame begins (the reference runs one frame per call),
// so hazards need nothing; each dispatch runs the effect's CPU pass.

// Every image of the plan, and the caller's output (Inputs::output, the executor's own image of
// the output resource when the plan does not own it).
template <typename T>
Status allocateImages(PassContext<T>& ctx, const PlanInputs& planInputs) {
  auto allocate = [&](gen::ResourceId id, gen::Format format, Extent extent, std::uint32_t levelCount) {
    const int channels = channelsOf(format);
    if (channels == 0)
      return Status::error(StatusCode::UnsupportedFormat,
                           "the plan's image '" + resourceName(id) +
                               "' has a format the CPU reference cannot hold (r32f, r16f, r8, rg32f, rg16f, rgba16f, rgba32f, rgba8)");
    auto& levels = ctx.levels(id);
    levels.clear();
    for (std::uint32_t m = 0; m < levelCount; ++m) {
      const Extent e = levelExtent(extent, m);
      levels.emplace_back(int(e.width), int(e.height), channels);
    }
    // The caller's output contents (checked against the extent and channels): what the final pass
    // keeps in the channels it does not write.
    const FloatImage* initial = ctx.in.output;
    if (gen::kResources[static_cast<std::size_t>(id)].kind == gen::ResourceKind::Output && initial)
      for (std::size_t i = 0; i < initial->data.size(); ++i) levels[0].v[i] = static_cast<T>(initial->data[i]);
    // A history's previous-frame copy: the previous run's (checked against the plan), else empty.
    if (gen::kResources[static_cast<std::size_t>(id)].history) {
      auto& previous = ctx.previousFrame(id);
      previous = levels[0];
      if (const FloatImage* h = ctx.in.history)
        for (std::size_t i = 0; i < h->data.size(); ++i) previous.v[i] = static_cast<T>(h->data[i]);
    }
    return Status::success();
  };
  for (const PlannedImage& img : ctx.plan.images)
    if (Status st = allocate(img.resource, img.format, img.extent, img.mipLevels); !st) return st;
  if (planInputs.userOutput)
    if (Status st = allocate(gen::ResourceId::ao, planInputs.outputFormat, ctx.plan.aoExtent, 1); !st) return st;
  return Status::success();
}

// Every image level a dispatch binds (inputs aside) is held, so a pass never indexes past the store.
template <typename T>
Status checkBindings(const PassContext<T>& ctx, const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
  for (const ScheduledBinding& b : bindings) {
    if (gen::kResources[static_cast<std::size_t>(b.resource)].kind == gen::ResourceKind::Input) continue;
    if (!ctx.holds(b.resource, b.baseLevel, b.levelCount))
      return invalid("pass '" + std::string(gen::pass(d.pass).name) + "' binds level " + std::to_string(b.baseLevel) +
                     (b.levelCount > 1 ? ".." + std::to_string(b.baseLevel + b.levelCount - 1) : std::string()) +
                     " of '" + resourceName(b.resource) + "', which the plan does not allocate");
  }
  return Status::success();
}

// Result's named images as before, then every other planned image by resource.
template <typename T>
void collectImages(const PassContext<T>& ctx, Result& out) {
  using R = gen::ResourceId;
  auto first = [&](R id) { return ctx.levels(id).empty() ? FloatImage{} : toFloatImage(ctx.levels(id)[0]); };
  out.csz = toFloatImages(ctx.levels(R::csz));
  out.csz2 = toFloatImages(ctx.levels(R::csz2));
  out.aoRaw = first(R::ao_raw);
  out.ao = first(R::ao);
  for (std::size_t r = 0; r < gen::kResources.size(); ++r) {
    const auto id = static_cast<R>(r);
    if (id == R::csz || id == R::csz2 || id == R::ao_raw || id == R::ao) continue;
    out.images[r] = toFloatImages(ctx.levels(id));
  }
}

template <typename T>
class CpuExecutor final : public Executor {
 public:
  CpuExecutor(const Inputs& in, const PlanInputs& planInputs, unsigned threads, bool measureTime, Result& out)
      : in_(in), planInputs_(planInputs), threads_(threads), measureTime_(measureTime), out_(out) {}

  Status createImage(const PlannedImage& image) override {
    if (channelsOf(image.format) == 0)
      return Status::error(StatusCode::UnsupportedFormat,
                           "the plan's image '" + resourceName(image.resource) +
                               "' has a format the CPU reference cannot hold (r32f, r16f, r8, rg32f, rg16f, rgba16f, rgba32f, rgba8)");
    return Status::success();  // allocated when the frame begins
  }
  void destroyImage(const PlannedImage&) noexcept override {}
  Status createPipeline(const gen::PassInfo&, const gen::PassVariantInfo&) override { return Status::success(); }

  Status beginFrame(const FrameWork& work) override {
    const Plan& plan = *work.plan;
    const ParamBlock& block = *work.block;
    // The block and the plan come from the same core functions; check that they agree anyway.
    if (std::uint32_t(block.max_mip) + 1 != plan.cszLevels)
      return invalid("max_mip " + std::to_string(block.max_mip) + " disagrees with the plan's " +
                     std::to_string(plan.cszLevels) + " csz levels");
    if (std::uint32_t(block.ao_size.x) != plan.aoExtent.width || std::uint32_t(block.ao_size.y) != plan.aoExtent.height)
      return invalid("the block's ao_size disagrees with the plan's AO extent " + extentText(plan.aoExtent));
    ctx_.emplace(in_, plan, block, threads_);
    if (Status st = allocateImages(*ctx_, planInputs_); !st) return st;
    if (measureTime_) out_.timings.method = TimingMethod::CpuClock;
    start_ = std::chrono::steady_clock::now();
    return Status::success();
  }
  void barrier(std::span<const Hazard>) override {}  // arrays: every write is visible to the next pass

  void dispatch(const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) override {
    if (!error_.ok()) return;
    if (pass_ && *pass_ != d.pass) lap();
    pass_ = d.pass;
    if (Status st = checkBindings(*ctx_, d, bindings); !st) error_ = st;
    else if (Status st2 = runEffectPass(*ctx_, d, bindings); !st2) error_ = st2;
  }

  Status endFrame() override {
    if (!error_.ok()) return error_;
    if (pass_) lap();
    collectImages(*ctx_, out_);
    return Status::success();
  }

 private:
  // The time since the last lap, as the pass that just ended (Options::measureTime).
  void lap() {
    if (!measureTime_) return;
    const auto now = std::chrono::steady_clock::now();
    const std::chrono::duration<double, std::milli> ms = now - start_;
    out_.timings.passes.push_back({std::string(gen::pass(*pass_).name), ms.count()});
    start_ = now;
  }

  const Inputs& in_;
  const PlanInputs& planInputs_;
  const unsigned threads_;
  const bool measureTime_;
  Result& out_;
  std::optional<PassContext<T>> ctx_;
  std::optional<gen::PassId> pass_;
  std::chrono::steady_clock::time_point start_;
  Status error_;
};

// The depth input as far as it is checked before a plan exists, and the plan inputs it gives.
Status planInputsOf(const Inputs& in, PlanInputs& out) {
  if (in.depth == nullptr) return invalid("no depth input: Inputs::depth is null");
  if (!knownFormat(in.depth->format))
    return Status::error(StatusCode::UnsupportedFormat,
                         "depth has an unknown format (" + std::to_string(int(in.depth->format)) + ")");
  if (in.depth->samples == 0) return invalid("depth has 0 samples per texel (1: single-sample)");
  const DepthEncoding encoding =
      in.depth->format == DepthFormat::LinearZ ? DepthEncoding::LinearZ : DepthEncoding::Hardware;
  // Inputs::output stands for the caller's image (userOutput), as on the GPU backends.
  out = {};
  out.depthEncoding = encoding;
  for (const gen::ResourceId id : gen::kInputIds)
    out.supplied[id] = isDepthInput(id) ? (id == gen::ResourceId::depth2 ? in.depth2 : in.depth) != nullptr
                                        : colourInput(in, id) != nullptr;
  for (std::size_t r = 0; r < in.moreInputs.size(); ++r) {
    const auto id = static_cast<gen::ResourceId>(r);
    const bool other = gen::kResources[r].kind == gen::ResourceKind::Input && !isDepthInput(id) &&
                       id != gen::ResourceId::normals && id != gen::ResourceId::motion;
    if (in.moreInputs[r] != nullptr && !other)
      return invalid("Inputs::moreInputs[" + std::string(gen::kResources[r].name) + "] is given, but " +
                     std::string(gen::kResources[r].name) +
                     " is not a colour input of the effect beyond normals and motion (those have their own member)");
  }
  out.userOutput = in.output != nullptr;
  out.outputFormat = in.outputFormat;
  out.depthSamples = in.depth->samples;
  return Status::success();
}

// The caller's images against the plan, with the CPU reference's own messages.
Status checkAgainstPlan(const Settings& settings, const Camera& camera, const Inputs& in, const Plan& plan) {
  if (in.output != nullptr) {
    const std::uint32_t channels = channelCount(in.outputFormat);
    if (in.output->extent != plan.aoExtent || in.output->channels != channels ||
        in.output->data.size() != std::size_t(plan.aoExtent.width) * plan.aoExtent.height * channels)
      return invalid("the initial output is " + extentText(in.output->extent) + " with " +
                     std::to_string(in.output->channels) + " channels (" + std::to_string(in.output->data.size()) +
                     " floats); a " + formatName(in.outputFormat) + " output of the viewport needs " +
                     extentText(plan.aoExtent) + " with " + std::to_string(channels));
  }
  const Extent expected = plan.inputExtent;
  if (Status st = checkDepth("depth", *in.depth, camera, expected, in.region); !st) return st;
  if (in.depth2 != nullptr) {
    if (in.depth2->format != in.depth->format)
      return invalid(std::string("depth2 is ") + toString(in.depth2->format) + " but depth is " +
                     toString(in.depth->format) + "; both layers must have the same format and convention");
    if (Status st = checkDepth("depth2", *in.depth2, camera, expected, in.region); !st) return st;
  }
  if (in.normals != nullptr)
    if (Status st = checkNormals(*in.normals, camera, expected, in.region); !st) return st;
  if (in.motion != nullptr)
    if (Status st = checkMotion(*in.motion, camera, expected, in.region); !st) return st;
  for (std::size_t r = 0; r < in.moreInputs.size(); ++r)
    if (const FloatImage* m = in.moreInputs[r])
      if (Status st = checkMoreInput(gen::kResources[r], *m, camera, expected, in.region); !st) return st;
  // Inside the images (checked above); images that wide cannot be in memory, but the block holds int.
  const Offset offset = in.region.value_or(Offset{});
  if (offset.x > std::uint32_t(INT32_MAX) || offset.y > std::uint32_t(INT32_MAX))
    return invalid("the offset (" + std::to_string(offset.x) + ", " + std::to_string(offset.y) +
                   ") does not fit the shaders' int (at most 2^31 - 1)");
  // The previous run's history and camera (Inputs::history, previousCamera), as a GPU backend's
  // temporal state would give them (sao/temporal.h).
  if ((in.history == nullptr) != (in.previousCamera == nullptr))
    return invalid(std::string("Inputs::") + (in.history ? "history is given without Inputs::previousCamera" :
                                                           "previousCamera is given without Inputs::history") +
                   ": the history is reused with the camera that made it");
  if (in.history == nullptr) return Status::success();
  if (!settings.temporal)
    return invalid("Inputs::history is given but the temporal setting is off: nothing would read it");
  const PlannedImage* planned = plan.image(gen::ResourceId::history);
  if (planned == nullptr) return invalid("the plan has no history image");
  if (in.history->extent != planned->extent || in.history->channels != 4 ||
      in.history->data.size() != std::size_t(planned->extent.width) * planned->extent.height * 4)
    return invalid("Inputs::history is " + extentText(in.history->extent) + " with " +
                   std::to_string(in.history->channels) + " channels; this run's history is " +
                   extentText(planned->extent) + " with 4 (a previous run with another size or resolution_divisor)");
  return Status::success();
}

// One frame of FrameState through the CPU executor: validation, plan, block, the passes.
template <typename T>
Status runFrame(const Settings& settings, const Camera& camera, const Inputs& in, const PlanInputs& planInputs,
                const Options& options, Result& r) {
  CpuExecutor<T> executor(in, planInputs, threadCount(options.threads), options.measureTime, r);
  FrameState frame("sao::cpu");
  if (Status st = frame.configure(settings, camera, planInputs, executor); !st) return st;
  if (Status st = checkAgainstPlan(settings, camera, in, frame.plan()); !st) return st;
  if (in.history) frame.continueHistory(*in.previousCamera);
  FrameInputs frameInputs;
  frameInputs.previousCamera = in.previousCamera;
  frameInputs.values = {in.region.value_or(Offset{}), in.frameIndex, in.outputChannels, in.outputBlend};
  if (Status st = frame.run(frameInputs, executor); !st) return st;
  r.plan = frame.plan();
  r.params = frame.block();
  return Status::success();
}

}  // namespace

const char* toString(Precision precision) {
  switch (precision) {
    case Precision::Double: return "double";
    case Precision::Float: return "float";
  }
  return "?";
}

Status run(const Settings& settings, const Camera& camera, const Inputs& inputs, const Options& options,
           Result& out) {
  out = Result{};
  Result r;
  PlanInputs planInputs;
  if (Status st = planInputsOf(inputs, planInputs); !st) return st;
  try {
    Status st;
    switch (options.precision) {
      case Precision::Float: st = runFrame<float>(settings, camera, inputs, planInputs, options, r); break;
      case Precision::Double: st = runFrame<double>(settings, camera, inputs, planInputs, options, r); break;
      default: return invalid("unknown precision " + std::to_string(int(options.precision)));
    }
    if (!st) return st;
  } catch (const std::bad_alloc&) {
    return Status::error(StatusCode::InvalidExtent, "out of memory running the CPU reference on a " +
                                                        extentText(r.plan.inputExtent) + " input");
  }
  out = std::move(r);
  return Status::success();
}

float roundToHalfAsShader(float x) { return roundToHalf(x); }
float roundToUnorm8AsShader(float x) { return roundToUnorm8(x); }
float outputMultiplyAsShader(float c, float a, bool unorm8) { return outputMultiply(c, a, unorm8); }

const FloatImage* colourInput(const Inputs& in, gen::ResourceId id) {
  if (id == gen::ResourceId::normals) return in.normals;
  if (id == gen::ResourceId::motion) return in.motion;
  return in.moreInputs[static_cast<std::size_t>(id)];
}

}  // namespace sao::cpu
