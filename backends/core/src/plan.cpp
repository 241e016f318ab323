#include "sao/plan.h"

#include "sao/inputs.h"
#include "sao/output.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sao {
namespace {

std::uint64_t imageBytes(gen::Format format, Extent e, std::uint32_t levels) {
  std::uint64_t total = 0;
  for (std::uint32_t m = 0; m < levels; ++m) {
    const Extent l = levelExtent(e, m);
    total += std::uint64_t(l.width) * l.height * bytesPerTexel(format);
  }
  return total;
}

std::uint32_t fullChainLevels(Extent e) {
  return 1 + static_cast<std::uint32_t>(std::floor(std::log2(double(std::max(e.width, e.height)))));
}

Status checkExtents(const Camera& c, Extent& input, Extent& ao) {
  const std::uint64_t w = std::uint64_t(c.width) + 2ull * c.guardBand;
  const std::uint64_t h = std::uint64_t(c.height) + 2ull * c.guardBand;
  if (c.width == 0 || c.height == 0)
    return Status::error(StatusCode::InvalidExtent, "viewport " + std::to_string(c.width) + "x" +
                                                        std::to_string(c.height) + " is empty");
  if (w > kMaxImageSide || h > kMaxImageSide)
    return Status::error(StatusCode::InvalidExtent,
                         "depth input " + std::to_string(w) + "x" + std::to_string(h) + " (viewport " +
                             std::to_string(c.width) + "x" + std::to_string(c.height) + " + guard band " +
                             std::to_string(c.guardBand) + ") exceeds the largest supported side " +
                             std::to_string(kMaxImageSide));
  input = {static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)};
  ao = {c.width, c.height};
  return Status::success();
}

}  // namespace

Extent levelExtent(Extent e, std::uint32_t level) {
  return {std::max(1u, e.width >> level), std::max(1u, e.height >> level)};
}

Extent resourceExtent(const Plan& plan, gen::ResourceId id) {
  if (const PlannedImage* img = plan.image(id)) return img->extent;
  const auto& info = gen::kResources[static_cast<std::size_t>(id)];
  const Extent base = info.inputExtent ? plan.inputExtent : plan.aoExtent;
  const Extent scaled{std::max(1u, base.width / info.scaleDenominator), std::max(1u, base.height / info.scaleDenominator)};
  const std::uint32_t d = std::max(1u, plan.extentDivisor[static_cast<std::size_t>(id)]);
  return {(scaled.width + d - 1) / d, (scaled.height + d - 1) / d};
}

bool holdsInput(Extent have, const std::optional<Offset>& region, Extent needed) {
  if (!region) return have == needed;
  return std::uint64_t(region->x) + needed.width <= have.width && std::uint64_t(region->y) + needed.height <= have.height;
}

std::uint32_t bytesPerTexel(gen::Format format) { return gen::formatInfo(format).bytesPerTexel; }

const PlannedImage* Plan::image(gen::ResourceId id) const {
  for (const auto& i : images)
    if (i.resource == id) return &i;
  return nullptr;
}

gen::ResourceId Plan::resolve(const PlannedPass& pass, gen::ResourceId declared) const {
  for (const auto& [from, to] : pass.aliases)
    if (from == declared) return to;
  return declared;
}

std::string Plan::describe() const {
  std::ostringstream s;
  s << "input " << inputExtent.width << "x" << inputExtent.height << ", AO " << aoExtent.width << "x"
    << aoExtent.height << ", csz levels " << cszLevels << "\n";
  s << "variants:";
  for (std::size_t v = 0; v < gen::kVariantCount; ++v) s << " " << gen::kVariants[v].name << "=" << variants[v];
  s << "\npasses:";
  for (const auto& p : passes) s << " " << gen::pass(p.pass).name;
  s << "\nimages:";
  for (const auto& i : images)
    s << " " << gen::kResources[static_cast<std::size_t>(i.resource)].name << "(" << i.extent.width << "x"
      << i.extent.height << (i.mipLevels > 1 ? ", " + std::to_string(i.mipLevels) + " levels" : "")
      << (i.copies > 1 ? ", x" + std::to_string(i.copies) : "") << ")";
  s << "\nbytes: " << totalBytes << "\n";
  return s.str();
}

Status plan(const Settings& settings, const Camera& camera, const PlanInputs& inputs, Plan& out) {
  out = Plan{};
  if (Status st = validate(settings); !st) return st;
  if (Status st = checkRefusals(settings); !st) return st;
  DepthModel model;
  if (Status st = analyze(camera, model); !st) return st;
  if (Status st = checkExtents(camera, out.inputExtent, out.aoExtent); !st) return st;
  if (inputs.depthSamples == 0)
    return Status::error(StatusCode::InvalidInput, "the depth input has 0 samples per texel (1: single-sample)");
  // Each variant as the effect's `select=` says: a bool setting, a supplied input, or its default.
  // PlanInputs names the optional inputs; a required one (the depth) is always supplied.
  const auto supplied = [&](gen::ResourceId input) { return isRequiredInput(input) || inputs.supplied[input]; };
  for (std::size_t v = 0; v < gen::kVariantCount; ++v) {
    const gen::VariantInfo& info = gen::kVariants[v];
    switch (info.select) {
      case gen::VariantSelect::Setting:
        out.variants[v] = gen::settingValue(settings, static_cast<gen::SettingId>(info.selectIndex)) != 0.0 ? 1 : 0;
        break;
      case gen::VariantSelect::Input:
        out.variants[v] = supplied(static_cast<gen::ResourceId>(info.selectIndex)) ? 1 : 0;
        break;
      case gen::VariantSelect::Output: {
        const auto formats = gen::kResources[info.selectIndex].formats;
        const auto it = std::find(formats.begin(), formats.end(), inputs.outputFormat);
        if (it == formats.end())
          return Status::error(StatusCode::UnsupportedFormat, std::string("the output format ") +
                                                                  formatName(inputs.outputFormat) +
                                                                  " is not one the effect writes (" + outputFormatList() + ")");
        out.variants[v] = static_cast<std::int32_t>(it - formats.begin());
        break;
      }
      case gen::VariantSelect::Multisampled:
        // Only the depth input may be multisampled (the effect's select=multisampled:depth).
        out.variants[v] = static_cast<gen::ResourceId>(info.selectIndex) == gen::ResourceId::depth && inputs.depthSamples > 1 ? 1 : 0;
        break;
      case gen::VariantSelect::Default:
        out.variants[v] = info.defaultValue;
        break;
    }
  }
  if (const auto why = gen::exclusionReason(out.variants); !why.empty()) {
    std::string combo;
    for (std::size_t v = 0; v < gen::kVariantCount; ++v)
      combo += " " + std::string(gen::kVariants[v].name) + "=" + std::to_string(out.variants[v]);
    return Status::error(StatusCode::InvalidInput,
                         "these inputs and settings select an excluded variant combination (" + combo.substr(1) +
                             "): " + std::string(why));
  }

  out.cszLevels = mipLevelsNeeded(settings, camera, model);
  for (std::size_t r = 0; r < gen::kResources.size(); ++r)
    if (const std::int32_t s = gen::kResources[r].divideBy; s >= 0)
      out.extentDivisor[r] = static_cast<std::uint32_t>(gen::settingValue(settings, static_cast<gen::SettingId>(s)));

  for (const auto& info : gen::passes()) {
    const auto id = static_cast<gen::PassId>(&info - gen::passes().data());
    PlannedPass p{id, gen::findPassVariant(id, out.variants), {}};
    if (!p.variant)
      return Status::error(StatusCode::InvalidInput, "no compiled variant of pass '" + std::string(info.name) + "'");
    if (info.levelSlots > 0 && out.cszLevels <= info.firstLevel) continue;  // the chain ends below its levels
    // A pass whose writes all belong to absent variants' resources (linear_z2 without a second
    // layer) has nothing to do.
    if (std::none_of(p.variant->bindings.begin(), p.variant->bindings.end(),
                     [](const gen::BindingInfo& b) { return b.write; }))
      continue;
    // The effect's skip_when= / alias_when= rules (e.g. blur 0: blur and ao_low go, upsample
    // reads ao_raw; docs/effect-math.md §6).
    if (gen::holds(info.skipWhen, settings)) continue;
    if (gen::holds(info.aliasWhen, settings))
      for (const auto& a : info.aliases) p.aliases.push_back({a.declared, a.serving});
    out.passes.push_back(std::move(p));
  }

  // Images: every effect-owned or output resource some planned pass touches, after aliasing.
  for (const auto& p : out.passes) {
    for (const auto& b : p.variant->bindings) {
      const gen::ResourceId id = out.resolve(p, b.resource);
      const auto& r = gen::kResources[static_cast<std::size_t>(id)];
      if (r.kind == gen::ResourceKind::Input || out.image(id)) continue;
      if (r.kind == gen::ResourceKind::Output && inputs.userOutput) continue;
      const Extent e = resourceExtent(out, id);  // not planned yet: the declared extent
      const std::uint32_t levels = r.fullMipChain ? out.cszLevels : 1;
      const gen::Format format = !r.formats.empty() ? inputs.outputFormat  // checked above
                                 : r.formatWhenVariant >= 0 && out.variants[std::size_t(r.formatWhenVariant)] != 0
                                     ? r.formatWhen
                                     : r.format;
      const std::uint32_t copies = r.history ? 2 : 1;
      out.images.push_back({id, format, e, levels, copies, copies * imageBytes(format, e, levels)});
    }
  }
  for (const auto& i : out.images) out.totalBytes += i.bytes;
  return Status::success();
}

std::uint64_t fullAllocationBytes(const Camera& camera, const PlanInputs& inputs) {
  Extent input, ao;
  if (!checkExtents(camera, input, ao)) return 0;
  std::uint64_t total = 0;
  for (const auto& r : gen::kResources) {
    if (r.kind == gen::ResourceKind::Input) continue;
    if (r.kind == gen::ResourceKind::Output && inputs.userOutput) continue;
    const Extent base = r.inputExtent ? input : ao;
    // format_when=: the larger of the two formats (the settings are not known here).
    gen::Format format = r.formats.empty() ? r.format : inputs.outputFormat;
    if (r.formatWhenVariant >= 0 && bytesPerTexel(r.formatWhen) > bytesPerTexel(format)) format = r.formatWhen;
    total += (r.history ? 2 : 1) * imageBytes(format, base, r.fullMipChain ? fullChainLevels(base) : 1);
  }
  return total;
}

}  // namespace sao
