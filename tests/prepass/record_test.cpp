// VkPrepass::record, the per-frame path sao-viewer draws with: recorded into the caller's command
// buffer, its depth has the same bits as render()'s, it refuses what it cannot draw, and a second
// frame at another size follows the first without validation messages.
#include <cstring>

#include "prepass_support.h"

namespace sao::prepasstest {
namespace {

#ifdef SAO_PREPASS_HAVE_VULKAN

class VkRecord : public PrepassTest {
 protected:
  void SetUp() override {
    PrepassTest::SetUp();
    ASSERT_TRUE(prepass::VkPrepass::create(vkPrepass().context(), prepass_).ok());
  }
  void TearDown() override {
    prepass_.reset();
    PrepassTest::TearDown();
  }
  // Records a frame and copies its depth out (D32F bits).
  Status recordAndRead(const glm::dmat4& view, const Camera& camera, std::vector<std::uint32_t>& bits) {
    vk::headless::Context& ctx = prepass_->context();
    vk::headless::Buffer buffer;
    const Extent e{camera.width + 2 * camera.guardBand, camera.height + 2 * camera.guardBand};
    if (Status s = ctx.createBuffer(VkDeviceSize(e.width) * e.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, buffer); !s)
      return s;
    Status recorded;
    Status submitted = ctx.submit([&](VkCommandBuffer cmd) {
      vk::headless::Image depth;
      recorded = prepass_->record(cmd, view, camera, DepthFormat::D32F, depth);
      if (!recorded) return;
      EXPECT_EQ(depth.layout, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
      EXPECT_TRUE(depth.extent == e);
      auto b = vk::headless::imageBarrier(depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, depth.layout,
                                          VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT);
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                           nullptr, 0, nullptr, 1, &b);
      VkBufferImageCopy copy{};
      copy.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
      copy.imageExtent = {e.width, e.height, 1};
      vkCmdCopyImageToBuffer(cmd, depth.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.buffer, 1, &copy);
      VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                             VK_ACCESS_HOST_READ_BIT};
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr,
                           0, nullptr);
    });
    if (submitted && recorded) {
      bits.resize(std::size_t(e.width) * e.height);
      std::memcpy(bits.data(), buffer.mapped, bits.size() * 4);
    }
    ctx.destroy(buffer);
    return submitted ? recorded : submitted;
  }
  std::unique_ptr<prepass::VkPrepass> prepass_;
};

TEST_F(VkRecord, DepthHasRendersBits) {
  const LoadedScene& loaded = loadScene("sphere-plane");
  const scenes::View& view = loaded.scene.views.front();
  ASSERT_TRUE(prepass_->setMesh(loaded.scene.mesh).ok());
  for (std::uint32_t guard : {0u, 4u}) {
    const Camera camera = scenes::makeCamera(view, 96, 64, INFINITY, ClipDepth::ZeroToOne, true, guard);
    std::vector<std::uint32_t> bits;
    ASSERT_TRUE(recordAndRead(scenes::viewMatrix(view), camera, bits).ok());
    prepass::PrepassResult rendered;
    ASSERT_TRUE(vkPrepass().render(loaded.scene.mesh, view, camera, {}, rendered).ok());
    ASSERT_EQ(rendered.depth.texels.size(), bits.size());
    std::size_t covered = 0;
    for (std::uint32_t b : bits) covered += b != 0;  // reversed-Z: 0 is the sky
    EXPECT_GT(covered, bits.size() / 4) << "guard band " << guard;
    EXPECT_EQ(std::memcmp(bits.data(), rendered.depth.texels.data(), bits.size() * 4), 0) << "guard band " << guard;
  }
}

TEST_F(VkRecord, RefusesWhatItCannotDraw) {
  const LoadedScene& loaded = loadScene("crease");
  const scenes::View& view = loaded.scene.views.front();
  const glm::dmat4 m = scenes::viewMatrix(view);
  Camera camera = scenes::makeCamera(view, 32, 32, INFINITY, ClipDepth::ZeroToOne, true);
  std::vector<std::uint32_t> bits;
  Status s = recordAndRead(m, camera, bits);
  EXPECT_EQ(s.code, StatusCode::InvalidInput);
  EXPECT_NE(s.message.find("setMesh"), std::string::npos) << s.message;
  EXPECT_EQ(prepass_->setMesh(scenes::Mesh{}).code, StatusCode::InvalidInput);
  ASSERT_TRUE(prepass_->setMesh(loaded.scene.mesh).ok());
  Camera flipped = camera;
  flipped.flipY = true;
  EXPECT_EQ(recordAndRead(m, flipped, bits).code, StatusCode::InvalidCamera);
  const Camera gl = scenes::makeCamera(view, 32, 32, 100.0, ClipDepth::NegativeOneToOne, false);
  s = recordAndRead(m, gl, bits);
  EXPECT_EQ(s.code, StatusCode::InvalidCamera);
  EXPECT_NE(s.message.find("[0, 1]"), std::string::npos) << s.message;
  EXPECT_TRUE(recordAndRead(m, camera, bits).ok()) << "the prepass works after refusals";
}

#endif

}  // namespace
}  // namespace sao::prepasstest
