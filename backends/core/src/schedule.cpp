#include "sao/schedule.h"

#include <algorithm>
#include <sstream>
#include <string>

namespace sao {
namespace {

std::uint32_t levelsOf(const Plan& plan, gen::ResourceId id) {
  const PlannedImage* img = plan.image(id);
  return img ? img->mipLevels : 1;
}

bool writes(const gen::PassInfo& info, gen::ResourceId id) {
  return std::find(info.writes.begin(), info.writes.end(), id) != info.writes.end();
}

const char* name(gen::ResourceId id) { return gen::kResources[static_cast<std::size_t>(id)].name.data(); }

std::string extentText(Extent e) { return std::to_string(e.width) + "x" + std::to_string(e.height); }

// Per image level: what the frame did to it so far, for the hazards of the next access.
struct LevelState {
  bool written = false;       // stored to earlier in this frame
  bool writePending = false;  // stored to and not yet made visible to sampled reads
  bool readSinceWrite = false;
};

class HazardTracker {
 public:
  explicit HazardTracker(std::vector<Hazard>& out) : out_(out) {}

  // Hazards from here on belong to the next dispatch (runs of levels merge only within one).
  void beginDispatch() { first_ = out_.size(); }

  // A sampled read of levels [base, base + count): one ReadAfterWrite hazard per run of levels
  // with a pending write.
  void read(gen::ResourceId id, std::uint32_t base, std::uint32_t count) {
    auto& levels = state_[static_cast<std::size_t>(id)];
    for (std::uint32_t m = base; m < base + count && m < levels.size(); ++m) {
      if (levels[m].writePending) {
        add(id, m, HazardKind::ReadAfterWrite);
        levels[m].writePending = false;
      }
      levels[m].readSinceWrite = true;
    }
  }

  void write(gen::ResourceId id, std::uint32_t level) {
    auto& s = state_[static_cast<std::size_t>(id)][level];
    if (s.readSinceWrite) add(id, level, HazardKind::WriteAfterRead);
    else if (s.written) add(id, level, HazardKind::WriteAfterWrite);
    s = {true, true, false};
  }

 private:
  // Extends the previous hazard when it covers the level just below on the same image.
  void add(gen::ResourceId id, std::uint32_t level, HazardKind kind) {
    if (out_.size() > first_) {
      Hazard& last = out_.back();
      if (last.resource == id && last.kind == kind && last.baseLevel + last.levelCount == level) {
        ++last.levelCount;
        return;
      }
    }
    out_.push_back({id, level, 1, kind});
  }

  std::vector<Hazard>& out_;
  std::size_t first_ = 0;
  std::array<std::array<LevelState, gen::SAO_MAX_MIP_LEVELS>, gen::kResources.size()> state_{};
};

}  // namespace

Schedule makeSchedule(const Plan& plan) {
  Schedule s;
  HazardTracker tracker(s.hazards);
  std::array<bool, gen::kResources.size()> read{}, written{};

  for (std::uint32_t i = 0; i < plan.passes.size(); ++i) {
    const PlannedPass& p = plan.passes[i];
    const gen::PassInfo& info = gen::pass(p.pass);
    ScheduledDispatch d;
    d.passIndex = i;
    d.pass = p.pass;
    d.variant = p.variant;
    // levels=A..B: levels A.. from A - 1; else level 0.
    d.level = info.firstLevel;
    d.firstBinding = static_cast<std::uint32_t>(s.bindings.size());
    bool sized = false;
    for (const gen::BindingInfo& b : p.variant->bindings) {
      ScheduledBinding sb;
      sb.binding = b.binding;
      sb.resource = plan.resolve(p, b.resource);
      sb.write = b.write;
      sb.previousFrame = !b.write && gen::kResources[static_cast<std::size_t>(sb.resource)].history;
      const std::uint32_t levels = levelsOf(plan, sb.resource);
      if (b.write) {
        sb.baseLevel = d.level;
        // levels=A..B: slot j is level A + j; the chain's levels from A on, at most B - A + 1.
        if (info.levelSlots > 0) sb.levelCount = std::min(info.levelSlots, levels - info.firstLevel);
        if (!sized) {  // the dispatch covers the (level of the) first written image
          const Extent e = levelExtent(resourceExtent(plan, sb.resource), sb.baseLevel);
          const std::uint32_t coverX = info.localX * info.texelsX, coverY = info.localY * info.texelsY;
          d.groupsX = (e.width + coverX - 1) / coverX;
          d.groupsY = (e.height + coverY - 1) / coverY;
          sized = true;
        }
      } else if (info.levelSlots > 0 && writes(info, b.resource)) {
        sb.baseLevel = info.firstLevel - 1;  // levels=A..B reads level A - 1 of a chain it writes, at lod 0
      } else {
        sb.levelCount = levels;
        sb.wholeChain = levels > 1;
      }
      s.bindings.push_back(sb);
    }
    d.bindingCount = static_cast<std::uint32_t>(s.bindings.size()) - d.firstBinding;
    if (!sized) {
      d.groupsX = (plan.aoExtent.width + info.localX - 1) / info.localX;
      d.groupsY = (plan.aoExtent.height + info.localY - 1) / info.localY;
    }

    d.firstHazard = static_cast<std::uint32_t>(s.hazards.size());
    tracker.beginDispatch();
    for (const ScheduledBinding& b : s.bindingsOf(d))
      if (!b.write) {
        // The previous frame's copy of a history: written before the frame (its entry hazard).
        if (!b.previousFrame) tracker.read(b.resource, b.baseLevel, b.levelCount);
        read[static_cast<std::size_t>(b.resource)] = true;
      }
    for (const ScheduledBinding& b : s.bindingsOf(d))
      if (b.write) {
        for (std::uint32_t m = b.baseLevel; m < b.baseLevel + b.levelCount; ++m) tracker.write(b.resource, m);
        written[static_cast<std::size_t>(b.resource)] = true;
      }
    d.hazardCount = static_cast<std::uint32_t>(s.hazards.size()) - d.firstHazard;
    s.dispatches.push_back(d);
  }

  s.firstEntryHazard = static_cast<std::uint32_t>(s.hazards.size());
  for (std::size_t r = 0; r < gen::kResources.size(); ++r) {
    const auto id = static_cast<gen::ResourceId>(r);
    const auto kind = gen::kResources[r].kind;
    if (kind == gen::ResourceKind::Input && read[r]) s.hazards.push_back({id, 0, 1, HazardKind::CallerWrote});
    if (gen::kResources[r].history && read[r]) s.hazards.push_back({id, 0, 1, HazardKind::ReadAfterWrite, true});
    // The previous frame (or the caller, for the output) read or wrote what this frame writes.
    if (written[r])
      s.hazards.push_back({id, 0, levelsOf(plan, id),
                           read[r] || kind == gen::ResourceKind::Output ? HazardKind::WriteAfterRead
                                                                         : HazardKind::WriteAfterWrite});
  }
  s.entryHazardCount = static_cast<std::uint32_t>(s.hazards.size()) - s.firstEntryHazard;
  s.firstExitHazard = static_cast<std::uint32_t>(s.hazards.size());
  for (std::size_t r = 0; r < gen::kResources.size(); ++r)
    if (gen::kResources[r].kind == gen::ResourceKind::Output && written[r])
      s.hazards.push_back({static_cast<gen::ResourceId>(r), 0, 1, HazardKind::CallerReads});
  s.exitHazardCount = static_cast<std::uint32_t>(s.hazards.size()) - s.firstExitHazard;
  return s;
}

std::string Schedule::describe() const {
  static constexpr const char* kKind[] = {"RAW", "WAR", "WAW", "caller-wrote", "caller-reads"};
  auto levels = [](std::uint32_t base, std::uint32_t count) {
    return count == 1 ? "[" + std::to_string(base) + "]"
                      : "[" + std::to_string(base) + ".." + std::to_string(base + count - 1) + "]";
  };
  auto hazardList = [&](std::span<const Hazard> hs) {
    std::string t;
    for (const Hazard& h : hs)
      t += std::string(" ") + kKind[static_cast<int>(h.kind)] + " " + name(h.resource) +
           (h.previousFrame ? "(prev)" : "") + levels(h.baseLevel, h.levelCount);
    return t;
  };
  std::ostringstream o;
  o << "entry:" << hazardList(entryHazards()) << "\n";
  for (const ScheduledDispatch& d : dispatches) {
    o << gen::pass(d.pass).name;
    if (d.level) o << "@" << d.level;
    o << " " << d.groupsX << "x" << d.groupsY << ":";
    for (const ScheduledBinding& b : bindingsOf(d))
      o << " " << b.binding << (b.write ? "=w " : "=r ") << name(b.resource) << (b.previousFrame ? "(prev)" : "")
        << levels(b.baseLevel, b.levelCount);
    if (d.hazardCount) o << " | before:" << hazardList(hazardsBefore(d));
    o << "\n";
  }
  o << "exit:" << hazardList(exitHazards()) << "\n";
  return o.str();
}

Status checkSupplied(const Plan& plan, const SuppliedImages& images, bool outputExpected, const char* who) {
  std::array<bool, gen::kResources.size()> needed{};
  for (const PlannedPass& p : plan.passes)
    for (const gen::BindingInfo& b : p.variant->bindings)
      if (!b.write) needed[static_cast<std::size_t>(plan.resolve(p, b.resource))] = true;

  for (std::size_t r = 0; r < gen::kResources.size(); ++r) {
    const SuppliedImage& in = images[r];
    const auto id = static_cast<gen::ResourceId>(r);
    switch (gen::kResources[r].kind) {
      case gen::ResourceKind::Input:
        if (needed[r] && !in.supplied)
          return Status::error(StatusCode::InvalidInput,
                               std::string(who) + ": the plan reads the " + name(id) + " input but none is supplied");
        if (!needed[r] && in.supplied)
          return Status::error(StatusCode::InvalidInput, std::string(who) + ": a " + name(id) +
                                                             " input is supplied but the effect's configuration reads none");
        if (in.supplied && !holdsInput(in.extent, in.region, plan.inputExtent)) {
          std::string message = std::string(who) + ": the " + name(id) + " input is " + extentText(in.extent) +
                                ", the camera needs " + extentText(plan.inputExtent) + " (the viewport " +
                                extentText(plan.aoExtent) + " plus twice the guard band " +
                                std::to_string((plan.inputExtent.width - plan.aoExtent.width) / 2) + ")";
          if (in.region)
            message += " at offset (" + std::to_string(in.region->x) + ", " + std::to_string(in.region->y) +
                       "), which ends at (" + std::to_string(std::uint64_t(in.region->x) + plan.inputExtent.width) +
                       ", " + std::to_string(std::uint64_t(in.region->y) + plan.inputExtent.height) +
                       "): the region must lie inside the texture";
          else
            message += "; to read a region of a larger texture, set Inputs::region";
          return Status::error(StatusCode::InvalidInput, message);
        }
        break;
      case gen::ResourceKind::Output:
        if (outputExpected && !in.supplied)
          return Status::error(StatusCode::InvalidInput,
                               std::string(who) + ": the effect was configured to write the caller's " + name(id) +
                                   " image but none is supplied");
        if (!outputExpected && in.supplied)
          return Status::error(StatusCode::InvalidInput,
                               std::string(who) + ": an " + name(id) +
                                   " image is supplied but the effect was configured to own its output");
        if (in.supplied && !(in.extent == plan.aoExtent))
          return Status::error(StatusCode::InvalidInput, std::string(who) + ": the output " + name(id) + " is " +
                                                             extentText(in.extent) + " but the viewport (the AO extent) is " +
                                                             extentText(plan.aoExtent));
        break;
      case gen::ResourceKind::Image: break;
    }
  }
  return Status::success();
}

bool sameImage(const PlannedImage& a, const PlannedImage& b) {
  return a.resource == b.resource && a.format == b.format && a.extent == b.extent && a.mipLevels == b.mipLevels;
}

bool sameImages(const Plan& a, const Plan& b) {
  return std::equal(a.images.begin(), a.images.end(), b.images.begin(), b.images.end(), sameImage);
}

}  // namespace sao
