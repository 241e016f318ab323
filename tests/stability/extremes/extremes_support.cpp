#include "extremes_support.h"

namespace sao::stability {

Camera convCamera(const Conv& cv, std::uint32_t w, std::uint32_t h, std::uint32_t guard, bool ortho,
                  double orthoHalfHeight) {
  if (ortho) return orthoCamera(w, h, 0.1, std::isinf(cv.far) ? 1e4 : cv.far, cv.clip, cv.reversed, guard, orthoHalfHeight);
  return camera(w, h, 0.1, cv.far, cv.clip, cv.reversed, guard);
}

SceneRun runScene(const std::string& label, const Settings& settings, const Camera& cam, const test::Scene& scene,
                  DepthFormat format, CaseOptions opt) {
  SceneRun r;
  r.depth = renderGpuDepth(scene, cam, format);
  r.z = aoPixelZ(scene, cam);
  r.sky.resize(r.z.size());
  for (std::size_t i = 0; i < r.z.size(); ++i) r.sky[i] = r.z[i] == 0.0;
  opt.skyMask = &r.sky;
  r.runs = runCase(label, settings, cam, {&r.depth, nullptr, nullptr}, opt);
  return r;
}

std::vector<bool> notMask(const std::vector<bool>& m) {
  std::vector<bool> o(m.size());
  for (std::size_t i = 0; i < m.size(); ++i) o[i] = !m[i];
  return o;
}

}  // namespace sao::stability
