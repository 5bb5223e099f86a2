// Simulated out-of-device-memory (SSS_FAIL_ALLOCATION_AFTER, ContextOptions::
// fail_allocation_after): after N successful allocations every further one fails with
// the error a real failure gives, says that it was simulated, names the size and the
// memory type, and leaves no Vulkan object behind (the layer reports leaked objects
// when the device is destroyed; this file fails on any message).
#include "VulkanTest.h"
#include "renderer/vk/Buffer.h"
#include "renderer/vk/Check.h"
#include "renderer/vk/Environment.h"
#include "renderer/vk/Image.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

namespace sss::vk {
namespace {

using testing::ScopedEnv;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A validated Context whose log outlives it, so that leaks reported at vkDestroyDevice
// are seen.
struct Validated {
  std::shared_ptr<ValidationLog> log = std::make_shared<ValidationLog>();
  std::unique_ptr<Context> ctx;
  explicit Validated(std::optional<uint64_t> fail_after) {
    ContextOptions options = testing::validated_options();
    options.validation_log = log;
    options.fail_allocation_after = fail_after;
    ctx = std::make_unique<Context>(options);
  }
  void expect_clean_end() {
    ctx->wait_idle();
    ctx.reset();
    for (const ValidationMessage& m : log->messages()) ADD_FAILURE() << to_string(m);
  }
};

TEST(AllocationFailure, TheAllocationAfterTheLimitFailsAsOutOfDeviceMemory) {
  Validated v(2);
  const BufferDesc desc(4096, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::DeviceLocal,
                        "third");
  {
    Buffer first(*v.ctx, {256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT});
    Buffer second(*v.ctx, {256, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUsage::Dynamic});
    EXPECT_EQ(v.ctx->successful_allocations(), 2u);
    try {
      Buffer third(*v.ctx, desc);
      ADD_FAILURE() << "the third allocation succeeded";
    } catch (const VulkanError& e) {
      EXPECT_EQ(e.result(), VK_ERROR_OUT_OF_DEVICE_MEMORY);
      const std::string what = e.what();
      EXPECT_TRUE(contains(what, "simulated")) << what;
      EXPECT_TRUE(contains(what, "SSS_FAIL_ALLOCATION_AFTER")) << what;
      // The buffer's memory requirements are at least its size (lavapipe: exactly).
      EXPECT_TRUE(contains(what, " bytes of device-local memory (memory type ")) << what;
      EXPECT_TRUE(contains(what, "VK_ERROR_OUT_OF_DEVICE_MEMORY")) << what;
    }
    // Images take the same path; and a freed block does not give the budget back
    // (the limit counts allocations made, so that a run fails at a reproducible point).
  }
  EXPECT_THROW(Image(*v.ctx, {8, 8, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT}),
               VulkanError);
  EXPECT_EQ(v.ctx->successful_allocations(), 2u);
  v.expect_clean_end();  // the VkBuffer / VkImage created before the failure are gone
}

TEST(AllocationFailure, ZeroFailsTheFirstAllocation) {
  Validated v(0);
  EXPECT_THROW(Buffer(*v.ctx, {64, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUsage::Upload}),
               VulkanError);
  v.expect_clean_end();
}

TEST(AllocationFailure, NoLimitByDefault) {
  ScopedEnv unset("SSS_FAIL_ALLOCATION_AFTER", nullptr);
  Validated v(std::nullopt);
  EXPECT_FALSE(v.ctx->fail_allocation_after().has_value());
  for (int i = 0; i < 8; ++i) Buffer b(*v.ctx, {64, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT});
  EXPECT_EQ(v.ctx->successful_allocations(), 8u);
  v.expect_clean_end();
}

TEST(AllocationFailure, TheEnvironmentVariableSetsTheLimit) {
  ScopedEnv env("SSS_FAIL_ALLOCATION_AFTER", "1");
  Validated v(std::nullopt);
  ASSERT_EQ(v.ctx->fail_allocation_after(), std::optional<uint64_t>(1));
  {
    Buffer first(*v.ctx, {64, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT});
    try {
      Buffer second(*v.ctx, {64, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT});
      ADD_FAILURE() << "the second allocation succeeded";
    } catch (const VulkanError& e) {
      EXPECT_EQ(e.result(), VK_ERROR_OUT_OF_DEVICE_MEMORY);
      EXPECT_TRUE(contains(e.what(), "simulated allocation failure (fail after 1 allocations"))
          << e.what();
    }
  }
  v.expect_clean_end();
}

TEST(AllocationFailure, AMalformedValueIsRefusedNamingTheVariable) {
  for (const char* bad : {"x", "-1", "3 ", "1e3", "99999999999999999999999"}) {
    ScopedEnv env("SSS_FAIL_ALLOCATION_AFTER", bad);
    try {
      Context ctx(testing::validated_options());
      ADD_FAILURE() << "accepted SSS_FAIL_ALLOCATION_AFTER=" << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_TRUE(contains(e.what(), std::string("SSS_FAIL_ALLOCATION_AFTER=") + bad)) << e.what();
    }
  }
}

}  // namespace
}  // namespace sss::vk
