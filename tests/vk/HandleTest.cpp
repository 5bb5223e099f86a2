#include "renderer/vk/Handle.h"

#include "VulkanTest.h"
#include "renderer/vk/Buffer.h"
#include "renderer/vk/Commands.h"
#include "renderer/vk/Image.h"
#include "renderer/vk/Sampler.h"

#include <gtest/gtest.h>

#include <type_traits>
#include <utility>
#include <vector>

namespace sss::vk {
namespace {

using testing::VulkanTest;

static_assert(!std::is_copy_constructible_v<FenceHandle>);
static_assert(!std::is_copy_assignable_v<FenceHandle>);
static_assert(std::is_nothrow_move_constructible_v<FenceHandle>);
static_assert(std::is_nothrow_move_assignable_v<FenceHandle>);
static_assert(!std::is_copy_constructible_v<Buffer> &&
              std::is_nothrow_move_constructible_v<Buffer>);
static_assert(!std::is_copy_constructible_v<Image> && std::is_nothrow_move_constructible_v<Image>);

TEST_F(VulkanTest, MovingAHandleLeavesTheSourceEmpty) {
  FenceHandle a = create_fence(ctx());
  ASSERT_TRUE(a);
  const VkFence raw = a.get();

  FenceHandle b(std::move(a));
  EXPECT_FALSE(a);  // NOLINT(bugprone-use-after-move): the point of the test
  EXPECT_EQ(a.get(), VK_NULL_HANDLE);
  EXPECT_EQ(b.get(), raw);

  FenceHandle c = create_fence(ctx());
  c = std::move(b);  // c's own fence is destroyed, b's moves in
  EXPECT_FALSE(b);
  EXPECT_EQ(c.get(), raw);

  c = std::move(c);  // self-move keeps the object
  EXPECT_EQ(c.get(), raw);

  c.reset();
  EXPECT_FALSE(c);
  c.reset();  // twice is harmless

  FenceHandle d = create_fence(ctx());
  const VkFence released = d.release();
  EXPECT_FALSE(d);
  vkDestroyFence(ctx().device(), released, nullptr);  // the caller owns it now
}

TEST_F(VulkanTest, MovingBuffersAndImagesLeavesThemEmpty) {
  Buffer a(ctx(), {256, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUsage::Dynamic});
  ASSERT_TRUE(a.host_visible());
  const VkBuffer raw = a.handle();
  Buffer b = std::move(a);
  EXPECT_FALSE(a);
  EXPECT_EQ(a.size(), 0u);
  EXPECT_FALSE(a.host_visible());  // no dangling mapping
  EXPECT_EQ(b.handle(), raw);
  EXPECT_EQ(b.size(), 256u);
  b = Buffer();  // destroys the buffer, then frees its memory
  EXPECT_FALSE(b);

  Image i(ctx(), {8, 8, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT});
  const VkImageView view = i.view();
  Image j;
  j = std::move(i);
  EXPECT_FALSE(i);
  EXPECT_EQ(i.view(), VK_NULL_HANDLE);
  EXPECT_EQ(j.view(), view);
  EXPECT_EQ(j.width(), 8u);
}

// Containers of handles reallocate by moving; every object is destroyed exactly once
// (a double destroy or a leak would be reported by the layer when the device goes).
TEST_F(VulkanTest, HandlesInContainersAreDestroyedOnce) {
  std::vector<SamplerHandle> samplers;
  for (int i = 0; i < 20; ++i) samplers.push_back(create_sampler(ctx()));
  samplers.erase(samplers.begin() + 3, samplers.begin() + 9);
  std::vector<Image> images;
  for (int i = 0; i < 5; ++i) {
    images.emplace_back(ctx(),
                        ImageDesc{4, 4, VK_FORMAT_R16G16B16A16_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT});
  }
  images.erase(images.begin());
  EXPECT_EQ(samplers.size(), 14u);
  EXPECT_EQ(images.size(), 4u);
}

}  // namespace
}  // namespace sss::vk
