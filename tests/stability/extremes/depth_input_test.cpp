// NaN, Inf, negative, > 1, denormal and extreme depth values: csz as docs/effect-math.md §3
// specifies, bit for bit, on every backend that accepts the input.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "extremes_support.h"

namespace sao::stability {
namespace {

// The linear_z pass as docs/effect-math.md §3 specifies it, in float with the block's constants:
// the value csz must hold.
float specZ(float d, const ParamBlock& p) {
  auto bits = [](float x) { return std::bit_cast<std::uint32_t>(x); };
  const bool finite = (bits(d) & 0x7F800000u) != 0x7F800000u;
  if (!finite || d * p.far_dir >= p.far_lim) return 0.0f;
  if (p.depth_mode != gen::SAO_DEPTH_MODE_LINEAR && (d < 0.0f || d > 1.0f)) return 0.0f;  // no hardware depth
  const float z = p.depth_mode == gen::SAO_DEPTH_MODE_PERSPECTIVE ? p.clip_info.x / (d * p.clip_info.y + p.clip_info.z)
                                                                  : d * p.clip_info.y + p.clip_info.z;
  const std::uint32_t b = bits(z);
  return (b > 0x80000000u && b < 0xFF800000u) ? z : 0.0f;
}

double specZDouble(double d, const ParamBlock& p) {
  if (!std::isfinite(d) || d * double(p.far_dir) >= double(p.far_lim)) return 0.0;
  if (p.depth_mode != gen::SAO_DEPTH_MODE_LINEAR && (d < 0.0 || d > 1.0)) return 0.0;
  const double c0 = p.clip_info.x, c1 = p.clip_info.y, c2 = p.clip_info.z;
  const double z = p.depth_mode == gen::SAO_DEPTH_MODE_PERSPECTIVE ? c0 / (d * c1 + c2) : d * c1 + c2;
  return (std::isfinite(z) && z < 0) ? z : 0.0;
}

std::string valueName(float v) {
  const std::uint32_t b = std::bit_cast<std::uint32_t>(v);
  if (std::isnan(v)) return fmt("NaN(0x%08X)", b);
  if (v == 0) return std::signbit(v) ? "-0" : "+0";
  return fmt("%.9g", double(v));
}

std::string zName(float z) { return z == 0.0f ? "sky" : fmt("%.4g", double(z)); }

// Runs frames of a plane at 2 m with `values` planted every 5th texel (and the same frame filled
// with a single value), on every backend; checks csz against the specification and A.
struct ValueCase {
  std::string convention;
  std::vector<std::string> zOfValue;  // csz per value (cpu)
  std::vector<std::string> zDouble;   // csz per value (cpu-double)
  std::vector<std::string> glHeld;    // whether GL's texture could hold the value
};
std::string joinRow(const std::string& head, const std::vector<std::string>& cells) {
  std::string row = head;
  for (const std::string& c : cells) row += " | " + c;
  return row;
}
std::size_t doubleOverflow = 0;  // csz texels the double reference stores as -Inf (F4)

ValueCase runValues(const std::string& what, const Camera& cam, DepthFormat fm, const std::vector<std::uint32_t>& texels,
                    bool gpuMayReject) {
  ValueCase vc;
  vc.convention = describe(cam);
  ParamBlock p;
  EXPECT_TRUE(computeConstants(fullResolution(), cam, fm == DepthFormat::LinearZ ? DepthEncoding::LinearZ : DepthEncoding::Hardware, p).ok());
  const test::Scene plane = test::planeScene(2.0);
  for (int mode = 0; mode < 2; ++mode) {  // 0: planted in a plane; 1: per value, a whole frame
    const std::size_t frames = mode == 0 ? 1 : texels.size();
    for (std::size_t f = 0; f < frames; ++f) {
      DepthImage depth = renderGpuDepth(plane, cam, fm);
      const Extent e = depth.extent;
      std::vector<int> valueAt(depth.texels.size(), -1);
      if (mode == 0) {
        std::size_t k = 0;
        for (std::uint32_t y = 2; y < e.height; y += 5)
          for (std::uint32_t x = 2; x < e.width; x += 5, ++k) {
            const std::size_t i = std::size_t(y) * e.width + x;
            valueAt[i] = int(k % texels.size());
            depth.texels[i] = texels[std::size_t(valueAt[i])];
          }
      } else {
        for (std::size_t i = 0; i < depth.texels.size(); ++i) depth.texels[i] = texels[f], valueAt[i] = int(f);
      }
      // Expected csz per texel (spec) and the AO pixels that are sky.
      std::vector<float> expect(depth.texels.size());
      std::vector<bool> sky(std::size_t(cam.width) * cam.height);
      for (std::size_t i = 0; i < depth.texels.size(); ++i) {
        const std::uint32_t t = depth.texels[i];
        float d;
        switch (fm) {
          case DepthFormat::D16: d = float(t & 0xFFFFu) * float(1.0 / 65535.0); break;
          case DepthFormat::D24: d = float(t & 0xFFFFFFu) * float(1.0 / 16777215.0); break;
          default: d = std::bit_cast<float>(t);
        }
        expect[i] = specZ(d, p);
      }
      for (std::uint32_t y = 0; y < cam.height; ++y)
        for (std::uint32_t x = 0; x < cam.width; ++x)
          sky[std::size_t(y) * cam.width + x] = expect[std::size_t(y + cam.guardBand) * e.width + x + cam.guardBand] == 0.0f;
      CaseOptions o;
      o.dumpPasses = true;
      o.gpuMayRejectInput = gpuMayReject;
      // A sky pixel is exactly 1; a pixel whose z is geometry may have any A in [0, 1].
      o.skyMask = &sky;
      const std::string label = fmt("%s, %s %s, %s", what.c_str(), vc.convention.c_str(), toString(fm),
                                    mode == 0 ? "planted" : valueName(std::bit_cast<float>(texels[f])).c_str());
      const CaseRuns runs = runCase(label, fullResolution(), cam, {&depth, nullptr, nullptr}, o);
      for (const BackendRun& b : runs.runs) {
        const FloatImage* csz = b.intermediate("csz_level0");
        if (!csz) continue;
        if (b.name != "cpu-double") {
          for (const auto& [name, img] : b.out.intermediates) EXPECT_TRUE(allFinite(img)) << label << " " << b.name << " " << name;
        }
        std::size_t mism = 0;
        for (std::size_t i = 0; i < expect.size(); ++i) {
          const float got = csz->data[i];
          bool ok;
          if (b.name == "cpu-double") {
            // The double reference: the same rules in double on the exact texel value (D16/D24:
            // v / (2^n - 1), so D24 code 2^24 - 2 is geometry there and sky in float, as
            // docs/effect-math.md §1 says). Where |z| > FLT_MAX (reversed-Z, infinite far, d
            // denormal) the double z is geometry and Result stores it as -Inf (finding F4): counted.
            const double zd = specZDouble(depth.value(std::uint32_t(i % e.width), std::uint32_t(i / e.width)), p);
            if (zd != 0 && std::fabs(zd) > double(std::numeric_limits<float>::max())) {
              if (std::isinf(got)) ++doubleOverflow;
              else ADD_FAILURE() << label << ": double z " << zd << " beyond float range stored as " << got;
              continue;
            }
            ok = (got == 0.0f) == (zd == 0.0) && (got == 0.0f || std::fabs(double(got) - zd) <= 1e-6 * std::fabs(zd) + 0x1p-149);
          } else
            ok = std::bit_cast<std::uint32_t>(got) == std::bit_cast<std::uint32_t>(expect[i]);
          if (!ok && mism++ < 3)
            ADD_FAILURE() << label << " on " << b.name << ": texel " << i << " depth bits 0x" << std::hex << depth.texels[i]
                          << std::dec << " gave csz " << got << ", the specification says " << expect[i];
        }
        if (mode == 1 && b.name == "cpu") vc.zOfValue.push_back(zName(csz->data[0]));
        if (mode == 1 && b.name == "cpu-double") vc.zDouble.push_back(zName(csz->data[0]));
      }
      if (mode == 1) {
        const BackendRun* gl = runs.find("gl");
        vc.glHeld.push_back(!backend("gl") ? "-" : gl ? "held" : "refused");
      }
    }
  }
  return vc;
}

// runValues for D32F texels on every convention, perspective and orthographic, with a table row of
// the csz each value gives (cpu; cpu-double where it differs; whether GL's texture held it).
void runD32fValuesOnEveryConvention(const std::string& what, const std::vector<std::uint32_t>& texels) {
  for (const Conv& cv : kConvs)
    for (bool ortho : {false, true}) {
      const Camera cam = convCamera(cv, 40, 30, 2, ortho);
      const ValueCase vc = runValues(what, cam, DepthFormat::D32F, texels, true);
      std::printf("[stability]   %s\n", joinRow(vc.convention + " (cpu)", vc.zOfValue).c_str());
      if (vc.zDouble != vc.zOfValue)
        std::printf("[stability]   %s\n", joinRow(vc.convention + " (cpu-double)", vc.zDouble).c_str());
      if (!ortho && cv.reversed && std::isinf(cv.far))
        std::printf("[stability]   %s\n", joinRow("GL texture", vc.glHeld).c_str());
    }
}

TEST(DepthInput, NaNInfNegativeAndAboveOne) {
  const float vals[] = {std::bit_cast<float>(0x7FC00000u), std::bit_cast<float>(0x7F800001u),
                        std::bit_cast<float>(0xFFC00000u), INFINITY, -INFINITY, -0.0f, -0.5f, -1e30f,
                        -std::numeric_limits<float>::max(), 1.5f, 1e30f, std::numeric_limits<float>::max()};
  std::vector<std::uint32_t> texels;
  for (float v : vals) texels.push_back(std::bit_cast<std::uint32_t>(v));
  std::string header = "value";
  for (float v : vals) header += " | " + valueName(v);
  std::printf("[stability] D32F input values -> csz (cpu):\n[stability]   %s\n", header.c_str());
  runD32fValuesOnEveryConvention("D32F special values", texels);
  // R32F linear z: everything that is not a finite negative non-zero z is sky.
  const float lin[] = {std::bit_cast<float>(0x7FC00000u), INFINITY, -INFINITY, 0.0f, -0.0f, 5.0f,
                       std::bit_cast<float>(0x80000001u), -1e30f, -std::numeric_limits<float>::max()};
  std::vector<std::uint32_t> lt;
  std::string lh;
  for (float v : lin) lt.push_back(std::bit_cast<std::uint32_t>(v)), lh += " | " + valueName(v);
  const ValueCase vl = runValues("R32F special values", camera(40, 30, 0.1, kInf, ClipDepth::ZeroToOne, true, 2),
                                 DepthFormat::LinearZ, lt, false);
  std::string row;
  for (const std::string& z : vl.zOfValue) row += " | " + z;
  std::printf("[stability] R32F linear z values%s\n[stability]   -> csz%s\n", lh.c_str(), row.c_str());
  report("NaN (quiet, signalling, negative), +-Inf, -0, negative, > 1 and +-FLT_MAX in D32F (6 conventions, persp+ortho) and R32F",
         "csz as docs/effect-math.md §3 specifies (bit-exact in float); sky -> A = 1; everything finite",
         "as specified on every backend that accepts the input; table in docs/STABILITY.md");
}

TEST(DepthInput, DenormalAndExtremeValues) {
  const float vals[] = {0.0f,
                        1.0f,
                        1.0f - 0x1p-24f,
                        0x1p-24f,
                        std::bit_cast<float>(0x00000001u),  // smallest denormal 1.4e-45
                        1e-40f,
                        std::bit_cast<float>(0x007FFFFFu),  // largest denormal
                        0x1p-126f,                          // smallest normal
                        0.5f};
  std::vector<std::uint32_t> texels;
  std::string header;
  for (float v : vals) texels.push_back(std::bit_cast<std::uint32_t>(v)), header += " | " + valueName(v);
  std::printf("[stability] D32F extreme values -> csz (cpu)%s\n", header.c_str());
  runD32fValuesOnEveryConvention("D32F extreme values", texels);
  // Integer formats: 0, 1, the last two codes.
  for (DepthFormat fm : {DepthFormat::D16, DepthFormat::D24}) {
    const std::uint32_t top = fm == DepthFormat::D16 ? 0xFFFFu : 0xFFFFFFu;
    const std::vector<std::uint32_t> codes = {0u, 1u, top - 1, top};
    for (const Conv& cv : {kConvs[1], kConvs[2], kConvs[4]}) {
      const Camera cam = convCamera(cv, 40, 30, 2);
      const ValueCase vc = runValues("unorm extreme codes", cam, fm, codes, false);
      const std::string head = vc.convention + " " + toString(fm) + " codes 0, 1, max-1, max";
      std::printf("[stability]   %s\n", joinRow(head + " (cpu)", vc.zOfValue).c_str());
      if (vc.zDouble != vc.zOfValue) std::printf("[stability]   %s\n", joinRow(head + " (cpu-double)", vc.zDouble).c_str());
    }
  }
  report("d = 0, 1, 1-2^-24, 2^-24, denormals, 2^-126 (D32F); codes 0, 1, max-1, max (D16, D24)",
         "finite; csz as specified; sky -> A = 1",
         fmt("as specified on every backend (table in docs/STABILITY.md); final A finite everywhere; cpu-double stores %zu "
             "csz texels beyond FLT_MAX as -Inf in its Result (finding F4)", doubleOverflow));
}

}  // namespace
}  // namespace sao::stability
