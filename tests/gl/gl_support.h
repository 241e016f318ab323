// Shared by the OpenGL backend tests: one headless debug context per test process, texture
// upload/readback through libepoxy, image comparison with failure images (image_compare.h).
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "analytic_scenes.h"
#include "image_compare.h"
#include "sao/camera.h"
#include "sao/gl/effect.h"
#include "sao/gl/headless.h"
#include "sao/gl/texture_io.h"
#include "sao/image.h"
#include "test_cameras.h"

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
// An immutable GL_TEXTURE_2D_ARRAY of `layers` layers (stereo: Inputs::layer), contents undefined.
std::uint32_t makeTextureArray(std::uint32_t internalFormat, Extent extent, std::uint32_t layers);
// An immutable depth array of `internalFormat` (GL_DEPTH_COMPONENT24 / 32F), layer i holding
// layers[i]'s values (decoded to floats, exact for D32F).
std::uint32_t uploadDepthArray(std::uint32_t internalFormat, const std::vector<const DepthImage*>& layers);

// A 60-degree perspective camera, near 0.1, far `farDistance` (inf: infinite), OpenGL depth.
inline Camera camera(std::uint32_t width, std::uint32_t height, std::uint32_t guard, double farDistance = 1000.0,
                     bool reversedZ = false) {
  return test::openglCamera(width, height, guard, farDistance, reversedZ);
}

std::string failureDir();  // tests/gl/failures in the build tree

// The reference tests' scenes (also what Vulkan is compared with GL on): "plane" (3 m away),
// "crease" (2 m), "sphere" (on a plane), "stairs", anything else the rods.
test::Scene sceneByName(const std::string& name);

// test::compare (image_compare.h) with its failure images under failureDir().
using test::acceptable;
using test::Agreement;
inline const test::FailureImagesIn compare{failureDir()};

}  // namespace sao::gltest
