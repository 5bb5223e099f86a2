// Device limits are honoured with the device's REAL values (queried, not assumed; on
// lavapipe by default): a request past a limit is refused with a VulkanError or
// std::invalid_argument that names the limit, before Vulkan is asked, so it cannot crash
// or trip the validation layer (the fixture fails on any message).
#include "VulkanTest.h"
#include "renderer/vk/Buffer.h"
#include "renderer/vk/Check.h"
#include "renderer/vk/Descriptors.h"
#include "renderer/vk/Image.h"
#include "renderer/vk/Memory.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace sss::vk {
namespace {

using testing::VulkanTest;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST_F(VulkanTest, AnAllocationPastMaxMemoryAllocationSizeIsRefused) {
  const VkDeviceSize max = ctx().info().max_memory_allocation_size;
  ASSERT_GT(max, 0u) << "the device reports no maxMemoryAllocationSize";
  VkMemoryRequirements requirements{};
  requirements.size = max + 1;
  requirements.alignment = 1;
  requirements.memoryTypeBits = ~0u;
  try {
    allocate_memory(ctx(), requirements, MemoryUsage::DeviceLocal, VK_NULL_HANDLE,
                    VK_NULL_HANDLE);
    ADD_FAILURE() << "allocated " << max + 1 << " bytes";
  } catch (const VulkanError& e) {
    EXPECT_EQ(e.result(), VK_ERROR_OUT_OF_DEVICE_MEMORY);
    EXPECT_TRUE(contains(e.what(), "maxMemoryAllocationSize (" + std::to_string(max) + ")"))
        << e.what();
  }
}

TEST_F(VulkanTest, ABufferPastMaxBufferSizeIsRefused) {
  const VkDeviceSize max = ctx().info().max_buffer_size;
  if (max == 0 || max == UINT64_MAX) GTEST_SKIP() << "maxBufferSize " << max;
  try {
    Buffer b(ctx(), {max + 1, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::DeviceLocal, "huge"});
    ADD_FAILURE() << "created a buffer of " << max + 1 << " bytes";
  } catch (const VulkanError& e) {
    EXPECT_TRUE(contains(e.what(), "maxBufferSize (" + std::to_string(max) + ")")) << e.what();
    EXPECT_TRUE(contains(e.what(), "\"huge\"")) << e.what();
  }
}

TEST_F(VulkanTest, AnImagePastMaxImageDimension2DIsRefused) {
  const uint32_t max = ctx().info().limits.maxImageDimension2D;
  for (const auto& [w, h] : {std::pair{max + 1, 1u}, std::pair{1u, max + 1}}) {
    try {
      Image image(ctx(), {w, h, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT, "wide"});
      ADD_FAILURE() << "created a " << w << "x" << h << " image";
    } catch (const VulkanError& e) {
      EXPECT_TRUE(contains(e.what(), "maxImageDimension2D (" + std::to_string(max) + ")"))
          << e.what();
    }
  }
  // The largest side allowed is made (a 1-texel-high strip: max * 4 bytes).
  Image edge(ctx(), {max, 1, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT});
  EXPECT_EQ(edge.width(), max);
}

// Every format the renderer creates is checked against its usage with the format's
// features first; an unsupported pair is named.
TEST_F(VulkanTest, AFormatWithoutTheFeatureForItsUsageIsRefusedByName) {
  // A depth format is never a colour attachment (no device has that feature for it).
  VkFormatProperties props{};
  vkGetPhysicalDeviceFormatProperties(ctx().physical_device(), VK_FORMAT_D32_SFLOAT, &props);
  ASSERT_EQ(props.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT, 0u);
  try {
    Image image(ctx(), {4, 4, VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "depth"});
    ADD_FAILURE() << "created a D32 colour attachment";
  } catch (const VulkanError& e) {
    EXPECT_EQ(e.result(), VK_ERROR_FORMAT_NOT_SUPPORTED);
    EXPECT_TRUE(contains(e.what(), "VK_FORMAT_D32_SFLOAT cannot be used as a colour attachment"))
        << e.what();
  }
}

// Ranges of one buffer bound at offsets rounded up to the device's alignment are
// accepted (and the layer is silent); an offset between two multiples is refused.
TEST_F(VulkanTest, DescriptorOffsetsRespectTheDeviceAlignment) {
  for (const VkDescriptorType type :
       {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}) {
    const VkDeviceSize alignment = descriptor_offset_alignment(ctx(), type);
    const VkPhysicalDeviceLimits& limits = ctx().info().limits;
    EXPECT_EQ(alignment, type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                             ? limits.minUniformBufferOffsetAlignment
                             : limits.minStorageBufferOffsetAlignment);
    const bool uniform = type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    // Three 20-byte ranges, each at the next aligned offset.
    constexpr VkDeviceSize kRange = 20;
    const VkDeviceSize stride = align_up(kRange, alignment);
    Buffer buffer(ctx(), {3 * stride, static_cast<VkBufferUsageFlags>(
                                          uniform ? VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT
                                                  : VK_BUFFER_USAGE_STORAGE_BUFFER_BIT)});
    DescriptorSetLayoutBuilder bindings;
    bindings.add(0, type, VK_SHADER_STAGE_COMPUTE_BIT).add(1, type, VK_SHADER_STAGE_COMPUTE_BIT);
    const auto layout = bindings.build(ctx());
    DescriptorPool pool(ctx(), bindings, 1);
    const VkDescriptorSet set = pool.allocate(layout.get());
    const auto write = [&](VkDeviceSize offset) {
      DescriptorWriter writer(set);
      if (uniform) {
        writer.uniform_buffer(0, buffer, offset, kRange).uniform_buffer(1, buffer, 2 * stride, kRange);
      } else {
        writer.storage_buffer(0, buffer, offset, kRange).storage_buffer(1, buffer, 2 * stride, kRange);
      }
      writer.update(ctx());
    };
    EXPECT_NO_THROW(write(stride));
    if (alignment > 1) {
      try {
        write(alignment / 2);
        ADD_FAILURE() << "offset " << alignment / 2 << " accepted";
      } catch (const std::invalid_argument& e) {
        EXPECT_TRUE(contains(e.what(), (uniform ? "minUniformBufferOffsetAlignment ("
                                                : "minStorageBufferOffsetAlignment (") +
                                           std::to_string(alignment) + ")"))
            << e.what();
      }
    }
  }
}

TEST_F(VulkanTest, AUniformRangePastMaxUniformBufferRangeIsRefused) {
  const uint32_t max = ctx().info().limits.maxUniformBufferRange;
  Buffer buffer(ctx(), {VkDeviceSize{max} + 256, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT});
  DescriptorSetLayoutBuilder bindings;
  bindings.add(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT);
  const auto layout = bindings.build(ctx());
  DescriptorPool pool(ctx(), bindings, 1);
  const VkDescriptorSet set = pool.allocate(layout.get());
  try {
    DescriptorWriter(set).uniform_buffer(0, buffer).update(ctx());  // the whole buffer
    ADD_FAILURE() << "bound " << max + 256 << " bytes as one uniform buffer";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "maxUniformBufferRange (" + std::to_string(max) + ")"))
        << e.what();
  }
  EXPECT_NO_THROW(DescriptorWriter(set).uniform_buffer(0, buffer, 0, max).update(ctx()));
}

}  // namespace
}  // namespace sss::vk
