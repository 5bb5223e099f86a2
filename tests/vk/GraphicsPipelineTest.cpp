// A triangle through the graphics pipeline builder and dynamic rendering, with a vertex
// buffer and a depth test; the pixels are read back.
#include "renderer/vk/GraphicsPipeline.h"

#include "VulkanTest.h"
#include "renderer/vk/Barrier.h"
#include "renderer/vk/Buffer.h"
#include "renderer/vk/Commands.h"
#include "renderer/vk/Image.h"
#include "renderer/vk/Pipeline.h"
#include "renderer/vk/Rendering.h"
#include "renderer/vk/Transfer.h"
#include "shaders/selftest_triangle.frag.h"
#include "shaders/selftest_triangle.vert.h"

#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <cstring>
#include <vector>

namespace sss::vk {
namespace {

using testing::VulkanTest;

struct Vertex {
  float position[3];
  float color[4];
};

TEST_F(VulkanTest, DrawsATriangleWithDepthTest) {
  constexpr uint32_t kSize = 32;
  constexpr VkFormat kColor = VK_FORMAT_R32G32B32A32_SFLOAT;
  constexpr VkFormat kDepth = VK_FORMAT_D32_SFLOAT;
  // Two triangles: a near red one over the left half, then a far green one over the
  // upper-left half (x + y < 0 in NDC), which the depth test must hide where the red one
  // is. The lower right keeps the clear colour.
  const std::array<Vertex, 6> vertices = {{
      {{-1.0f, -1.0f, 0.25f}, {1, 0, 0, 1}},
      {{-1.0f, 3.0f, 0.25f}, {1, 0, 0, 1}},
      {{0.0f, -1.0f, 0.25f}, {1, 0, 0, 1}},
      {{-1.0f, -1.0f, 0.75f}, {0, 1, 0, 1}},
      {{-1.0f, 3.0f, 0.75f}, {0, 1, 0, 1}},
      {{1.0f, -1.0f, 0.75f}, {0, 1, 0, 1}},
  }};
  Buffer vertex_buffer(ctx(), {sizeof(vertices), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT |
                                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT});
  upload_buffer(ctx(), vertex_buffer, std::span<const Vertex>(vertices));

  Image color(ctx(), {kSize, kSize, kColor,
                      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
  Image depth(ctx(), {kSize, kSize, kDepth, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT});

  const PipelineLayoutHandle layout = create_pipeline_layout(ctx(), VK_NULL_HANDLE, 0, 0);
  const PipelineHandle pipeline =
      GraphicsPipelineBuilder()
          .vertex_shader(sss_spv_selftest_triangle_vert)
          .fragment_shader(sss_spv_selftest_triangle_frag)
          .vertex_binding(0, sizeof(Vertex))
          .vertex_attribute(0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position))
          .vertex_attribute(1, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, color))
          .color(kColor)
          .depth(kDepth, DepthTest::Write)
          .cull(VK_CULL_MODE_NONE)
          .build(ctx(), layout.get(), "triangle");

  submit_once(ctx(), [&](VkCommandBuffer cmd) {
    const Scope attachment_write{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT};
    const Scope depth_access{
        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
            VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
    pipeline_barrier(
        cmd, {image_barrier(color, VK_IMAGE_LAYOUT_UNDEFINED,
                            VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kNothing, attachment_write),
              image_barrier(depth, VK_IMAGE_LAYOUT_UNDEFINED,
                            VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, kNothing, depth_access)});
    const ColorTarget target(color.view(), {{0.0f, 0.0f, 1.0f, 1.0f}});
    const DepthTarget depth_target(depth.view());
    begin_rendering(cmd, color.extent(), {&target, 1}, &depth_target);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.get());
    const VkBuffer buffers[] = {vertex_buffer.handle()};
    const VkDeviceSize offsets[] = {0};
    vkCmdBindVertexBuffers(cmd, 0, 1, buffers, offsets);
    vkCmdDraw(cmd, 6, 1, 0, 0);
    end_rendering(cmd);
    pipeline_barrier(cmd, {image_barrier(color, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                         VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, attachment_write,
                                         kTransferRead)});
  });

  const std::vector<std::byte> bytes =
      download_image(ctx(), color, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  std::vector<float> pixels(kSize * kSize * 4);
  std::memcpy(pixels.data(), bytes.data(), bytes.size());
  const auto pixel = [&](uint32_t x, uint32_t y) {
    const float* p = &pixels[(y * kSize + x) * 4];
    return std::array<float, 4>{p[0], p[1], p[2], p[3]};
  };
  EXPECT_EQ(pixel(4, 16), (std::array<float, 4>{1, 0, 0, 1}));   // near triangle wins
  EXPECT_EQ(pixel(20, 4), (std::array<float, 4>{0, 1, 0, 1}));   // only the far one
  EXPECT_EQ(pixel(30, 30), (std::array<float, 4>{0, 0, 1, 1}));  // clear colour
}

TEST_F(VulkanTest, BuilderRejectsIncompletePipelines) {
  const PipelineLayoutHandle layout = create_pipeline_layout(ctx(), VK_NULL_HANDLE, 0, 0);
  EXPECT_THROW(GraphicsPipelineBuilder().color(VK_FORMAT_R8G8B8A8_UNORM).build(ctx(), layout.get()),
               std::logic_error);
  EXPECT_THROW(GraphicsPipelineBuilder()
                   .vertex_shader(sss_spv_selftest_triangle_vert)
                   .build(ctx(), layout.get()),
               std::logic_error);
}

}  // namespace
}  // namespace sss::vk
