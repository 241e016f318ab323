// A depth discontinuity (a card over a wall): no dark or white one-pixel line after the blur.
#include <algorithm>
#include <cmath>
#include <string>

#include "extremes_support.h"

namespace sao::stability {
namespace {

TEST(Discontinuity, NoOnePixelLineAfterTheBlur) {
  // A camera-facing card (|x|, |y| <= 0.5 m) at 2 m over a wall at 2.5 m (within the radius: the
  // card really darkens the wall around it) and at 10 m (beyond it: A must stay 1 everywhere).
  double minFar = 1, worstCardAll = 1, worstLineAll = -1;
  for (double wallD : {10.0, 2.5})
    for (bool ortho : {false, true})
      for (const WallSetup& ws : {kWallSetups[1], kWallSetups[3]}) {
        const Camera cam = ortho ? orthoCamera(64, 48, 0.1, 100.0, ws.clip, ws.reversed, 8, 1.0)
                                 : camera(64, 48, 0.1, kInf, ws.clip, ws.reversed, 8);
        const test::Scene scene = cardOverWall(2.0, wallD, 0.5);
        const SceneRun r = runScene(fmt("card at 2 m over wall at %g m, %s", wallD, describe(cam).c_str()), fullResolution(), cam,
                                    scene, ws.fm);
        const int W = int(cam.width), H = int(cam.height);
        for (const BackendRun& b : r.runs.runs) {
          const FloatImage& ao = b.out.ao;
          auto A = [&](int x, int y) { return double(ao.at(std::uint32_t(x), std::uint32_t(y))); };
          auto onCard = [&](int x, int y) { return r.z[std::size_t(y) * W + x] > -2.2; };
          if (wallD == 10.0) {
            EXPECT_GE(range(ao).min, 1.0 - k255) << b.name << " " << describe(cam);
            continue;
          }
          // Card pixels (including the edge row/column) are lit: nothing is in front of them.
          double worstCard = 1, worstLine = 0;
          for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
              if (onCard(x, y)) worstCard = std::min(worstCard, A(x, y));
          // The wall next to the card's edges: a one-pixel line is a first step (edge pixel to its
          // wall neighbour) out of line with the steps further out. The 2x2 reconstruction makes
          // pairs of equal values, so the comparison is with the largest of the next five steps.
          auto excess = [&](int e, int dx, int dy) {  // e: first wall pixel, (dx, dy): away from the card
            auto at = [&](int k) { return A(e % W + k * dx, e / W + k * dy); };
            double further = 0;
            for (int k = 1; k <= 5; ++k) further = std::max(further, std::fabs(at(k) - at(k + 1)));
            return std::fabs(at(0) - at(1)) - 2.0 * further;
          };
          for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
              if (onCard(x, y)) continue;
              if (x + 7 < W && x >= 1 && onCard(x - 1, y)) worstLine = std::max(worstLine, excess(y * W + x, 1, 0));
              if (x >= 7 && x + 1 < W && onCard(x + 1, y)) worstLine = std::max(worstLine, excess(y * W + x, -1, 0));
              if (y + 7 < H && y >= 1 && onCard(x, y - 1)) worstLine = std::max(worstLine, excess(y * W + x, 0, 1));
              if (y >= 7 && y + 1 < H && onCard(x, y + 1)) worstLine = std::max(worstLine, excess(y * W + x, 0, -1));
            }
          EXPECT_LE(worstLine, k255) << b.name << " " << describe(cam) << ": a one-pixel line along the card's edge";
          worstLineAll = std::max(worstLineAll, worstLine);
          EXPECT_GE(worstCard, 1.0 - k255) << b.name << " " << describe(cam);
          worstCardAll = std::min(worstCardAll, worstCard);
        }
        if (wallD == 10.0)
          for (const BackendRun& b : r.runs.runs) minFar = std::min(minFar, range(b.out.ao).min);
      }
  report("depth discontinuity: camera-facing card at 2 m over a wall at 10 m (beyond the radius) and 2.5 m (within), "
         "persp + ortho, D24 standard / D32F reversed",
         "wall at 10 m: A >= 1-1/255 everywhere; wall at 2.5 m: card A >= 1-1/255 up to its edge, first wall step "
         "<= 2x the next steps + 1/255 (no dark or white one-pixel line)",
         fmt("10 m: min A %.4f; 2.5 m: min A on the card %.4f, worst first-step excess %.4f", minFar, worstCardAll, worstLineAll));
}

}  // namespace
}  // namespace sao::stability
