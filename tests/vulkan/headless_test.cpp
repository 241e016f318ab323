// The headless helper: it finds a device (a GPU when there is one, else lavapipe, also with an
// exported but empty VK_DRIVER_FILES), and its messenger really catches validation errors and
// synchronization hazards (so that "no messages" in the other tests means something).
#include <cstdlib>

#include "sao/vulkan/headless.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

TEST(VkHeadless, FindsADevice) {
  const std::string saved = std::getenv("VK_DRIVER_FILES") ? std::getenv("VK_DRIVER_FILES") : "";
  const char* env = std::getenv("VK_DRIVER_FILES") ? saved.c_str() : nullptr;
  std::printf("VK_DRIVER_FILES at start: %s\n", env ? (*env ? env : "(exported, empty)") : "(unset)");
  std::unique_ptr<vk::headless::Context> c;
  const Status st = vk::headless::Context::create({}, c);
  ASSERT_TRUE(st.ok()) << st.message;
  std::printf("device: %s\n", c->description().c_str());
  EXPECT_NE(c->device(), VK_NULL_HANDLE);
  EXPECT_NE(c->queue(), VK_NULL_HANDLE);
  EXPECT_GE(c->apiVersion(), VK_API_VERSION_1_1);
  // Without a GPU the helper settles on the CPU device; with one it must not.
  std::uint32_t n = 0;
  vkEnumeratePhysicalDevices(c->instance(), &n, nullptr);
  std::vector<VkPhysicalDevice> all(n);
  vkEnumeratePhysicalDevices(c->instance(), &n, all.data());
  bool gpu = false;
  for (auto d : all) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    gpu |= p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU || p.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU;
  }
  EXPECT_EQ(c->isCpuDevice(), !gpu) << "a real GPU is preferred when one exists";
  if (env && *env && std::string(env).find("nonexistent") != std::string::npos) {
    EXPECT_FALSE(c->driverFiles().empty()) << "a VK_DRIVER_FILES that finds nothing is replaced by lavapipe's";
  }
  if (env && !*env) {
    // Unset (the loader's normal search) or pointed at lavapipe, never left exported and empty.
    const char* now = std::getenv("VK_DRIVER_FILES");
    EXPECT_TRUE(!now || *now) << "VK_DRIVER_FILES is still exported empty";
    EXPECT_NE(c->description().find("VK_DRIVER_FILES"), std::string::npos) << "the description says what happened";
  }
}

TEST(VkHeadless, CpuPreferenceGivesTheCpuDevice) {
  vk::headless::Options o;
  o.device = vk::headless::DevicePreference::Cpu;
  std::unique_ptr<vk::headless::Context> c;
  const Status st = vk::headless::Context::create(o, c);
  ASSERT_TRUE(st.ok()) << st.message;
  EXPECT_TRUE(c->isCpuDevice()) << c->description();
}

TEST(VkHeadless, ValidationCatchesAnInvalidCall) {
  auto& ctx = context();
  expectNoMessages("before the test");
  EXPECT_NE(ctx.layerStatus().find("SYNCHRONIZATION_VALIDATION"), std::string::npos)
      << "synchronization validation is on: " << ctx.layerStatus();
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 0;  // VUID-VkBufferCreateInfo-size-00912
  info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  VkBuffer b = VK_NULL_HANDLE;
  if (vkCreateBuffer(ctx.device(), &info, nullptr, &b) == VK_SUCCESS && b) vkDestroyBuffer(ctx.device(), b, nullptr);
  const auto messages = ctx.takeMessages();
  ASSERT_FALSE(messages.empty()) << "the validation layer reported nothing";
  EXPECT_NE(vk::headless::toString(messages).find("size"), std::string::npos) << vk::headless::toString(messages);
}

TEST(VkHeadless, SynchronizationValidationCatchesAHazard) {
  auto& ctx = context();
  expectNoMessages("before the test");
  vk::headless::Image a, b;
  ASSERT_TRUE(ctx.createStorageImage(VK_FORMAT_R16_SFLOAT, {8, 8}, a).ok());
  ASSERT_TRUE(ctx.createStorageImage(VK_FORMAT_R16_SFLOAT, {8, 8}, b).ok());
  // Two clears of the same image without a barrier between them: write-after-write.
  ASSERT_TRUE(ctx.submit([&](VkCommandBuffer cmd) {
                   const auto bar = vk::headless::imageBarrier(a.image, VK_IMAGE_ASPECT_COLOR_BIT,
                                                               VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, 0,
                                                               VK_ACCESS_TRANSFER_WRITE_BIT);
                   vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                                        nullptr, 0, nullptr, 1, &bar);
                   const VkClearColorValue v{};
                   const VkImageSubresourceRange r{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
                   vkCmdClearColorImage(cmd, a.image, VK_IMAGE_LAYOUT_GENERAL, &v, 1, &r);
                   vkCmdClearColorImage(cmd, a.image, VK_IMAGE_LAYOUT_GENERAL, &v, 1, &r);
                 })
                  .ok());
  const auto messages = ctx.takeMessages();
  ASSERT_FALSE(messages.empty()) << "synchronization validation reported nothing";
  EXPECT_NE(vk::headless::toString(messages).find("SYNC-HAZARD-WRITE-AFTER-WRITE"), std::string::npos)
      << vk::headless::toString(messages);
  ctx.destroy(a);
  ctx.destroy(b);
}

TEST(VkHeadless, UploadAndReadBackAreExact) {
  auto& ctx = context();
  expectNoMessages("before the test");
  // R32F goes through a colour upload and read-back bit for bit.
  DepthImage z;
  z.extent = {7, 5};
  z.format = DepthFormat::LinearZ;
  for (std::uint32_t i = 0; i < 35; ++i) z.texels.push_back(encodeDepth(DepthFormat::LinearZ, -0.5 - i * 0.37));
  vk::headless::Image img;
  ASSERT_TRUE(ctx.uploadDepth(z, VK_FORMAT_R32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, img).ok());
  FloatImage back;
  ASSERT_TRUE(ctx.readback(img.image, VK_FORMAT_R32_SFLOAT, z.extent, 0, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                           VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT, back)
                  .ok());
  for (std::uint32_t y = 0; y < 5; ++y)
    for (std::uint32_t x = 0; x < 7; ++x) EXPECT_EQ(back.at(x, y), float(z.value(x, y)));
  ctx.destroy(img);
  // A mismatched format is refused with a message.
  const Status st = ctx.uploadDepth(z, VK_FORMAT_D16_UNORM, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, img);
  EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
  expectNoMessages("during the test");
}

}  // namespace
}  // namespace sao::vktest
