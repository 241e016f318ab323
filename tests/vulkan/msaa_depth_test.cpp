// A multisampled depth input, Vulkan only (Config::depthSamples): create() refuses a count that is
// not one sample bit and counts the device cannot sample. Both policies against the CPU reference
// and the single-sample runs, and the second-layer refusal: tests/executors/msaa_depth_test.cpp.
#include <cstdio>
#include <string>
#include <tuple>

#include "sao/presets.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8;
constexpr auto kMultisample = static_cast<std::size_t>(gen::VariantId::DEPTH_MULTISAMPLE);

class MsaaDepth : public VkTest {};

vk::Config msaaConfig(VkFormat format, VkSampleCountFlagBits samples) {
  vk::Config c;
  c.camera = vulkanCamera(kW, kH, kGuard, 100.0);
  c.settings = presetSettings(Preset::Medium);
  c.depthFormat = format;
  c.depthSamples = samples;
  return c;
}

TEST_F(MsaaDepth, CreateRefusesBadSampleCounts) {
  std::unique_ptr<vk::Effect> effect;
  {
    const Status st = vk::Effect::create(context().deviceContext(),
                                         msaaConfig(VK_FORMAT_D32_SFLOAT, static_cast<VkSampleCountFlagBits>(3)), effect);
    EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
    EXPECT_NE(st.message.find("depthSamples"), std::string::npos) << st.message;
    EXPECT_EQ(effect, nullptr);
  }
  // Each count against the device's limit for the format: refused exactly where it cannot sample it.
  const auto& limits = context().properties().limits;
  for (const auto& [format, counts, what] :
       {std::tuple{VK_FORMAT_D32_SFLOAT, limits.sampledImageDepthSampleCounts, "D32_SFLOAT"},
        std::tuple{VK_FORMAT_R32_SFLOAT, limits.sampledImageColorSampleCounts, "R32_SFLOAT"}}) {
    std::printf("%s: sampled image sample counts 0x%x\n", what, unsigned(counts));
    for (std::uint32_t n = 2; n <= 64; n *= 2) {
      SCOPED_TRACE(std::string(what) + " " + std::to_string(n) + " samples");
      const Status st =
          vk::Effect::create(context().deviceContext(), msaaConfig(format, static_cast<VkSampleCountFlagBits>(n)), effect);
      if (counts & n) {
        ASSERT_TRUE(st.ok()) << st.message;
        EXPECT_EQ(effect->plan().variants[kMultisample], 1);
        EXPECT_EQ(effect->params().depth_samples, int(n));
      } else {
        EXPECT_EQ(st.code, StatusCode::UnsupportedFormat) << st.message;
        EXPECT_NE(st.message.find("depthSamples"), std::string::npos) << st.message;
        EXPECT_EQ(effect, nullptr);
      }
      effect.reset();
    }
  }
}

}  // namespace
}  // namespace sao::vktest
