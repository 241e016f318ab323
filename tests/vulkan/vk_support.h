// Shared by the Vulkan backend tests: one headless context per test process with the validation
// layer and synchronization validation on (any message fails the running test), a one-call "run
// the effect on this depth and read everything back", and image comparison with failure images
// (image_compare.h).
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "image_compare.h"
#include "sao/camera.h"
#include "sao/image.h"
#include "sao/vulkan/effect.h"
#include "sao/vulkan/headless.h"
#include "test_cameras.h"

namespace sao::vktest {

// The process-wide context: validation + synchronization validation, the helper's usual device
// choice (a GPU when one exists, else lavapipe); SAO_VK_TEST_DEVICE=cpu forces the CPU device.
vk::headless::Context& context();

// Every test fails on a validation message raised while it ran.
class VkTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
};

// Fails the current test with the messages collected so far (and clears them).
void expectNoMessages(const char* where);

// The depth representations the tests upload.
enum class VkDepth { D16, X8D24, D24S8, D32F, D32FS8, R32F };
const char* toString(VkDepth f);
VkFormat vkFormat(VkDepth f);
DepthFormat cpuFormat(VkDepth f);

struct RunOptions {
  VkImageLayout depthLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  const FloatImage* normals = nullptr;  // uploaded as normalsFormat (its channels: 4, or 2 for RG)
  VkFormat normalsFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  const DepthImage* depth2 = nullptr;
  bool readIntermediates = true;        // ao_raw (and csz level 0)
  bool readChain = false;               // every level of csz (and csz2 with depth2, csz_share with thickness_model 1)
  std::optional<Offset> region;                              // vk::Inputs::region: the region inside larger inputs
  // A depth image the test made itself (e.g. multisampled), bound instead of uploading `depth`
  // (runEffect then does not read `depth`; its InputImage::format, when UNDEFINED, is the run's
  // format); depthSamples other than 1 goes into the depth's InputImage::samples.
  std::optional<vk::InputImage> depthImage;
  VkSampleCountFlagBits depthSamples = VK_SAMPLE_COUNT_1_BIT;
};

struct RunResult {
  Plan plan;
  ParamBlock params{};
  FloatImage ao;      // 1 channel
  FloatImage aoRaw;   // 2 channels (A, key z)
  VkFormat aoRawFormat = VK_FORMAT_UNDEFINED;  // the effect's ao_raw image (rg32f, or rg16f with half_intermediates)
  FloatImage csz0;    // csz level 0
  FloatImage aoLow;   // 2 channels (A, key z) when the plan has ao_low (resolution_divisor > 1)
  std::vector<FloatImage> csz, csz2;  // every level, with RunOptions::readChain
  std::vector<FloatImage> cszShare;  // every level (2 channels: z, the packed shares), with readChain where the plan has it
};

// Uploads `depth` in `format`, creates an effect (the default Config), records it once with
// `settings`, `camera` and the inputs (the first record plans), submits, waits and reads back.
Status runEffect(const Settings& settings, const Camera& camera, const DepthImage& depth, VkDepth format,
                 RunResult& out, const RunOptions& options = {});

// create() on context() with `config`; a failure fails the test and returns null.
std::unique_ptr<vk::Effect> makeEffect(const vk::Config& config = {});
// `record` into one command buffer, submitted and waited for; returns what `record` returned.
Status submitRecord(const std::function<Status(VkCommandBuffer)>& record);
// Reads back the owned output in its layout, or `userOutput` in Config::outputLayout.
FloatImage readOutput(const vk::Effect& e, const vk::OutputImage* userOutput = nullptr);
// One record() of these, submitted, expected to succeed, and the output read back.
FloatImage recordAndRead(vk::Effect& e, const Camera& camera, const Settings& settings, const vk::Inputs& in,
                         const vk::OutputImage* userOutput = nullptr);
// A storage image for the caller's output (Context::createStorageImage), destroyed with it.
struct StorageOutput {
  StorageOutput(VkFormat format, Extent extent) {
    EXPECT_TRUE(context().createStorageImage(format, extent, image).ok());
    output = {image.image, image.view, format, extent};
  }
  ~StorageOutput() { context().destroy(image); }
  vk::headless::Image image;
  vk::OutputImage output;
};
// `st` has `code` and a message containing `needle` (and is not empty).
void expectStatus(const Status& st, StatusCode code, const std::string& needle = "", const std::string& what = "");

// Cameras: 60 degree vertical field of view, near 0.1 (test_cameras.h).
using test::openglCamera;
using test::vulkanCamera;

std::string failureDir();  // tests/vulkan/failures in the build tree

// test::compare (image_compare.h) with its failure images under failureDir().
using test::acceptable;
using test::Agreement;
inline const test::FailureImagesIn compare{failureDir()};

// Resident set size of this process, bytes (/proc/self/statm).
std::uint64_t residentBytes();

}  // namespace sao::vktest
