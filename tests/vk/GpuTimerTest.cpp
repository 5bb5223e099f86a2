#include "renderer/vk/GpuTimer.h"

#include "VulkanTest.h"
#include "renderer/vk/Buffer.h"
#include "renderer/vk/Commands.h"
#include "renderer/vk/Descriptors.h"
#include "renderer/vk/Pipeline.h"
#include "shaders/selftest_fill.comp.h"
#include "shaders/shared/config.h"
#include "shaders/shared/selftest.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace sss::vk {
namespace {

using testing::VulkanTest;

TEST_F(VulkanTest, TimestampScopeAroundDispatch) {
  GpuTimer timer(ctx(), 8);
  if (!timer.supported()) GTEST_SKIP() << "the queue has no timestamps";

  constexpr uint32_t kCount = 1 << 20;
  Buffer values(ctx(), {kCount * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT});
  DescriptorSetLayoutBuilder bindings;
  bindings.add(0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT);
  const auto set_layout = bindings.build(ctx());
  const shader::SelftestFillParams params{kCount, 1.0f, 0.0f, 0};
  const auto layout =
      create_pipeline_layout(ctx(), set_layout.get(), sizeof(params), VK_SHADER_STAGE_COMPUTE_BIT);
  const auto pipeline = create_compute_pipeline(ctx(), layout.get(), sss_spv_selftest_fill_comp);
  DescriptorPool pool(ctx(), bindings, 1);
  const VkDescriptorSet set = pool.allocate(set_layout.get());
  DescriptorWriter(set).storage_buffer(0, values).update(ctx());

  // Two frames through the same timer: reset() makes it reusable.
  for (int frame = 0; frame < 2; ++frame) {
    submit_once(ctx(), [&](VkCommandBuffer cmd) {
      timer.reset(cmd);
      auto outer = timer.scope(cmd, "frame");
      timer.begin(cmd, "fill");
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout.get(), 0, 1, &set, 0,
                              nullptr);
      vkCmdPushConstants(cmd, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(params),
                         &params);
      vkCmdDispatch(cmd, group_count(kCount, shader::kWorkgroup1D), 1, 1);
      timer.end(cmd);
      timer.begin(cmd, "empty");
      timer.end(cmd);
      timer.begin(cmd, "empty");  // the same name twice adds up
      timer.end(cmd);
    });
    const std::vector<PassTime>& times = timer.resolve();
    ASSERT_EQ(times.size(), 3u);
    EXPECT_EQ(times[0].name, "frame");
    EXPECT_EQ(times[1].name, "fill");
    EXPECT_EQ(times[2].name, "empty");
    EXPECT_EQ(times[2].count, 2u);
    for (const PassTime& t : times) {
      EXPECT_TRUE(std::isfinite(t.ms)) << t.name;
      EXPECT_GE(t.ms, 0.0) << t.name;
      EXPECT_LT(t.ms, 60000.0) << t.name;  // not a wrapped or garbage difference
    }
    ASSERT_TRUE(timer.milliseconds("fill").has_value());
    EXPECT_GT(*timer.milliseconds("fill"), 0.0);  // a million invocations take time
    EXPECT_GE(*timer.milliseconds("frame"), *timer.milliseconds("fill"));
    EXPECT_FALSE(timer.milliseconds("no such pass").has_value());
  }
}

TEST_F(VulkanTest, TimerRejectsUnbalancedScopes) {
  GpuTimer timer(ctx(), 4);
  submit_once(ctx(), [&](VkCommandBuffer cmd) {
    timer.reset(cmd);
    EXPECT_THROW(timer.end(cmd), std::logic_error);
    timer.begin(cmd, "open");
    EXPECT_THROW(timer.resolve(), std::logic_error);
    timer.end(cmd);
  });
  EXPECT_EQ(timer.resolve().size(), timer.supported() ? 1u : 0u);
}

TEST_F(VulkanTest, TimerBeyondCapacityStillLabels) {
  GpuTimer timer(ctx(), 2);
  submit_once(ctx(), [&](VkCommandBuffer cmd) {
    timer.reset(cmd);
    for (const char* name : {"a", "b", "c"}) {
      timer.begin(cmd, name);
      timer.end(cmd);
    }
  });
  const auto& times = timer.resolve();
  if (timer.supported()) {
    ASSERT_EQ(times.size(), 2u);  // "c" is labelled but not timed
    EXPECT_EQ(times[1].name, "b");
  }
}

}  // namespace
}  // namespace sss::vk

namespace sss::vk {
namespace {

// Labels go through VK_EXT_debug_utils of the loader and driver when no layer is loaded
// (the viewer's normal configuration).
TEST(GpuTimer, WorksWithoutTheValidationLayer) {
  ContextOptions options;
  options.device_name = testing::test_device_name();
  Context ctx(options);
  GpuTimer timer(ctx, 4);
  submit_once(ctx, [&](VkCommandBuffer cmd) {
    timer.reset(cmd);
    auto pass = timer.scope(cmd, "pass");
  });
  const auto& times = timer.resolve();
  if (timer.supported()) {
    ASSERT_EQ(times.size(), 1u);
    EXPECT_EQ(times[0].name, "pass");
    EXPECT_GE(times[0].ms, 0.0);
  }
}

}  // namespace
}  // namespace sss::vk
