// Compiled with -ffp-contract=off (samples/bench/CMakeLists.txt): the tap addresses are float
// expressions that must round as the shader's do (effect/cpu/sao_math.h).
#include "traffic_replay.h"

#include "sao/constants.h"
#include "sao/cpu/reference.h"
#include "sao/plan.h"
#include "sao/presets.h"
#include "tap_trace.h"
#include "width_trace.h"

namespace sao::bench {

namespace detail = sao::cpu::detail;

struct TrafficScene::Impl {
  Camera camera;
  DepthEncoding encoding = DepthEncoding::Hardware;
  Extent depthExtent;
  std::vector<detail::Image<float>> csz;  // every level down to 1x1, at most SAO_MAX_MIP_LEVELS
};

TrafficScene::TrafficScene(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
TrafficScene::~TrafficScene() = default;

Status TrafficScene::create(const DepthImage& depth, const Camera& camera, std::unique_ptr<TrafficScene>& out) {
  cpu::Options options;
  options.precision = cpu::Precision::Float;
  cpu::Result r;
  if (Status s = cpu::run(presetSettings(Preset::Medium), camera, {&depth, nullptr, nullptr}, options, r); !s)
    return s;
  auto impl = std::make_unique<Impl>();
  impl->camera = camera;
  impl->encoding = depth.format == DepthFormat::LinearZ ? DepthEncoding::LinearZ : DepthEncoding::Hardware;
  impl->depthExtent = depth.extent;
  const FloatImage& z0 = r.csz.at(0);
  const int w = int(z0.extent.width), h = int(z0.extent.height);
  detail::Image<float>& level0 = impl->csz.emplace_back(w, h, 1);
  level0.v = z0.data;
  // Table 1's rotated grid, as the mips pass: level m is max(1, size0 >> m) large.
  for (int m = 1; m < gen::SAO_MAX_MIP_LEVELS && ((w >> (m - 1)) > 1 || (h >> (m - 1)) > 1); ++m) {
    const detail::Image<float>& prev = impl->csz.back();
    detail::Image<float> next(std::max(w >> m, 1), std::max(h >> m, 1), 1);
    for (int y = 0; y < next.h; ++y)
      for (int x = 0; x < next.w; ++x) {
        int sx, sy;
        detail::rotatedGridSource(x, y, prev.w, prev.h, sx, sy);
        next.at(x, y) = prev.at(sx, sy);
      }
    impl->csz.push_back(std::move(next));
  }
  out.reset(new TrafficScene(std::move(impl)));
  return Status::success();
}

Status TrafficScene::replay(const Settings& settings, const TrafficVariant& variant, std::span<const Machine> machines,
                            ReplayResult& out) const {
  Settings s = settings;
  s.use_z_hierarchy = variant.zHierarchy;
  gen::SaoParams params{};
  if (Status st = computeConstants(s, impl_->camera, impl_->encoding, params); !st) return st;
  if (params.max_mip < 0 || std::size_t(params.max_mip) >= impl_->csz.size())
    return Status::error(StatusCode::InvalidInput, "traffic replay: max_mip " + std::to_string(params.max_mip) +
                                                       " beyond the " + std::to_string(impl_->csz.size()) +
                                                       " csz levels of the scene");
  const detail::Image<float>& z0 = impl_->csz[0];
  if (params.ao_size.x + 2 * params.guard.x != z0.w || params.ao_size.y + 2 * params.guard.y != z0.h)
    return Status::error(StatusCode::InvalidInput, "traffic replay: the camera does not match the scene's depth");

  // Surface 0: csz (its levels), surface 1: the normals input at the depth's extent (rgba16f),
  // surfaces 2 and 3: csz_share (rg32f: z and the packed shares) and width_run (rg16f), csz's
  // levels, with thickness_model 1.
  std::vector<SurfaceShape> surfaces(4);
  surfaces[0].texelBytes = variant.zTexelBytes;
  for (const auto& l : impl_->csz) surfaces[0].levels.push_back({std::uint32_t(l.w), std::uint32_t(l.h)});
  surfaces[1] = {8, {{impl_->depthExtent.width, impl_->depthExtent.height}}};
  surfaces[2] = {bytesPerTexel(gen::kResources[std::size_t(gen::ResourceId::csz_share)].format), surfaces[0].levels};
  surfaces[3] = {bytesPerTexel(gen::kResources[std::size_t(gen::ResourceId::width_run)].format), surfaces[0].levels};
  static_assert(int(cpu::trace::Surface::Csz) == 0 && int(cpu::trace::Surface::Normals) == 1 &&
                int(cpu::trace::Surface::CszShare) == 2 && int(cpu::trace::Surface::WidthRun) == 3);

  std::vector<TrafficModel> models;
  for (const Machine& m : machines) {
    if (Status st = validate(m); !st) return st;
    models.emplace_back(m, surfaces);
  }
  GroupReads group;
  // thickness_model 1: the width passes run first, one dispatch each, through the same caches.
  out.widthTraffic.assign(models.size(), Traffic{});
  if (s.thickness_model == 1) {
    const cpu::trace::WidthTrace width(impl_->csz, params);
    for (int pass = 0; pass < 2; ++pass) {
      for (int gy = 0; gy < width.groupsY(); ++gy)
        for (int gx = 0; gx < width.groupsX(); ++gx) {
          group.clear();
          if (pass == 0)
            width.widthGroup(gx, gy, group);
          else
            width.resolveGroup(gx, gy, group);
          for (TrafficModel& m : models) m.add(group);
        }
      for (TrafficModel& m : models) m.finish();
    }
    for (std::size_t i = 0; i < models.size(); ++i) out.widthTraffic[i] = models[i].traffic();
  }
  const cpu::trace::AoSampleTrace trace(impl_->csz, params, variant.zHierarchy, variant.normalsSupplied, 8, 8,
                                        s.estimator == 1);
  for (int gy = 0; gy < trace.groupsY(); ++gy)
    for (int gx = 0; gx < trace.groupsX(); ++gx) {
      group.clear();
      trace.group(gx, gy, group);
      for (TrafficModel& m : models) m.add(group);
    }
  out.traffic.clear();
  for (TrafficModel& m : models) {
    m.finish();
    out.traffic.push_back(m.traffic());
  }
  out.pixels = std::uint64_t(trace.aoWidth()) * std::uint64_t(trace.aoHeight());  // AO pixels sampled
  out.maxMip = params.max_mip;
  return Status::success();
}

}  // namespace sao::bench
