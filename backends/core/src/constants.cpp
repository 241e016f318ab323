#include "sao/constants.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "sao/spiral.h"

namespace sao {
namespace {

double at(const Camera& c, int row, int col) { return c.projection[col * 4 + row]; }

// S' of eq. 5: pixels spanned by one view unit at distance 1 (perspective) or anywhere (ortho).
double projScale(const Camera& c) { return 0.5 * c.height * std::fabs(at(c, 1, 1)); }

float f(double v) { return static_cast<float>(v); }

static_assert(int(NormalsEncoding::CameraXyz) == gen::SAO_NORMALS_CAMERA_XYZ &&
              int(NormalsEncoding::WorldXyz) == gen::SAO_NORMALS_WORLD_XYZ &&
              int(NormalsEncoding::CameraOctahedral) == gen::SAO_NORMALS_CAMERA_OCTAHEDRAL &&
              int(NormalsEncoding::WorldOctahedral) == gen::SAO_NORMALS_WORLD_OCTAHEDRAL,
              "NormalsEncoding is the block's normals_encoding");
static_assert(int(DepthSamplePolicy::Sample0) == gen::SAO_DEPTH_SAMPLE_0 &&
                  int(DepthSamplePolicy::Nearest) == gen::SAO_DEPTH_SAMPLE_NEAREST,
              "DepthSamplePolicy is the block's depth_sample_policy");

// Eq. 3 in csz texel coordinates (guard folded into b): proj_info of the block.
gen::Float4 projInfoOf(const Camera& c) {
  const bool ortho = c.kind == ProjectionKind::Orthographic;
  const double W = c.width, H = c.height, g = c.guardBand;
  const double sy = c.flipY ? -1.0 : 1.0;
  double ax, ay, bx, by;

  if (!ortho) {
    ax = -2.0 / (W * at(c, 0, 0));
    ay = -2.0 * sy / (H * at(c, 1, 1));
    bx = (1.0 - at(c, 0, 2)) / at(c, 0, 0) - g * ax;
    by = (sy - at(c, 1, 2)) / at(c, 1, 1) - g * ay;
  } else {
    ax = 2.0 / (W * at(c, 0, 0));
    ay = 2.0 * sy / (H * at(c, 1, 1));
    bx = -(1.0 + at(c, 0, 3)) / at(c, 0, 0) - g * ax;
    by = -(sy + at(c, 1, 3)) / at(c, 1, 1) - g * ay;
  }
  return {f(ax), f(ay), f(bx), f(by)};
}

// 1e-4: far looser than a float-stored rotation's rounding (~1e-7), far tighter than a scaled or
// sheared matrix.
constexpr double kRotationTolerance = 1e-4;

// A rotation, column-major 3x3: finite, orthonormal columns to kRotationTolerance, determinant +1.
Status checkRotation(const std::array<double, 9>& r, const char* name) {
  auto bad = [](const std::string& what) { return Status::error(StatusCode::InvalidCamera, what); };
  for (double v : r)
    if (!std::isfinite(v)) return bad(std::string(name) + " has a non-finite element");
  auto col = [&](int i, int k) { return r[std::size_t(i * 3 + k)]; };
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      const double d = col(i, 0) * col(j, 0) + col(i, 1) * col(j, 1) + col(i, 2) * col(j, 2);
      const double want = i == j ? 1.0 : 0.0;
      if (std::fabs(d - want) > kRotationTolerance) {
        char text[200];
        if (i == j)
          std::snprintf(text, sizeof text, "column %d has length %.9g", i, std::sqrt(d));
        else
          std::snprintf(text, sizeof text, "columns %d and %d have the dot product %.9g", i, j, d);
        return bad(std::string(name) + " is not a rotation: " + text +
                   " (the columns must be orthonormal to 1e-4)");
      }
    }
  const double det = col(0, 0) * (col(1, 1) * col(2, 2) - col(2, 1) * col(1, 2)) -
                     col(1, 0) * (col(0, 1) * col(2, 2) - col(2, 1) * col(0, 2)) +
                     col(2, 0) * (col(0, 1) * col(1, 2) - col(1, 1) * col(0, 2));
  if (det < 0) return bad(std::string(name) + " is a reflection (determinant -1), not a rotation");
  return Status::success();
}

// The normals encoding and the view rotation: a world-space encoding needs a rotation, and a
// rotation that is set must be one (a scale or shear would bend every normal, a mirror would turn
// the normals away from the viewer).
Status checkNormalsEncoding(const Camera& c) {
  auto bad = [](const std::string& what) { return Status::error(StatusCode::InvalidCamera, what); };
  const int e = int(c.normalsEncoding);
  if (e < gen::SAO_NORMALS_CAMERA_XYZ || e > gen::SAO_NORMALS_WORLD_OCTAHEDRAL)
    return bad("Camera::normalsEncoding = " + std::to_string(e) + " is not a NormalsEncoding");
  const bool world = c.normalsEncoding == NormalsEncoding::WorldXyz || c.normalsEncoding == NormalsEncoding::WorldOctahedral;
  if (world && !c.viewRotation)
    return bad(std::string("Camera::normalsEncoding = ") +
               (c.normalsEncoding == NormalsEncoding::WorldXyz ? "WorldXyz" : "WorldOctahedral") +
               " (world-space normals) needs Camera::viewRotation, the world -> camera rotation; none is set");
  if (const int d = int(c.depthSamplePolicy); d != gen::SAO_DEPTH_SAMPLE_0 && d != gen::SAO_DEPTH_SAMPLE_NEAREST)
    return bad("Camera::depthSamplePolicy = " + std::to_string(d) + " is not a DepthSamplePolicy");
  if (!c.viewRotation) return Status::success();
  return checkRotation(*c.viewRotation, "Camera::viewRotation");
}

// Camera::view: finite, a rotation (checkRotation) and a translation, last row 0 0 0 1; its rotation
// the same as viewRotation's when both are set; required with temporal accumulation.
Status checkView(const Camera& c, const Settings& s) {
  auto bad = [](const std::string& what) { return Status::error(StatusCode::InvalidCamera, what); };
  if (!c.view) {
    if (s.temporal)
      return bad("the temporal setting needs Camera::view (the world -> camera matrix) on every frame's camera, to "
                 "find each pixel's surface in the previous frame; none is set (a camera that never moves: the identity)");
    return Status::success();
  }
  const auto& v = *c.view;
  for (double x : v)
    if (!std::isfinite(x)) return bad("Camera::view has a non-finite element");
  if (v[3] != 0.0 || v[7] != 0.0 || v[11] != 0.0 || v[15] != 1.0)
    return bad("Camera::view's last row is not 0 0 0 1: it must be a rigid world -> camera transform");
  const std::array<double, 9> r{v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10]};
  if (Status st = checkRotation(r, "Camera::view's upper 3x3"); !st) return st;
  if (c.viewRotation)
    for (std::size_t k = 0; k < 9; ++k)
      if (std::fabs(r[k] - (*c.viewRotation)[k]) > kRotationTolerance)
        return bad("Camera::viewRotation differs from Camera::view's rotation (element " + std::to_string(k) +
                   "): they describe one camera");
  return Status::success();
}

const char* encodingName(NormalsEncoding e) {
  switch (e) {
    case NormalsEncoding::CameraXyz: return "CameraXyz";
    case NormalsEncoding::WorldXyz: return "WorldXyz";
    case NormalsEncoding::CameraOctahedral: return "CameraOctahedral";
    case NormalsEncoding::WorldOctahedral: return "WorldOctahedral";
  }
  return nullptr;
}

}  // namespace

std::uint32_t normalsChannelsRead(NormalsEncoding encoding) {
  switch (encoding) {
    case NormalsEncoding::CameraXyz:
    case NormalsEncoding::WorldXyz: return 3;
    case NormalsEncoding::CameraOctahedral:
    case NormalsEncoding::WorldOctahedral: return 2;
  }
  return 0;  // computeConstants names a value outside the enum
}

Status checkNormalsChannels(NormalsEncoding encoding, std::uint32_t channels, const std::string& format,
                            const char* noun) {
  if (channels >= normalsChannelsRead(encoding)) return Status::success();
  const char* name = encodingName(encoding);
  const bool xyz = normalsChannelsRead(encoding) == 3;
  const char* count = channels == 0 ? "no channels" : channels == 1 ? "one channel" : "two channels";
  const std::string advice =
      xyz ? (channels == 2 ? std::string("use an octahedral encoding or a three- or four-channel ") + noun
                           : std::string("use a three- or four-channel ") + noun +
                                 " (or an octahedral encoding with a two-channel one)")
          : std::string("use a two-, three- or four-channel ") + noun;
  return Status::error(StatusCode::UnsupportedFormat, format + " (" + count + ") but Camera::normalsEncoding is " +
                                                          name + ", which reads " + (xyz ? ".xyz" : ".xy") + ": " +
                                                          advice);
}

std::uint32_t mipLevelsNeeded(const Settings& s, const Camera& c, const DepthModel& m) {
  if (!s.use_z_hierarchy) return 1;
  const double r = s.radius * c.metersToViewUnits;
  double rMax = r * projScale(c);
  if (c.kind == ProjectionKind::Perspective) rMax /= m.nearDistance;
  rMax = std::min(rMax, double(gen::SAO_MAX_RADIUS_PX));
  if (!(rMax >= 1.0)) return 1;
  const int msb = static_cast<int>(std::floor(std::log2(rMax)));
  // In 64 bits: a camera that plan() would reject must not wrap around to 0 here (log2(0) = -inf).
  const std::uint64_t size0 = std::uint64_t(std::max(c.width, c.height)) + 2ull * c.guardBand;
  const int chain = size0 == 0 ? 0 : static_cast<int>(std::floor(std::log2(double(size0))));
  const int top = std::min(gen::SAO_MAX_MIP_LEVELS - 1, chain);
  return 1 + static_cast<std::uint32_t>(std::clamp<std::int64_t>(std::int64_t(msb) - s.mip_switch_log2, 0, top));
}

Status computeConstants(const Settings& s, const Camera& c, DepthEncoding encoding, ParamBlock& p) {
  if (Status st = validate(s); !st) return st;
  DepthModel m;
  if (Status st = analyze(c, m); !st) return st;
  if (Status st = checkNormalsEncoding(c); !st) return st;
  if (Status st = checkView(c, s); !st) return st;
  p = ParamBlock{};
  const bool ortho = c.kind == ProjectionKind::Orthographic;
  const double u = c.metersToViewUnits;
  p.proj_info = projInfoOf(c);

  // eq. 2 and the far/clear test.
  if (encoding == DepthEncoding::LinearZ) {
    p.clip_info = {0.0f, 1.0f, 0.0f, 0.0f};
    p.depth_mode = gen::SAO_DEPTH_MODE_LINEAR;
    p.far_dir = 0.0f;
    p.far_lim = 1.0f;
  } else {
    p.clip_info = {f(m.c0), f(m.c1), f(m.c2), 0.0f};
    p.depth_mode = ortho ? gen::SAO_DEPTH_MODE_ORTHOGRAPHIC : gen::SAO_DEPTH_MODE_PERSPECTIVE;
    p.far_dir = c.reversedZ ? -1.0f : 1.0f;
    p.far_lim = c.reversedZ ? 0.0f : 1.0f;
  }
  p.ortho = ortho ? 1 : 0;

  const double r = s.radius * u;
  p.radius = f(r);
  p.radius2 = f(r * r);
  p.bias = s.bias;
  // Eq. 1's term max(0, v.n + z beta) / (v.v + eps) has the unit 1/length: sigma multiplies the sum
  // by the view-space radius r, so sigma is unitless and A is the same in any unit system and for a
  // scene scaled together with its radius (at r = 1 m it is the paper's sigma in metres).
  p.intensity_div_s = f(2.0 * s.intensity * r / s.samples);
  if (s.estimator == 1) {
    // The visibility estimator's "sum" is the occlusion 1 - V in [0, 1]: A = max(0, 1 - sigma (1 - V))^k.
    // Its thickness model and slices are uploaded only for it (the inert rules say so).
    p.intensity_div_s = s.intensity;
    p.thickness = f(double(s.thickness) * u);
    p.depth_tolerance = s.depth_tolerance;
    p.slices = s.slices;
    p.slice_turn = static_cast<std::uint32_t>(std::llround(2147483648.0 / s.slices));  // half a turn over slices
    p.thickness_min = s.thickness_model == 1 ? f(double(gen::SAO_WIDTH_MIN_M) * u) : 0.0f;
  }
  p.epsilon = f(double(s.epsilon) * u * u);
  p.contrast = s.contrast;
  p.proj_scale = f(projScale(c));
  p.inv_samples = f(1.0 / s.samples);
  p.samples = s.samples;
  p.spiral_turns = s.spiral_turns > 0 ? s.spiral_turns : spiralTurns(s.samples);  // 0: the built-in choice
  p.tap_turn0 = spiralTapTurn(0, p.samples, p.spiral_turns);
  const double step = 2.0 * std::numbers::pi * double(p.spiral_turns) / double(p.samples);  // tau/s turns
  p.tap_step = {f(std::cos(step)), f(std::sin(step))};
  p.log_q = s.mip_switch_log2;
  p.max_mip = static_cast<std::int32_t>(mipLevelsNeeded(s, c, m)) - 1;
  p.quad_edge_threshold = f(s.quad_edge_threshold * u);
  // The (A, key) images' key: z itself, or with rg16f intermediates z / u, the key in metres, so
  // that binary16's range (65504) holds any scene's units and a scene in millimetres rounds its
  // keys where the same scene in metres does. The blur's sharpness is per key unit.
  if (s.half_intermediates) {
    p.key_scale = f(1.0 / u);
    p.key_to_view = f(u);
    p.blur_edge_sharpness = s.blur_edge_sharpness;
  } else {
    p.key_scale = 1.0f;
    p.key_to_view = 1.0f;
    p.blur_edge_sharpness = f(s.blur_edge_sharpness / u);
  }
  p.blur_edge_relative = s.blur_edge_relative;  // per |dz|/|z|: the same in any key unit
  p.blur_edge_slope = s.blur_edge_slope ? 1 : 0;
  p.blur_radius = s.blur_radius;
  p.blur_stride = s.blur_stride;

  // Gaussian in taps, sigma = R/2: w(t) = exp(-2 t^2 / R^2), w(0) = 1 implicit.
  static_assert(sizeof(p.blur_weights_1_4) + sizeof(p.blur_weights_5_8) == gen::SAO_MAX_BLUR_RADIUS * sizeof(float),
                "the block holds one weight per tap 1..SAO_MAX_BLUR_RADIUS");
  float w[gen::SAO_MAX_BLUR_RADIUS] = {};
  for (int t = 1; t <= std::min(s.blur_radius, gen::SAO_MAX_BLUR_RADIUS); ++t)
    w[t - 1] = f(std::exp(-2.0 * t * t / (double(s.blur_radius) * s.blur_radius)));
  p.blur_weights_1_4 = {w[0], w[1], w[2], w[3]};
  p.blur_weights_5_8 = {w[4], w[5], w[6], w[7]};

  p.ao_size = {static_cast<std::int32_t>(c.width), static_cast<std::int32_t>(c.height)};
  p.guard = {static_cast<std::int32_t>(c.guardBand), static_cast<std::int32_t>(c.guardBand)};
  p.ao_divisor = s.resolution_divisor;  // validated: 1, 2 or 4
  // Distance fade (off when fade_end is 0): lengths in view units like the radius; validate()
  // checked fade_start < fade_end when it is on.
  if (s.fade_end > 0.0f) {
    const double start = double(s.fade_start) * u, end = double(s.fade_end) * u;
    p.fade_start = f(start);
    p.fade_end = f(end);
    // At most FLT_MAX, so that t stays finite even for a range of a few denormals.
    p.fade_inv_range = f(std::min(1.0 / (end - start), double(std::numeric_limits<float>::max())));
  }
  // Multi-bounce (Jimenez et al. 2016's fit, docs/effect-math.md "Multi-bounce"): off at albedo 0,
  // where the store keeps A exactly (the fit itself is not quite the identity there).
  if (s.albedo > 0.0f) {
    const double rho = s.albedo;
    p.multi_bounce = 1;
    p.bounce_a = f(2.0404 * rho - 0.3324);
    p.bounce_b = f(-4.7951 * rho + 0.6417);
    p.bounce_c = f(2.7552 * rho + 0.6903);
  }
  p.normals_encoding = int(c.normalsEncoding);
  // Columns of R (identity without one: the camera encodings never read it).
  const std::array<double, 9> R = c.viewRotation.value_or(std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1});
  p.view_x = {f(R[0]), f(R[1]), f(R[2]), 0.0f};
  p.view_y = {f(R[3]), f(R[4]), f(R[5]), 0.0f};
  p.view_z = {f(R[6]), f(R[7]), f(R[8]), 0.0f};
  p.output_mask = 15;  // every channel of the output (kAllChannels); backends put the caller's mask here
  p.output_blend = gen::SAO_OUTPUT_BLEND_REPLACE;  // and the caller's blend (sao/output.h) here
  p.depth_sample_policy = int(c.depthSamplePolicy);
  p.depth_samples = 1;  // backends put the depth input's sample count here
  setFrameIndex(p, 0);  // the paper's spiral; backends set the caller's frame
  // Temporal accumulation: the history's share (docs/effect-math.md, "Temporal"); no history until
  // a backend sets the previous frame's camera (setPreviousFrame).
  p.temporal_min_blend = f(1.0 - double(s.temporal_hysteresis));
  p.temporal_max_frames = f(1.0 / (1.0 - double(s.temporal_hysteresis)));
  p.temporal_depth_k = f(1.0 / double(s.temporal_depth_tolerance));
  setPreviousFrame(p, c, nullptr);
  return Status::success();
}

gen::Float4 projInfo(const Camera& camera) { return projInfoOf(camera); }

void setPreviousFrame(ParamBlock& p, const Camera& current, const Camera* previous) {
  if (!previous || !current.view || !previous->view) {
    p.prev_from_cur_x = {1.0f, 0.0f, 0.0f, 0.0f};
    p.prev_from_cur_y = {0.0f, 1.0f, 0.0f, 0.0f};
    p.prev_from_cur_z = {0.0f, 0.0f, 1.0f, 0.0f};
    p.prev_proj_info = p.proj_info;
    p.history_valid = 0;
    return;
  }
  // M = V_prev * V_cur^-1 in double, V_cur^-1 = [R^T | -R^T t] (rigid): rows of M's upper 3x4.
  const auto& a = *previous->view;
  const auto& b = *current.view;
  auto A = [&](int r, int c) { return a[std::size_t(c * 4 + r)]; };
  auto B = [&](int r, int c) { return b[std::size_t(c * 4 + r)]; };
  double inv[3][4];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) inv[r][c] = B(c, r);
    inv[r][3] = -(B(0, r) * B(0, 3) + B(1, r) * B(1, 3) + B(2, r) * B(2, 3));
  }
  gen::Float4* rows[3] = {&p.prev_from_cur_x, &p.prev_from_cur_y, &p.prev_from_cur_z};
  for (int r = 0; r < 3; ++r) {
    double m[4];
    for (int c = 0; c < 4; ++c) m[c] = A(r, 0) * inv[0][c] + A(r, 1) * inv[1][c] + A(r, 2) * inv[2][c];
    m[3] += A(r, 3);
    *rows[r] = {f(m[0]), f(m[1]), f(m[2]), f(m[3])};
  }
  p.prev_proj_info = projInfoOf(*previous);
  p.history_valid = 1;
}

void setFrameIndex(ParamBlock& block, std::uint32_t frameIndex) {
  const FrameSpiral f = frameSpiral(frameIndex);
  block.frame_phase = f.phase;
  block.frame_alpha_offset = f.alphaOffset;
}

}  // namespace sao
