#include "scene_cache.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include "sao/raytrace/converged.h"
#include "sao/raytrace/screen_visibility.h"
#include "sao/samples/error_structure.h"
#include "sao/samples/metrics.h"

namespace sao::bench {

void fail(const std::string& message) {
  std::fprintf(stderr, "\nsao-bench: %s\n", message.c_str());
  std::exit(1);
}

std::vector<std::string> benchScenes(bool quick) {
  if (quick) return {"crease", "sphere-plane"};
  return {"sponza-like", "sphere-plane", "crease", "thin", "gears"};
}

ScreenKey screenKey(const Settings& s, Extra extra, std::optional<bool> thicknessFromWidth) {
  return {s.radius, s.thickness, s.depth_tolerance, extra, thicknessFromWidth.value_or(s.thickness_model == 1)};
}

ObscuranceKey obscuranceKey(const Settings& s) { return {s.radius, s.intensity, s.bias, s.epsilon, s.contrast}; }

Prepared& SceneCache::prepare(const std::string& name, std::uint32_t w, std::uint32_t h) {
  const std::string key = name + "@" + std::to_string(w) + "x" + std::to_string(h);
  auto it = scenes_.find(key);
  if (it != scenes_.end()) return it->second;
  Prepared& p = scenes_[key];
  if (Status s = scenes::loadScene(name, p.scene); !s) fail(s.message);
  for (const std::string& warning : p.scene.warnings) std::fprintf(stderr, "sao-bench: warning: %s\n", warning.c_str());
  if (Status s = raytrace::RayScene::create(p.scene.mesh, p.rays); !s) fail(s.message);
  if (orthographic_) p.scene.views[0] = scenes::toOrthographic(p.scene.views[0], p.scene.mesh);
  p.camera = scenes::makeCamera(p.scene.views[0], w, h, INFINITY, ClipDepth::ZeroToOne, true);
  const scenes::UnitChoice unit = scenes::chooseUnits(p.scene.mesh, p.scene.units, units_);
  if (units_) std::fprintf(stderr, "\nsao-bench: %s: units %s\n", name.c_str(), unit.note.c_str());
  // The depth is drawn with a factor of 1 (the scene's world is in its own units, the view units;
  // the prepass would scale a world in metres); the effect and the references get the scene's.
  if (prepass_) {
    prepass::PrepassOptions po;
    po.format = DepthFormat::D32F;
    po.secondLayer = true;
    po.minSeparation = kSecondLayerSeparation * unit.metersToViewUnits;
    prepass::PrepassResult r;
    if (Status s = prepass_->render(p.scene.mesh, p.scene.views[0], p.camera, po, r); !s)
      fail(std::string(prepass_->name()) + " prepass of " + name + ": " + s.message);
    p.primary.depth = std::move(r.depth);
    p.primary.position = std::move(r.position);
    p.primary.normal = std::move(r.normal);
    p.secondLayer.emplace();
    p.secondLayer->depth = std::move(r.depth2);
    p.secondLayer->position = std::move(r.position2);
    p.secondLayer->normal = std::move(r.normal2);
  } else if (Status s = raytrace::castPrimary(*p.rays, p.scene.views[0], p.camera, DepthFormat::D32F, p.primary); !s) {
    fail(s.message);
  }
  p.mask = samples::geometryMask(p.primary.position, 0);
  p.silhouette = samples::silhouetteBand(p.primary.position, 0);
  p.camera.metersToViewUnits = unit.metersToViewUnits;
  return p;
}

const FloatImage& nearFieldReference(Prepared& p, double radius, std::uint32_t rays) {
  auto it = p.references.find(radius);
  if (it != p.references.end()) return it->second;
  raytrace::ReferenceOptions o;
  o.radius = radius * p.camera.metersToViewUnits;  // radius is in metres, the scene in its own units
  o.rays = rays;
  FloatImage& ref = p.references[radius];
  if (Status s = raytrace::referenceAmbientOcclusion(*p.rays, p.camera, p.primary, p.scene.views[0], o, ref); !s)
    fail(s.message);
  return ref;
}

std::pair<double, double> nearFieldNoise(Prepared& p, double radius, std::uint32_t rays) {
  auto it = p.referenceNoise.find(radius);
  if (it != p.referenceNoise.end()) return it->second;
  const FloatImage& first = nearFieldReference(p, radius, rays);
  raytrace::ReferenceOptions o;
  o.radius = radius * p.camera.metersToViewUnits;
  o.rays = rays;
  o.seed = 2;
  FloatImage second;
  if (Status s = raytrace::referenceAmbientOcclusion(*p.rays, p.camera, p.primary, p.scene.views[0], o, second); !s)
    fail(s.message);
  double variance = 0;
  std::size_t pixels = 0;
  for (std::size_t i = 0; i < p.mask.size(); ++i)
    if (p.mask[i]) variance += double(first.data[i]) * (1.0 - first.data[i]), ++pixels;
  const double measured = samples::compareToReference(second, first, p.mask).raw.rmse / std::sqrt(2.0);
  return p.referenceNoise[radius] = {measured, std::sqrt(variance / double(std::max<std::size_t>(pixels, 1)) / rays)};
}

const FloatImage& obscuranceReference(Prepared& p, const Settings& s, std::uint32_t rays) {
  const ObscuranceKey key = obscuranceKey(s);
  auto it = p.obscurance.find(key);
  if (it != p.obscurance.end()) return it->second;
  FloatImage& ref = p.obscurance[key];
  if (Status st = raytrace::referenceObscurance(*p.rays, p.camera, p.primary, p.scene.views[0],
                                                raytrace::obscuranceOptions(s, rays), ref);
      !st)
    fail(st.message);
  return ref;
}

const raytrace::Primary& secondLayer(Prepared& p) {
  if (!p.secondLayer) {
    p.secondLayer.emplace();
    if (Status s = raytrace::castSecondLayer(*p.rays, p.scene.views[0], p.camera, DepthFormat::D32F,
                                             kSecondLayerSeparation * p.camera.metersToViewUnits, *p.secondLayer);
        !s)
      fail(s.message);
  }
  return *p.secondLayer;
}

samples::RunInputs runInputs(Prepared& p, Extra extra) {
  samples::RunInputs inputs{&p.primary.depth, nullptr, nullptr};
  if (extra == Extra::Normals) inputs.normals = &p.primary.normal;
  if (extra == Extra::SecondLayer) inputs.depth2 = &secondLayer(p).depth;
  return inputs;
}

const char* inputsName(Extra extra) {
  switch (extra) {
    case Extra::Normals: return "depth+normals";
    case Extra::SecondLayer: return "depth+depth2";
    case Extra::None: break;
  }
  return "depth";
}

Converged& convergedReference(Prepared& p, const Settings& s, Extra extra, const ConvergedOptions& options) {
  const ConvergedKey key{obscuranceKey(s), extra};
  auto it = p.converged.find(key);
  if (it != p.converged.end()) return it->second;
  const samples::RunInputs inputs = runInputs(p, extra);
  Converged& c = p.converged[key];
  raytrace::ConvergedOptions co;
  co.taps = options.taps;
  co.rings = std::max(1u, options.taps / 32);  // 128 rings at the default 4096 taps (docs/reference.md)
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpuStart = std::clock();
  if (Status st = raytrace::convergedEstimator(s, p.camera, {inputs.depth, inputs.depth2, inputs.normals}, co, c.ao); !st)
    fail("reference (c): " + st.message);
  c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  c.cpuSeconds = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
  if (options.measureNoise) {  // a second, independent estimate: E[(c1 - c2)^2] / 2 is the variance
    FloatImage second;
    co.seed = 2;
    if (Status st = raytrace::convergedEstimator(s, p.camera, {inputs.depth, inputs.depth2, inputs.normals}, co, second); !st)
      fail("reference (c): " + st.message);
    c.noise = samples::compareToReference(second, c.ao, p.mask).raw.rmse / std::sqrt(2.0);
  }
  if (options.nearFieldAo) c.rmseVsAo = samples::compareToReference(c.ao, *options.nearFieldAo, p.mask).raw.rmse;
  if (options.obscurance) c.rmseVsObscurance = samples::compareToReference(c.ao, *options.obscurance, p.mask).raw.rmse;
  return c;
}

Screen& screenReference(Prepared& p, const Settings& s, Extra extra, const ScreenOptions& options) {
  const ScreenKey key = screenKey(s, extra, options.thicknessFromWidth);
  auto it = p.screen.find(key);
  if (it != p.screen.end()) return it->second;
  const samples::RunInputs inputs = runInputs(p, extra);
  Screen& d = p.screen[key];
  raytrace::ScreenVisibilityOptions so;
  so.slices = options.slices;
  so.stride = options.stride;
  so.thicknessFromWidth = options.thicknessFromWidth;
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpuStart = std::clock();
  if (Status st = raytrace::screenVisibility(s, p.camera, {inputs.depth, inputs.depth2, inputs.normals}, so, d.ao); !st)
    fail("reference (d): " + st.message);
  d.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  d.cpuSeconds = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
  d.mask = p.mask;
  for (std::uint32_t y = 0; y < p.camera.height; ++y)
    for (std::uint32_t x = 0; x < p.camera.width; ++x)
      if (x % options.stride != 0 || y % options.stride != 0) d.mask[std::size_t(y) * p.camera.width + x] = 0;
  if (options.nearFieldAo) d.rmseVsAo = samples::compareToReference(d.ao, *options.nearFieldAo, d.mask).raw.rmse;
  if (options.converged)
    d.rmseConvergedVsScreen = samples::compareToReference(*options.converged, d.ao, d.mask).raw.rmse;
  return d;
}

}  // namespace sao::bench
