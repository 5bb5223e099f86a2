#include "renderer/vk/DeletionQueue.h"

#include "VulkanTest.h"
#include "renderer/vk/Barrier.h"
#include "renderer/vk/Buffer.h"
#include "renderer/vk/Check.h"
#include "renderer/vk/Commands.h"
#include "renderer/vk/Transfer.h"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace sss::vk {
namespace {

using testing::VulkanTest;

// Counts its own destruction, so the test sees exactly when the queue destroys it.
struct Tracked {
  explicit Tracked(std::vector<std::string>* log, std::string name)
      : log_(log), name_(std::move(name)) {}
  Tracked(Tracked&& other) noexcept
      : log_(std::exchange(other.log_, nullptr)), name_(other.name_) {}
  ~Tracked() {
    if (log_ != nullptr) log_->push_back(name_);
  }
  std::vector<std::string>* log_;
  std::string name_;
};

TEST_F(VulkanTest, DeferredObjectsDieOnlyWhenTheirFrameRetires) {
  std::vector<std::string> destroyed;
  DeletionQueue queue(ctx(), 2);
  queue.defer(0, Tracked(&destroyed, "frame0-a"));
  queue.defer(0, Tracked(&destroyed, "frame0-b"));
  queue.defer(1, Tracked(&destroyed, "frame1"));
  queue.push(1, [&] { destroyed.push_back("frame1-callback"); });
  EXPECT_TRUE(destroyed.empty());
  EXPECT_EQ(queue.pending(0), 2u);
  EXPECT_EQ(queue.pending(1), 2u);

  queue.retire(1);
  EXPECT_EQ(destroyed, (std::vector<std::string>{"frame1-callback", "frame1"}));  // newest first
  EXPECT_EQ(queue.pending(0), 2u);

  queue.retire(0);
  EXPECT_EQ(destroyed,
            (std::vector<std::string>{"frame1-callback", "frame1", "frame0-b", "frame0-a"}));
  EXPECT_EQ(queue.pending(), 0u);

  queue.retire(0);  // retiring an empty frame is fine
  EXPECT_THROW(queue.retire(2), std::out_of_range);
  EXPECT_THROW(DeletionQueue(ctx(), 0), std::invalid_argument);
}

TEST_F(VulkanTest, FlushAllAndDestructorDestroyEverything) {
  std::vector<std::string> destroyed;
  {
    DeletionQueue queue(ctx(), 3);
    queue.defer(2, Tracked(&destroyed, "a"));
    queue.flush_all();
    EXPECT_EQ(destroyed.size(), 1u);
    queue.defer(1, Tracked(&destroyed, "b"));
  }
  EXPECT_EQ(destroyed, (std::vector<std::string>{"a", "b"}));
}

// The real use: a buffer that a submitted frame reads is deferred, survives until the
// frame's fence, and is destroyed by retire() without validation errors.
TEST_F(VulkanTest, DeferredBufferOutlivesItsFrame) {
  constexpr uint32_t kFrames = 2;
  DeletionQueue queue(ctx(), kFrames);
  // One pool per frame in flight, reset whole when its frame comes round again.
  std::vector<CommandPoolHandle> pools;
  std::vector<FenceHandle> fences;
  std::vector<VkCommandBuffer> cmds;
  for (uint32_t f = 0; f < kFrames; ++f) {
    fences.push_back(create_fence(ctx(), true));
    pools.push_back(create_command_pool(ctx(), 0));
    cmds.push_back(allocate_command_buffer(ctx(), pools.back().get()));
  }
  Buffer target(ctx(),
                {1 << 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT});

  for (uint32_t frame_number = 0; frame_number < 6; ++frame_number) {
    const uint32_t f = frame_number % kFrames;
    wait_for_fence(ctx(), fences[f].get());
    queue.retire(f);  // frame f's previous use is over
    const VkFence fence = fences[f].get();
    VK_CHECK(vkResetFences(ctx().device(), 1, &fence));
    VK_CHECK(vkResetCommandPool(ctx().device(), pools[f].get(), 0));

    // A per-frame source buffer, used by this frame's copy, then dropped at once.
    Buffer source(ctx(), {1 << 16, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload});
    std::vector<uint32_t> words(source.size() / 4, frame_number);
    source.write(words.data(), source.size());

    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmds[f], &begin));
    const VkBufferMemoryBarrier2 before[] = {buffer_barrier(target, kAllCommands, kTransferWrite)};
    pipeline_barrier(cmds[f], {}, before);
    const VkBufferCopy region{0, 0, source.size()};
    vkCmdCopyBuffer(cmds[f], source.handle(), target.handle(), 1, &region);
    const VkBufferMemoryBarrier2 after[] = {buffer_barrier(target, kTransferWrite, kAllCommands)};
    pipeline_barrier(cmds[f], {}, after);
    VK_CHECK(vkEndCommandBuffer(cmds[f]));
    VkCommandBufferSubmitInfo cmd_info{};
    cmd_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO;
    cmd_info.commandBuffer = cmds[f];
    VkSubmitInfo2 submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2;
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmd_info;
    ctx().submit({&submit, 1}, fence);

    queue.defer(f, std::move(source));  // destroying it now would be a use-after-free
    EXPECT_FALSE(source);
    EXPECT_EQ(queue.pending(f), 1u);
  }
  queue.flush_all();
  const auto last = download_buffer_as<uint32_t>(ctx(), target, 4);
  EXPECT_EQ(last[0], 5u);
}

}  // namespace
}  // namespace sss::vk
