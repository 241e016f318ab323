// sao::cpu::run — validation, then the schedule's dispatches in order, each run by the effect's
// CPU pass (its C++ oracle, beside its GLSL in effect/cpu/), on images allocated from the plan.
// Nothing here names a pass or an effect-owned image except to fill Result's named fields.
#include "sao/cpu/reference.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <new>
#include <span>
#include <string>
#include <vector>

#include "sao/cpu/parallel.h"
#include "sao/frame.h"
#include "sao/schedule.h"
#include "sao/temporal.h"

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

// Channels of an image in `format` as the CPU reference holds it; 0 when it cannot.
int channelsOf(gen::Format format) {
  switch (format) {
    case gen::Format::R32F:
    case gen::Format::R16F:
    case gen::Format::R8: return 1;
    case gen::Format::RG32F:
    case gen::Format::RG16F: return 2;
    case gen::Format::RGBA16F:
    case gen::Format::RGBA32F:
    case gen::Format::RGBA8: return 4;
    default: return 0;
  }
}

// ------------------------------------------------------------------------------------------------
// The executor: every image of the plan (the output included), then the schedule's dispatches in
// order (sao/schedule.h), each run by the effect's CPU pass. Images are plain arrays, so the
// schedule's hazards need nothing here.

template <typename T>
Status allocateImages(PassContext<T>& ctx) {
  for (const PlannedImage& img : ctx.plan.images) {
    const int channels = channelsOf(img.format);
    if (channels == 0)
      return Status::error(StatusCode::UnsupportedFormat,
                           "the plan's image '" + resourceName(img.resource) +
                               "' has a format the CPU reference cannot hold (r32f, r16f, r8, rg32f, rg16f, rgba16f, rgba32f, rgba8)");
    auto& levels = ctx.levels(img.resource);
    levels.clear();
    for (std::uint32_t m = 0; m < img.mipLevels; ++m) {
      const Extent e = levelExtent(img.extent, m);
      levels.emplace_back(int(e.width), int(e.height), channels);
    }
    // The caller's output contents (checked against the extent and channels): what the final pass
    // keeps in the channels it does not write.
    const FloatImage* initial = ctx.in.output;
    if (gen::kResources[static_cast<std::size_t>(img.resource)].kind == gen::ResourceKind::Output && initial)
      for (std::size_t i = 0; i < initial->data.size(); ++i) levels[0].v[i] = static_cast<T>(initial->data[i]);
    // A history's previous-frame copy: the previous run's (checked against the plan), else empty.
    if (gen::kResources[static_cast<std::size_t>(img.resource)].history) {
      auto& previous = ctx.previousFrame(img.resource);
      previous = levels[0];
      if (const FloatImage* h = ctx.in.history)
        for (std::size_t i = 0; i < h->data.size(); ++i) previous.v[i] = static_cast<T>(h->data[i]);
    }
  }
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
Status execute(const Inputs& in, const Plan& plan, const gen::SaoParams& params, unsigned threads, bool measureTime,
               Result& out) {
  PassContext<T> ctx(in, plan, params, threads);
  if (Status st = allocateImages(ctx); !st) return st;
  if (measureTime) out.timings.method = TimingMethod::CpuClock;
  const Schedule schedule = makeSchedule(plan);
  auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < schedule.dispatches.size(); ++i) {
    const ScheduledDispatch& d = schedule.dispatches[i];
    const std::span<const ScheduledBinding> bindings = schedule.bindingsOf(d);
    if (Status st = checkBindings(ctx, d, bindings); !st) return st;
    if (Status st = runEffectPass(ctx, d, bindings); !st) return st;
    const bool lastOfPass = i + 1 == schedule.dispatches.size() || schedule.dispatches[i + 1].passIndex != d.passIndex;
    if (measureTime && lastOfPass) {
      const auto now = std::chrono::steady_clock::now();
      const std::chrono::duration<double, std::milli> ms = now - start;
      out.timings.passes.push_back({std::string(gen::pass(d.pass).name), ms.count()});
      start = now;
    }
  }
  collectImages(ctx, out);
  return Status::success();
}

// The previous run's history and camera (Inputs::history, previousCamera) into the block, as a GPU
// backend's temporal state would give them (sao/temporal.h).
Status checkHistory(const Settings& settings, const Camera& camera, const Inputs& in, Result& r) {
  if ((in.history == nullptr) != (in.previousCamera == nullptr))
    return invalid(std::string("Inputs::") + (in.history ? "history is given without Inputs::previousCamera" :
                                                           "previousCamera is given without Inputs::history") +
                   ": the history is reused with the camera that made it");
  if (in.history == nullptr) return Status::success();
  if (!settings.temporal)
    return invalid("Inputs::history is given but the temporal setting is off: nothing would read it");
  const PlannedImage* planned = r.plan.image(gen::ResourceId::history);
  if (planned == nullptr) return invalid("the plan has no history image");
  if (in.history->extent != planned->extent || in.history->channels != 4 ||
      in.history->data.size() != std::size_t(planned->extent.width) * planned->extent.height * 4)
    return invalid("Inputs::history is " + extentText(in.history->extent) + " with " +
                   std::to_string(in.history->channels) + " channels; this run's history is " +
                   extentText(planned->extent) + " with 4 (a previous run with another size or resolution_divisor)");
  TemporalHistory h;
  h.holdsFrame = true;
  h.settings = settings;
  h.camera = *in.previousCamera;
  return prepareTemporalFrame(h, settings, camera, in.previousCamera, false, r.params);
}

Status validateAndPlan(const Settings& settings, const Camera& camera, const Inputs& in, Result& r) {
  if (in.depth == nullptr) return invalid("no depth input: Inputs::depth is null");
  if (!knownFormat(in.depth->format))
    return Status::error(StatusCode::UnsupportedFormat,
                         "depth has an unknown format (" + std::to_string(int(in.depth->format)) + ")");
  const DepthEncoding encoding =
      in.depth->format == DepthFormat::LinearZ ? DepthEncoding::LinearZ : DepthEncoding::Hardware;
  if (in.depth->samples == 0) return invalid("depth has 0 samples per texel (1: single-sample)");
  const PlanInputs planInputs{encoding,          in.normals != nullptr, in.depth2 != nullptr, false, in.outputFormat,
                              in.depth->samples, in.motion != nullptr};
  if (Status st = plan(settings, camera, planInputs, r.plan); !st) return st;
  // The output's use, as the GPU backends check it: Inputs::output stands for the caller's image.
  PlanInputs outputUse = planInputs;
  outputUse.userOutput = in.output != nullptr;
  const FrameValues frame{in.region.value_or(Offset{}), in.frameIndex, in.outputChannels, in.outputBlend};
  if (Status st = checkFrameOutput(r.plan, outputUse, frame, "sao::cpu"); !st) return st;
  if (in.output != nullptr) {
    const std::uint32_t channels = channelCount(in.outputFormat);
    if (in.output->extent != r.plan.aoExtent || in.output->channels != channels ||
        in.output->data.size() != std::size_t(r.plan.aoExtent.width) * r.plan.aoExtent.height * channels)
      return invalid("the initial output is " + extentText(in.output->extent) + " with " +
                     std::to_string(in.output->channels) + " channels (" + std::to_string(in.output->data.size()) +
                     " floats); a " + formatName(in.outputFormat) + " output of the viewport needs " +
                     extentText(r.plan.aoExtent) + " with " + std::to_string(channels));
  }
  const Extent expected = r.plan.inputExtent;
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
  // Inside the images (checked above); images that wide cannot be in memory, but the block holds int.
  const Offset& offset = frame.inputOffset;
  if (offset.x > std::uint32_t(INT32_MAX) || offset.y > std::uint32_t(INT32_MAX))
    return invalid("the offset (" + std::to_string(offset.x) + ", " + std::to_string(offset.y) +
                   ") does not fit the shaders' int (at most 2^31 - 1)");
  if (Status st = frameConstants(settings, camera, planInputs, frame, r.params); !st) return st;
  if (Status st = checkHistory(settings, camera, in, r); !st) return st;
  // The block and the plan come from the same core functions; check that they agree anyway.
  if (std::uint32_t(r.params.max_mip) + 1 != r.plan.cszLevels)
    return invalid("max_mip " + std::to_string(r.params.max_mip) + " disagrees with the plan's " +
                   std::to_string(r.plan.cszLevels) + " csz levels");
  if (std::uint32_t(r.params.ao_size.x) != r.plan.aoExtent.width ||
      std::uint32_t(r.params.ao_size.y) != r.plan.aoExtent.height)
    return invalid("the block's ao_size disagrees with the plan's AO extent " + extentText(r.plan.aoExtent));
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
  if (Status st = validateAndPlan(settings, camera, inputs, r); !st) return st;
  const unsigned threads = threadCount(options.threads);
  try {
    Status st;
    const bool timed = options.measureTime;
    switch (options.precision) {
      case Precision::Float: st = execute<float>(inputs, r.plan, r.params, threads, timed, r); break;
      case Precision::Double: st = execute<double>(inputs, r.plan, r.params, threads, timed, r); break;
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

}  // namespace sao::cpu
