// Walls facing the camera and at grazing incidence, perspective and orthographic: the bias each
// depth format needs.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "extremes_support.h"

namespace sao::stability {
namespace {

const double kBiases[] = {0, 1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5};

// Min A over the wall pixels whose taps stay inside the depth input (r' <= distance to its border:
// past the border the effect extends the edge texel at constant depth, a screen-space limit that
// is not the bias's business), for one backend.
double wallMinA(const BackendRun& b, const SceneRun& r, const Camera& cam, const ParamBlock& p) {
  double m = 1;
  const int W = int(cam.width), H = int(cam.height), g = int(cam.guardBand);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const double z = r.z[std::size_t(y) * W + x];
      if (z == 0) continue;
      const double rpx = std::min(double(p.radius) * p.proj_scale / (p.ortho ? 1.0 : -z), 65536.0);
      const int border = std::min({x + g, W + g - 1 - x, y + g, H + g - 1 - y});
      if (rpx > border) continue;
      m = std::min(m, double(b.out.ao.at(std::uint32_t(x), std::uint32_t(y))));
    }
  return m;
}

TEST(Walls, FacingAndGrazingWallNeedNoMoreThanTheDefaultBias) {
  // A plane through (0, 0, -D) facing the camera, and the same plane turned 89° about the vertical
  // axis (grazing incidence on the centre column; it then spans ~0.02 D .. infinity across the
  // left half of the image). Default radius 1 m, and a radius projecting to 8 px at D. For each
  // format: the smallest bias (of 0, 1e-4, 2e-4, 5e-4, ... 0.5) with min A >= 1 - 1/255 over the
  // wall pixels whose taps stay inside the input. Grazing walls also run without the z hierarchy,
  // which separates depth precision from the MIP approximation (eq. 9-10: a tap at h >= 2^log_q
  // px reads z from a neighbouring texel of a coarser level, while Q keeps the tap pixel's centre).
  const float defaultBias = fullResolution().bias;
  // Per condition (facing; grazing with the z hierarchy; grazing without), over every backend.
  double worstNeeded[3] = {0, 0, 0}, minAtDefaultAll[3] = {1, 1, 1};
  std::string failing;
  std::printf("[stability] bias needed for min A >= 1 - 1/255 (cpu; '>0.5' = none in range)\n");
  for (double angle : {0.0, 89.0})
    for (bool hierarchy : {true, false}) {
      if (angle == 0.0 && !hierarchy) continue;
      std::string table;
      for (const WallSetup& ws : kWallSetups) {
        std::string row = fmt("%-20s", ws.name);
        for (double D : {1.0, 10.0, 100.0})
          for (bool scaledRadius : {false, true}) {
            const Camera cam = camera(64, 48, 0.1, kInf, ws.clip, ws.reversed, 8);
            const test::Scene wall = turnedWall(D, angle);
            const double radius = scaledRadius ? std::clamp(8.0 * D / (0.5 * 48 * std::sqrt(3.0)), 0.01, 100.0) : 1.0;
            std::map<std::string, double> needed, minAtDefault;
            for (double bias : kBiases) {
              Settings s = fullResolution();
              s.radius = float(radius);
              s.bias = float(bias);
              s.use_z_hierarchy = hierarchy;
              ParamBlock p;
              ASSERT_TRUE(computeConstants(s, cam, DepthEncoding::Hardware, p).ok());
              const SceneRun r = runScene(fmt("wall %g deg at %g m, %s, radius %.3g, bias %g%s", angle, D, ws.name, radius, bias,
                                              hierarchy ? "" : ", no hierarchy"),
                                          s, cam, wall, ws.fm);
              bool allPass = true;
              for (const BackendRun& b : r.runs.runs) {
                const double m = wallMinA(b, r, cam, p);
                if (float(bias) == defaultBias) minAtDefault[b.name] = m;
                if (m >= 1.0 - k255) {
                  if (!needed.count(b.name)) needed[b.name] = bias;
                } else {
                  allPass = false;
                }
              }
              if (allPass && float(bias) >= defaultBias) break;
            }
            const int cond = angle == 0.0 ? 0 : hierarchy ? 1 : 2;
            EXPECT_FALSE(minAtDefault.empty()) << ws.name << " D = " << D << ": no backend ran the default bias";
            for (const auto& [name, m] : minAtDefault) {
              const double need = needed.count(name) ? needed[name] : INFINITY;
              // The default bias suffices for every format and distance, facing or grazing, with
              // or without the z hierarchy (the grazing case with it is what set the default).
              EXPECT_GE(m, 1.0 - k255) << ws.name << " " << angle << " deg D = " << D << " radius " << radius
                                       << (hierarchy ? "" : " no hierarchy") << " on " << name << " (needs bias " << need << ")";
              worstNeeded[cond] = std::max(worstNeeded[cond], need);
              minAtDefaultAll[cond] = std::min(minAtDefaultAll[cond], m);
              if (m < 1.0 - k255)
                failing += fmt("%s%s %g deg%s D=%g r=%.3g on %s: min A %.4f (needs %g)", failing.empty() ? "" : "; ",
                               ws.name, angle, hierarchy ? "" : " no hierarchy", D, radius, name.c_str(), m, need);
            }
            const double need = needed.count("cpu") ? needed["cpu"] : INFINITY;
            row += fmt(" | %s (%.4f)", std::isinf(need) ? ">0.5" : fmt("%g", need).c_str(),
                       minAtDefault.count("cpu") ? minAtDefault["cpu"] : -1.0);
          }
        table += "\n[stability]   " + row;
      }
      std::printf("[stability] wall %g deg%s: format | 1 m r=1 | 1 m r'=8px | 10 m r=1 | 10 m r'=8px | 100 m r=1 | 100 m r'=8px"
                  " -- bias needed (min A at the default bias)%s\n",
                  angle, hierarchy ? "" : " without z hierarchy", table.c_str());
    }
  const char* what[3] = {"flat wall facing the camera", "wall at 89° (grazing), z hierarchy on (default)",
                         "wall at 89° (grazing), z hierarchy off"};
  for (int cond = 0; cond < 3; ++cond)
    report(fmt("%s at 1, 10, 100 m (D16/D24 std, D32F std/rev, R32F; every backend)", what[cond]),
           fmt("A >= 1-1/255 at the default bias %g", double(defaultBias)),
           fmt("largest bias needed %g; min A at the default %.4f", worstNeeded[cond], minAtDefaultAll[cond]));
  if (!failing.empty()) std::printf("[stability] walls NOT MET where %s\n", failing.c_str());
}

TEST(Walls, OrthographicFacingAndGrazingWall) {
  // The same walls seen by an orthographic camera 10 cm tall (S' = 480 px/m), radius 1/60 m
  // 0.05 m (r' = 24 px everywhere: taps at h >= 8 px read coarser z levels), near 0.1 m, far 2 D + 10 m.
  std::string measured;
  for (double angle : {0.0, 89.0})
    for (bool hierarchy : {true, false}) {
      if (angle == 0.0 && !hierarchy) continue;
      for (const WallSetup& ws : kWallSetups) {
        if (ws.fm == DepthFormat::D16) continue;
        for (double D : {1.0, 10.0, 100.0}) {
          const Camera cam = orthoCamera(64, 48, 0.1, 2 * D + 10, ws.clip, ws.reversed, 8, 0.05);
          double need = INFINITY, minDefault = 1;
          for (double bias : kBiases) {
            Settings s = fullResolution();
            s.radius = 0.05f;
            s.bias = float(bias);
            s.use_z_hierarchy = hierarchy;
            ParamBlock p;
            ASSERT_TRUE(computeConstants(s, cam, DepthEncoding::Hardware, p).ok());
            const SceneRun r = runScene(fmt("ortho wall %g deg at %g m, %s, bias %g%s", angle, D, ws.name, bias,
                                            hierarchy ? "" : ", no hierarchy"),
                                        s, cam, turnedWall(D, angle), ws.fm);
            double m = 1;
            for (const BackendRun& b : r.runs.runs) m = std::min(m, wallMinA(b, r, cam, p));
            if (s.bias == fullResolution().bias) minDefault = m;
            if (m >= 1.0 - k255 && std::isinf(need)) need = bias;
            if (!std::isinf(need) && s.bias >= fullResolution().bias) break;
          }
          if (angle == 0.0 || !hierarchy) {
            EXPECT_GE(minDefault, 1.0 - k255) << ws.name << " " << angle << " deg D = " << D;
          } else {
            EXPECT_LE(need, 0.02) << ws.name << " D = " << D;
          }
          measured += fmt("%s%g deg%s %s %g m: needs %g (min A %.4f)", measured.empty() ? "" : "; ", angle,
                          hierarchy ? "" : " no-hier", ws.name, D, need, minDefault);
        }
      }
    }
  report("orthographic walls facing / at 89° at 1, 10, 100 m (r' = 24 px; D24 std, D32F std/rev, R32F)",
         "facing, and grazing without the z hierarchy: A >= 1-1/255 at the default bias; grazing with it: bias <= 0.02",
         measured);
}

}  // namespace
}  // namespace sao::stability
