// Temporal accumulation on the CPU reference (the `temporal` setting, sao_temporal.glsl): the
// first frame is the frame without history bit for bit; a static camera's frames accumulate
// towards the converged result like more taps in one frame (the [temporal] static target: 16
// frames at or below one frame with 4x the taps); a camera moving past a thin panel in front of a
// wall restarts the history where the wall was hidden (no ghost) and keeps it where it was not.
// The history is carried from run to run by the caller (cpu::Inputs::history, previousCamera).
#include <cmath>
#include <cstdio>
#include <vector>

#include "cpu_frames.h"
#include "moving_camera.h"
#include "test_support.h"

namespace sao::test {
namespace {

using cpu::Precision;

Settings withTaps(int samples, bool temporal) {
  Settings s;
  s.samples = samples;
  s.quad_edge_threshold = 0.0f;  // no 2x2 averaging
  s.blur_radius = 0;             // no blur
  s.resolution_divisor = 1;
  s.temporal = temporal;
  s.temporal_hysteresis = 0.95f;  // a running mean for the first 20 frames
  return s;
}

double rmse(const FloatImage& a, const FloatImage& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i) sum += (double(a.data[i]) - b.data[i]) * (double(a.data[i]) - b.data[i]);
  return std::sqrt(sum / double(a.data.size()));
}

// One frame of a path through CpuFrames: the depth and frame index.
cpu::Result frameOf(CpuFrames& frames, const Camera& camera, const DepthImage& depth, std::uint32_t frame) {
  cpu::Inputs in;
  in.depth = &depth;
  in.frameIndex = frame;
  return frames.run(camera, in);
}

TEST(Temporal, FirstFrameIsTheFrameWithoutHistory) {
  const Camera cam = movedCamera(testCamera(4, 1000.0, ClipDepth::NegativeOneToOne, false, 96, 64), {});
  const DepthImage depth = renderDepth(sphereOnPlaneScene(), cam, DepthFormat::D32F);
  cpu::Inputs in;
  in.depth = &depth;
  in.frameIndex = 3;
  for (int divisor : {1, 2}) {
    Settings off = withTaps(8, false), on = withTaps(8, true);
    off.resolution_divisor = on.resolution_divisor = divisor;
    const cpu::Result a = runOrFail(off, cam, in, Precision::Float);
    const cpu::Result b = runOrFail(on, cam, in, Precision::Float);
    ASSERT_EQ(a.ao.data.size(), b.ao.data.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.ao.data.size(); ++i) differ += a.ao.data[i] != b.ao.data[i];
    EXPECT_EQ(differ, 0u) << "divisor " << divisor;
    EXPECT_EQ(b.params.history_valid, 0);
    // The history holds one frame on geometry, none on sky.
    const FloatImage& h = b.images[std::size_t(gen::ResourceId::history)].at(0);
    EXPECT_EQ(h.extent, b.aoRaw.extent);
    for (std::uint32_t y = 0; y < h.extent.height; ++y)
      for (std::uint32_t x = 0; x < h.extent.width; ++x)
        EXPECT_EQ(h.at(x, y, 2), b.aoRaw.at(x, y, 1) < 0.0f ? 1.0f : 0.0f) << x << "," << y;
  }
}

TEST(Temporal, StaticCameraReachesFourTimesTheTapsInSixteenFrames) {
  const Camera cam = movedCamera(testCamera(4, 1000.0, ClipDepth::NegativeOneToOne, false, 96, 64), {});
  const DepthImage depth = renderDepth(sphereOnPlaneScene(), cam, DepthFormat::D32F);
  cpu::Inputs in;
  in.depth = &depth;
  const FloatImage converged = runOrFail(withTaps(64, false), cam, in, Precision::Float).ao;
  CpuFrames frames(withTaps(4, true));
  FloatImage last;
  for (std::uint32_t frame = 0; frame < 16; ++frame) last = frameOf(frames, cam, depth, frame).ao;
  const double single4 = rmse(runOrFail(withTaps(4, false), cam, in, Precision::Float).ao, converged);
  const double single16 = rmse(runOrFail(withTaps(16, false), cam, in, Precision::Float).ao, converged);
  const double accumulated = rmse(last, converged);
  std::printf("TEMPORAL static RMSE vs 64 taps: 1 frame x 4 taps %.4f, 1 frame x 16 taps %.4f, "
              "16 accumulated frames x 4 taps %.4f\n", single4, single16, accumulated);
  EXPECT_LE(accumulated, single16) << "16 frames of s taps should reach one frame of 4s taps";
  // Every geometry texel of the history holds the 16 frames (no rejection on a still camera).
  const FloatImage& h = frames.history();
  std::size_t geometry = 0, full = 0;
  for (std::uint32_t y = 0; y < h.extent.height; ++y)
    for (std::uint32_t x = 0; x < h.extent.width; ++x)
      if (h.at(x, y, 1) < 0.0f) {
        ++geometry;
        full += h.at(x, y, 2) == 16.0f;
      }
  EXPECT_GT(geometry, 0u);
  EXPECT_EQ(full, geometry);
}

// A thin panel (0.4 m wide, 1 m tall, 5 cm deep, at z = -3) before a wall at z = -4, the camera
// strafing along +x by 0.4 m a frame (the panel moves ~2 px against the wall a frame at 128x72):
// every wall texel whose whole bilinear footprint in the previous frame lay on the panel must start
// again (frames = 1: no ghost of the panel), and every wall texel whose footprint lay on the wall
// keeps its history (frames > 1). The footprint is found in double from the analytic scene.
TEST(Temporal, StrafePastAPanelRestartsOnlyDisoccludedPixels) {
  Scene world;
  world.planes.push_back({{0, 0, -4}, {0, 0, 1}, {}});
  world.boxes.push_back({{-0.2, -0.5, -3.05}, {0.2, 0.5, -2.95}});
  const Camera base = testCamera(4, 1000.0, ClipDepth::NegativeOneToOne, false, 128, 72);
  CpuFrames frames(withTaps(8, true));
  std::size_t disoccluded = 0, restarted = 0, steady = 0, kept = 0;
  constexpr double kStep = 0.4;
  for (std::uint32_t frame = 0; frame < 6; ++frame) {
    const Vec3 eye{kStep * frame - 1.0, 0, 0};
    const Camera cam = movedCamera(base, eye);
    const DepthImage depth = renderDepth(seenFrom(world, eye), cam, DepthFormat::D32F);
    const cpu::Result r = frameOf(frames, cam, depth, frame);
    if (frame == 0) continue;
    const Scene before = seenFrom(world, {eye.x - kStep, 0, 0});
    const FloatImage& h = frames.history();
    const auto& pi = r.params.proj_info;  // the same projection in both frames
    const double g = cam.guardBand;
    // What the previous camera saw at viewport texel (tx, ty): its surface's z.
    auto seenZ = [&](int tx, int ty) {
      const double dx = -((tx + g + 0.5) * pi.x + pi.z), dy = -((ty + g + 0.5) * pi.y + pi.w);
      const double len = std::sqrt(dx * dx + dy * dy + 1.0);
      const auto hits = before.trace({0, 0, 0}, {dx / len, dy / len, -1.0 / len});
      return hits.empty() ? 0.0 : hits.front().point.z;
    };
    for (std::uint32_t y = 0; y < h.extent.height; ++y)
      for (std::uint32_t x = 0; x < h.extent.width; ++x) {
        const double z = h.at(x, y, 1);
        if (!(z < -3.5)) continue;  // wall texels only
        const double cx = x + g + 0.5, cy = y + g + 0.5;
        const double px = z * (cx * pi.x + pi.z) + kStep, py = z * (cy * pi.y + pi.w);  // in the previous camera
        const double ux = (px / z - pi.z) / pi.x - 0.5 - g, uy = (py / z - pi.w) / pi.y - 0.5 - g;
        const int x0 = int(std::floor(ux)), y0 = int(std::floor(uy));
        int panel = 0, wall = 0;
        for (int k = 0; k < 4; ++k) {
          const double sz = seenZ(x0 + (k & 1), y0 + (k >> 1));
          panel += sz > -3.5 && sz < 0.0;
          wall += sz < -3.5;
        }
        if (panel == 4) {
          ++disoccluded;
          restarted += h.at(x, y, 2) == 1.0f;
        } else if (wall == 4 && x0 >= 0 && y0 >= 0 && x0 + 1 < int(h.extent.width) && y0 + 1 < int(h.extent.height)) {
          ++steady;
          kept += h.at(x, y, 2) > 1.0f;
        }
      }
  }
  std::printf("TEMPORAL strafe past a panel: %zu wall texels hidden in the previous frame, %zu restarted; %zu wall "
              "texels seen in both, %zu kept their history\n", disoccluded, restarted, steady, kept);
  ASSERT_GT(disoccluded, 20u) << "the path reveals no wall: the test checks nothing";
  EXPECT_EQ(restarted, disoccluded) << "a texel hidden by the panel kept history: a ghost";
  EXPECT_EQ(kept, steady) << "a texel seen in both frames lost its history";
}

// A box (0.6 m wide, front face at z = -2.95) moving 0.1 m a frame along +x before a wall at z = -4,
// the camera still, with motion vectors (MOTION_VECTORS): the box's texels whose previous position
// (texel + motion) had the box under its whole bilinear footprint keep their history; the wall
// texels the box covered in the previous frame start again (the box's depth there is rejected).
TEST(Temporal, MotionVectorsFollowAMovingBoxAndTheWallItUncoversStartsAgain) {
  const Camera cam = movedCamera(testCamera(4, 1000.0, ClipDepth::NegativeOneToOne, false, 128, 72), {});
  const gen::Float4 pi = projInfo(cam);
  const double g = cam.guardBand;
  const Extent input{cam.width + 2 * cam.guardBand, cam.height + 2 * cam.guardBand};
  auto sceneAt = [](std::uint32_t frame) {
    Scene s;
    s.planes.push_back({{0, 0, -4}, {0, 0, 1}, {}});
    const double x = 0.1 * frame - 0.3;
    s.boxes.push_back({{x - 0.3, -0.5, -3.05}, {x + 0.3, 0.5, -2.95}});
    return s;
  };
  // The camera-space point of csz texel (tx, ty) and what it hits.
  auto hitAt = [&](const Scene& s, double tx, double ty) {
    const double dx = -((tx + 0.5) * pi.x + pi.z), dy = -((ty + 0.5) * pi.y + pi.w);
    const double len = std::sqrt(dx * dx + dy * dy + 1.0);
    const auto hits = s.trace({0, 0, 0}, {dx / len, dy / len, -1.0 / len});
    return hits.empty() ? Vec3{0, 0, 0} : hits.front().point;
  };
  Settings settings = withTaps(8, true);
  struct Counts {
    std::size_t boxTexels = 0, boxKept = 0, uncovered = 0, uncoveredRestarted = 0;
  };
  auto runSequence = [&](bool useMotion) {
    Counts n;
    CpuFrames frames(settings);
    for (std::uint32_t frame = 0; frame < 5; ++frame) {
      const Scene now = sceneAt(frame);
      const DepthImage depth = renderDepth(now, cam, DepthFormat::D32F);
      // Motion: a box point was 0.1 m to the left a frame ago; the wall does not move.
      FloatImage motion(input, 2);
      for (std::uint32_t y = 0; y < input.height; ++y)
        for (std::uint32_t x = 0; x < input.width; ++x) {
          const Vec3 p = hitAt(now, x, y);
          if (!(p.z > -3.5 && p.z < 0)) continue;
          const double px = ((p.x - 0.1) / p.z - pi.z) / pi.x - 0.5;  // the texel coordinate it had
          motion.at(x, y, 0) = float(px - x);
        }
      cpu::Inputs in;
      in.depth = &depth;
      in.frameIndex = frame;
      if (useMotion) in.motion = &motion;
      frames.run(cam, in);
      if (frame == 0) continue;
      const FloatImage& history = frames.history();
      const Scene before = sceneAt(frame - 1);
      for (std::uint32_t y = 0; y < history.extent.height; ++y)
        for (std::uint32_t x = 0; x < history.extent.width; ++x) {
          const double z = history.at(x, y, 1);
          const double cx = x + g, cy = y + g;
          const double mx = motion.at(std::uint32_t(cx), std::uint32_t(cy), 0);
          const double ux = cx + mx - g, uy = cy - g;  // the previous position, viewport texels
          const int x0 = int(std::floor(ux)), y0 = int(std::floor(uy));
          int boxBefore = 0;
          for (int k = 0; k < 4; ++k) {
            const Vec3 p = hitAt(before, x0 + (k & 1) + g, y0 + (k >> 1) + g);
            boxBefore += p.z > -3.5 && p.z < 0;
          }
          if (z > -3.5 && z < 0 && boxBefore == 4) {
            ++n.boxTexels;
            n.boxKept += history.at(x, y, 2) > 1.0f;
          }
          const Vec3 was = hitAt(before, cx, cy);
          if (z < -3.5 && was.z > -3.5 && was.z < 0 && mx == 0.0) {
            // Wall now, box before, at this texel and (motion 0) its whole footprint's centre texel.
            const Vec3 l = hitAt(before, cx - 1, cy), rr = hitAt(before, cx + 1, cy);
            if (l.z > -3.5 && rr.z > -3.5) {
              ++n.uncovered;
              n.uncoveredRestarted += history.at(x, y, 2) == 1.0f;
            }
          }
        }
    }
    return n;
  };
  const Counts with = runSequence(true), without = runSequence(false);
  std::printf("TEMPORAL moving box with motion vectors: %zu box texels, %zu kept their history (%zu without motion "
              "vectors); %zu uncovered wall texels, %zu restarted\n",
              with.boxTexels, with.boxKept, without.boxKept, with.uncovered, with.uncoveredRestarted);
  ASSERT_GT(with.boxTexels, 100u);
  ASSERT_GT(with.uncovered, 20u);
  EXPECT_EQ(with.boxKept, with.boxTexels) << "the moving box lost its history: the motion vectors were not followed";
  EXPECT_LT(without.boxKept, with.boxKept) << "without motion vectors the box's leading edge should start again";
  EXPECT_EQ(with.uncoveredRestarted, with.uncovered) << "wall texels the box covered kept the box's history: a ghost";
  // Without the temporal setting a motion input is refused by name.
  cpu::Inputs plain;
  const DepthImage depth = renderDepth(sceneAt(0), cam, DepthFormat::D32F);
  FloatImage zero(input, 2);
  plain.depth = &depth;
  plain.motion = &zero;
  cpu::Result refused;
  const Status st = cpu::run(withTaps(8, false), cam, plain, {Precision::Float, 2}, refused);
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("motion vectors serve temporal accumulation only"), std::string::npos) << st.message;
}

// The normal test (with supplied normals): a still camera's second frame keeps every geometry
// texel's history (frames 2); the same history with every texel's normal turned by 90 degrees (the
// packed .w of the history replaced) gives none of it (frames 1): same depth, another surface
// orientation. Without supplied normals the rebuilt ones are not tested: the same turned history
// is kept.
TEST(Temporal, HistoryOfAnotherNormalIsRejectedWithSuppliedNormals) {
  const Camera cam = movedCamera(testCamera(4, 1000.0, ClipDepth::NegativeOneToOne, false, 96, 64), {});
  const DepthImage depth = renderDepth(sphereOnPlaneScene(), cam, DepthFormat::D32F);
  const FloatImage normals = renderNormals(sphereOnPlaneScene(), cam);
  const Settings settings = withTaps(8, true);
  cpu::Inputs in;
  in.depth = &depth;
  in.normals = &normals;
  const cpu::Result first = runOrFail(settings, cam, in, Precision::Float);
  FloatImage history = first.images[std::size_t(gen::ResourceId::history)].at(0);
  in.history = &history;
  in.previousCamera = &cam;
  in.frameIndex = 1;
  auto counts = [&](const cpu::Result& r, float frames) {
    const FloatImage& h = r.images[std::size_t(gen::ResourceId::history)].at(0);
    std::size_t geometry = 0, match = 0;
    for (std::uint32_t y = 0; y < h.extent.height; ++y)
      for (std::uint32_t x = 0; x < h.extent.width; ++x)
        if (h.at(x, y, 1) < 0.0f) {
          ++geometry;
          match += h.at(x, y, 2) == frames;
        }
    return std::pair{geometry, match};
  };
  const auto [geometry, kept] = counts(runOrFail(settings, cam, in, Precision::Float), 2.0f);
  EXPECT_GT(geometry, 1000u);
  EXPECT_EQ(kept, geometry) << "a still camera keeps every texel's history";
  // Every stored normal turned by 90 degrees, packed as the shader packs it (octahedral, 12 bits a
  // component).
  for (std::uint32_t y = 0; y < history.extent.height; ++y)
    for (std::uint32_t x = 0; x < history.extent.width; ++x) {
      float& code = history.at(x, y, 3);
      const float qx = std::floor(code / 4096.0f), qy = code - qx * 4096.0f;
      const double ex = qx / 4095.0 * 2 - 1, ey = qy / 4095.0 * 2 - 1;
      double nx = ex, ny = ey, nz = 1 - std::abs(ex) - std::abs(ey);
      if (nz < 0) {
        nx = (1 - std::abs(ey)) * (ex >= 0 ? 1 : -1);
        ny = (1 - std::abs(ex)) * (ey >= 0 ? 1 : -1);
      }
      // Turned 90 degrees: a vector perpendicular to it (its cross product with an axis it is not near).
      const bool nearZ = std::abs(nz) > 0.9 * std::sqrt(nx * nx + ny * ny + nz * nz);
      const double ax = nearZ ? 1 : 0, az = nearZ ? 0 : 1;
      const double rx = ny * az, ry = nz * ax - nx * az, rz = -ny * ax;
      const double l1 = std::abs(rx) + std::abs(ry) + std::abs(rz);
      double px = rx / l1, py = ry / l1;
      if (rz < 0) {
        const double fx = (1 - std::abs(py)) * (px >= 0 ? 1 : -1), fy = (1 - std::abs(px)) * (py >= 0 ? 1 : -1);
        px = fx;
        py = fy;
      }
      code = float(std::floor((px * 0.5 + 0.5) * 4095 + 0.5) * 4096 + std::floor((py * 0.5 + 0.5) * 4095 + 0.5));
    }
  const auto [geometry2, restarted] = counts(runOrFail(settings, cam, in, Precision::Float), 1.0f);
  std::printf("TEMPORAL normal test: %zu of %zu texels keep their history; with the history's normals turned 90 "
              "degrees %zu restart\n", kept, geometry, restarted);
  EXPECT_EQ(restarted, geometry2) << "a history texel of another orientation was accepted";
  in.normals = nullptr;
  const auto [geometry3, keptRebuilt] = counts(runOrFail(settings, cam, in, Precision::Float), 2.0f);
  EXPECT_EQ(keptRebuilt, geometry3) << "rebuilt normals are not tested";
}

TEST(Temporal, HistoryWithoutItsCameraOrOfAnotherSizeIsRefused) {
  const Camera cam = movedCamera(testCamera(4, 1000.0, ClipDepth::NegativeOneToOne, false, 96, 64), {});
  const DepthImage depth = renderDepth(sphereOnPlaneScene(), cam, DepthFormat::D32F);
  cpu::Inputs in;
  in.depth = &depth;
  const FloatImage wrong(Extent{10, 10}, 4);
  in.history = &wrong;
  cpu::Result r;
  Status st = cpu::run(withTaps(8, true), cam, in, {Precision::Float, 2}, r);
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("previousCamera"), std::string::npos) << st.message;
  in.previousCamera = &cam;
  st = cpu::run(withTaps(8, true), cam, in, {Precision::Float, 2}, r);
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("10x10"), std::string::npos) << st.message;
  // Temporal without Camera::view: refused by name.
  Camera noView = cam;
  noView.view.reset();
  cpu::Inputs plain;
  plain.depth = &depth;
  st = cpu::run(withTaps(8, true), noView, plain, {Precision::Float, 2}, r);
  EXPECT_EQ(st.code, StatusCode::InvalidCamera);
  EXPECT_NE(st.message.find("Camera::view"), std::string::npos) << st.message;
  // A view that is not rigid.
  Camera scaled = cam;
  (*scaled.view)[0] = 2.0;
  st = cpu::run(withTaps(8, true), scaled, plain, {Precision::Float, 2}, r);
  EXPECT_EQ(st.code, StatusCode::InvalidCamera);
  EXPECT_NE(st.message.find("Camera::view"), std::string::npos) << st.message;
}

}  // namespace
}  // namespace sao::test
