// The AlchemyAO obscurance reference: the integral that the effect's estimator (AlchemyAO eq. 10,
// docs/effect-math.md §5.5-5.6) approximates, estimated by ray casting.
//
// Derivation (docs/reference.md has it in full). AlchemyAO eq. 6-8 write the obscurance at C with
// normal n as an integral over the hemisphere Omega of the falloff-weighted occluder,
//   A = 1 - u * Integral_Gamma (v.n) / max(u^2, v.v) dw,  v = t(C, w) w,
// Gamma being the directions whose first hit t lies within r. Eq. 9 estimates it from s uniform
// directions (pdf 1/(2 pi)): 1 - (2 pi u / s) Sum max(0, v_i.n) H(r - |v_i|) / max(u^2, v_i.v_i).
// Section 2.3 then (a) scales by sigma/pi in place of u in the numerator, (b) replaces max(u^2, v.v)
// by v.v + eps and (c) adds the bias z_C*beta to v.n, which gives eq. 10's factor 2 sigma / s:
//   (2 pi / s) * (sigma / pi) = 2 sigma / s.
// So eq. 10 (without its clamp and contrast) is the uniform-direction Monte-Carlo estimator of
//   O = (sigma/pi) Integral_Omega H(r - t) max(0, t cos + z_C beta) / (t^2 + eps) dw,  cos = w.n,
// and that O is what this file computes. Here the directions are cosine-weighted, pdf cos/pi, so
// one ray contributes f(w) / pdf(w):
//   c(w) = (sigma/pi) H(r - t) max(0, t cos + z_C beta) / (t^2 + eps) * pi / cos
//        = sigma H(r - t) max(0, t cos + z_C beta) / (cos (t^2 + eps)),
// a ray without a hit within r contributes 0, and E[c] = Integral_Omega f(w) (cos/pi)(pi/cos) dw = O
// (unbiased: f vanishes where cos <= 0, since z_C beta <= 0, and the pdf is positive wherever
// cos > 0). Dividing by cos cancels the cos of v.n: max(0, t cos + z_C beta) / cos <= t, so
// 0 <= c <= sigma t / (t^2 + eps) <= sigma / (2 sqrt(eps)), and the variance is finite.
// The output clamps the converged mean once: clamp(1 - O, 0, 1)^k; rays are never clamped.
#include <algorithm>
#include <cmath>

#include "sampling.h"
#include "sao/cpu/parallel.h"
#include "sao/raytrace/raytrace.h"

namespace sao::raytrace {

double obscuranceAt(const RayScene& scene, glm::dvec3 p, glm::dvec3 n, double zC, double radius, double intensity,
                    double bias, double epsilon, std::uint32_t rays, std::uint64_t seed, double tMin) {
  if (rays == 0) return 0.0;
  const detail::Frame frame(n);
  std::uint64_t state = seed;
  detail::splitmix(state);
  const double zBeta = zC * bias;  // <= 0 in front of the camera
  double sum = 0;
  for (std::uint32_t r = 0; r < rays; ++r) {
    double cosTheta = 0;
    const glm::dvec3 dir = detail::cosineDirection(frame, state, cosTheta);
    const auto hit = scene.intersect(p, dir, radius, tMin);  // |dir| = 1: t is the distance
    if (!hit.hit || !(hit.t <= radius) || !(cosTheta > 0)) continue;
    const double t = hit.t;
    sum += intensity * std::max(0.0, t * cosTheta + zBeta) / (cosTheta * (t * t + epsilon));
  }
  return sum / rays;
}

ObscuranceOptions obscuranceOptions(const Settings& s, std::uint32_t rays, std::uint64_t seed) {
  ObscuranceOptions o;
  o.radius = s.radius;
  o.intensity = s.intensity;
  o.bias = s.bias;
  o.epsilon = s.epsilon;
  o.contrast = s.contrast;
  o.rays = rays;
  o.seed = seed;
  return o;
}

Status referenceObscurance(const RayScene& scene, const Camera& camera, const Primary& primary,
                           const scenes::View& view, const ObscuranceOptions& o, FloatImage& ao) {
  auto bad = [](const std::string& what) { return Status::error(StatusCode::InvalidInput, "obscurance reference: " + what); };
  if (!(o.radius > 0) || !std::isfinite(o.radius)) return bad("radius must be a finite number > 0");
  if (!(o.intensity >= 0) || !std::isfinite(o.intensity)) return bad("intensity must be a finite number >= 0");
  if (!(o.bias >= 0) || !std::isfinite(o.bias)) return bad("bias must be a finite number >= 0");
  if (!(o.epsilon > 0) || !std::isfinite(o.epsilon)) return bad("epsilon must be a finite number > 0");
  if (!(o.contrast > 0) || !std::isfinite(o.contrast)) return bad("contrast must be a finite number > 0");
  if (o.rays == 0) return bad("needs at least one ray per pixel");
  const double u = camera.metersToViewUnits;
  if (!(u > 0) || !std::isfinite(u)) return bad("the camera's metersToViewUnits must be a finite number > 0");
  const Extent input{camera.width + 2 * camera.guardBand, camera.height + 2 * camera.guardBand};
  if (primary.position.extent != input || primary.normal.extent != input)
    return bad("primary images do not match the camera's depth extent");
  // The effect's units (docs/effect-math.md §2): lengths in view units, the scene's world units.
  const double radius = o.radius * u, intensity = o.intensity * radius, epsilon = o.epsilon * u * u;
  const glm::dmat4 toWorld = glm::inverse(scenes::viewMatrix(view));
  ao = FloatImage({camera.width, camera.height}, 1, 1.0f);
  const std::uint32_t g = camera.guardBand;
  cpu::parallelFor(camera.height, o.threads, [&](std::uint32_t y) {
    for (std::uint32_t x = 0; x < camera.width; ++x) {
      if (primary.position.at(x + g, y + g, 3) == 0.0f) continue;  // sky
      const glm::dvec3 pc(primary.position.at(x + g, y + g, 0), primary.position.at(x + g, y + g, 1),
                          primary.position.at(x + g, y + g, 2));
      const glm::dvec3 ncam(primary.normal.at(x + g, y + g, 0), primary.normal.at(x + g, y + g, 1),
                            primary.normal.at(x + g, y + g, 2));
      const glm::dvec3 p = glm::dvec3(toWorld * glm::dvec4(pc, 1.0));
      const glm::dvec3 n = glm::normalize(glm::dvec3(toWorld * glm::dvec4(ncam, 0.0)));
      const double obscurance = obscuranceAt(scene, p, n, pc.z, radius, intensity, o.bias, epsilon, o.rays,
                                             detail::pixelSeed(o.seed, x, y), 1e-4 * std::max(1.0, glm::length(pc)));
      const double a = std::clamp(1.0 - obscurance, 0.0, 1.0);
      ao.at(x, y) = float(o.contrast == 1.0 ? a : std::pow(a, o.contrast));
    }
  });
  return Status::success();
}

}  // namespace sao::raytrace
