// Shared by the OpenGL backend tests: one headless debug context per test process, texture
// upload/readback through libepoxy, image comparison with failure images.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sao/camera.h"
#include "sao/gl/effect.h"
#include "sao/gl/headless.h"
#include "sao/gl/texture_io.h"
#include "sao/image.h"

namespace sao::gltest {

// The process-wide headless context (created on first use, current on the main thread).
gl::HeadlessContext& context();

// Every test fails on a GL_DEBUG_TYPE_ERROR message raised while it ran.
class GlTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  std::unique_ptr<gl::Effect> makeEffect();
};

// Upload and readback live in sao_gl_headless (sao/gl/texture_io.h); these wrappers fail the
// test when an upload does not hold exactly the given texels.
using gl::cpuFormat;
using gl::deleteTexture;
using gl::GlDepth;
using gl::internalFormat;
using gl::makeTexture;
using gl::readTexture;
using gl::readTextureLevel;
using gl::toString;
std::uint32_t uploadDepth(const DepthImage& depth, GlDepth format);
std::uint32_t uploadNormals(const FloatImage& normals);  // GL_RGBA16F, nearest-even halves

// A 60-degree perspective camera, near 0.1, far `farDistance` (inf: infinite), OpenGL depth.
Camera camera(std::uint32_t width, std::uint32_t height, std::uint32_t guard, double farDistance = 1000.0,
              bool reversedZ = false);

struct Agreement {
  double maxAbs = 0;       // largest |actual - expected|
  double p999 = 0;         // 99.9th percentile of |actual - expected|
  double fractionWithin = 0;  // share of pixels within `within`
  std::size_t beyond = 0;     // pixels beyond `never`
  std::size_t nonFinite = 0;  // NaN / Inf in actual
};

// Compares channel `channel` of two images. When `write` is set and the comparison fails
// (fractionWithin < 0.999 or beyond > 0 or non-finite), writes <dir>/<name>_{actual,expected,diff}
// .png (diff scaled so that `never` is white) and float EXRs, and says where in `note`.
Agreement compare(const FloatImage& actual, const FloatImage& expected, std::uint32_t channel, double within,
                  double never, const std::string& name, std::string* note = nullptr);
bool acceptable(const Agreement& a);

std::string failureDir();  // tests/gl/failures in the build tree

}  // namespace sao::gltest
