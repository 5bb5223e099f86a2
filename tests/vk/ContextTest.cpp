#include "renderer/vk/Context.h"

#include "VulkanTest.h"
#include "renderer/vk/Check.h"
#include "renderer/vk/DeviceSelection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace sss::vk {
namespace {

using testing::VulkanTest;

TEST_F(VulkanTest, CreatesDeviceAndQueue) {
  EXPECT_NE(ctx().instance(), VK_NULL_HANDLE);
  EXPECT_NE(ctx().physical_device(), VK_NULL_HANDLE);
  EXPECT_NE(ctx().device(), VK_NULL_HANDLE);
  EXPECT_NE(ctx().queue(), VK_NULL_HANDLE);
  EXPECT_EQ(ctx().surface(), VK_NULL_HANDLE);  // headless
  const DeviceInfo& info = ctx().info();
  EXPECT_FALSE(info.name.empty());
  EXPECT_GE(info.api_version, VK_API_VERSION_1_3);
  EXPECT_GT(info.limits.maxImageDimension2D, 0u);
  EXPECT_GT(info.max_memory_allocation_size, 0u);
  EXPECT_GT(info.memory.memoryTypeCount, 0u);
  EXPECT_TRUE(std::isfinite(info.timestamp_period));
  EXPECT_GT(info.timestamp_period, 0.0f);
  EXPECT_LE(info.timestamp_valid_bits, 64u);
}

TEST_F(VulkanTest, ValidationLayerIsLoadedWhenInstalled) {
  if (!ctx().validation_enabled()) GTEST_SKIP() << "VK_LAYER_KHRONOS_validation is not installed";
  EXPECT_TRUE(ctx().validation_enabled());
}

TEST(Context, DefaultPicksTheBestDevice) {
  ContextOptions options = testing::validated_options();
  options.device_name.clear();
  Context ctx(options);
  // Whatever it picked ranks at least as high as every usable device.
  const auto candidates = examine_devices(ctx.instance(), {});
  for (const DeviceCandidate& c : candidates) {
    if (c.usable()) {
      EXPECT_GE(device_type_rank(ctx.info().type), device_type_rank(c.type)) << c.name;
    }
  }
  EXPECT_EQ(ctx.validation_message_count(), 0u);
}

TEST(Context, NameSelectsLavapipeCaseInsensitively) {
  ContextOptions options = testing::validated_options();
  options.device_name = "LLVMpipe";
  Context ctx(options);
  EXPECT_NE(ctx.info().name.find("llvmpipe"), std::string::npos) << ctx.info().name;
  EXPECT_EQ(ctx.info().type, VK_PHYSICAL_DEVICE_TYPE_CPU);
  // lavapipe's facts (DESIGN.md §9).
  EXPECT_EQ(ctx.info().timestamp_valid_bits, 64u);
  EXPECT_FLOAT_EQ(ctx.info().timestamp_period, 1.0f);
  EXPECT_EQ(ctx.validation_message_count(), 0u);
}

TEST(Context, UnknownNameThrowsListingDevices) {
  ContextOptions options = testing::validated_options();
  options.device_name = "no-such-gpu";
  try {
    Context ctx(options);
    FAIL() << "a Context was created for a device that does not exist";
  } catch (const VulkanError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no-such-gpu"), std::string::npos) << what;
    EXPECT_NE(what.find("available devices"), std::string::npos) << what;
    EXPECT_NE(what.find("llvmpipe"), std::string::npos) << what;
    EXPECT_EQ(e.result(), VK_ERROR_INITIALIZATION_FAILED);
  }
}

TEST(Context, MissingDeviceExtensionIsNamed) {
  ContextOptions options = testing::validated_options();
  options.device_extensions = {"VK_SSS_not_an_extension"};
  try {
    Context ctx(options);
    FAIL() << "a device without the extension was accepted";
  } catch (const VulkanError& e) {
    EXPECT_NE(std::string(e.what()).find("lacks the device extension VK_SSS_not_an_extension"),
              std::string::npos)
        << e.what();
  }
}

TEST(Context, MissingInstanceExtensionIsNamed) {
  ContextOptions options;
  options.instance_extensions = {"VK_SSS_not_an_extension"};
  EXPECT_THROW(Context ctx(options), VulkanError);
}

TEST(Context, RunsWithoutValidation) {
  ContextOptions options;
  options.device_name = testing::test_device_name();
  Context ctx(options);
  EXPECT_FALSE(ctx.validation_enabled());
}

TEST(DeviceSelection, RanksAndNames) {
  EXPECT_GT(device_type_rank(VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU),
            device_type_rank(VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU));
  EXPECT_GT(device_type_rank(VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU),
            device_type_rank(VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU));
  EXPECT_GT(device_type_rank(VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU),
            device_type_rank(VK_PHYSICAL_DEVICE_TYPE_CPU));
  EXPECT_TRUE(name_matches("llvmpipe (LLVM 15.0.6, 256 bits)", "LLVMPIPE"));
  EXPECT_TRUE(name_matches("NVIDIA GeForce RTX 4090", "rtx"));
  EXPECT_TRUE(name_matches("anything", ""));
  EXPECT_FALSE(name_matches("llvmpipe", "radeon"));
}

TEST(DeviceSelection, PrefersDiscreteAndExplainsUnusable) {
  auto device = [](const char* name, VkPhysicalDeviceType type, const char* why) {
    DeviceCandidate c;
    c.name = name;
    c.type = type;
    c.api_version = VK_API_VERSION_1_3;
    c.unsuitable = why;
    return c;
  };
  const std::vector<DeviceCandidate> devices = {
      device("llvmpipe", VK_PHYSICAL_DEVICE_TYPE_CPU, ""),
      device("Intel UHD", VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU, ""),
      device("Old Radeon", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU,
             "lacks the Vulkan 1.3 feature dynamicRendering"),
  };
  EXPECT_EQ(choose_device(devices, "").name, "Intel UHD");
  EXPECT_EQ(choose_device(devices, "llvm").name, "llvmpipe");
  try {
    choose_device(devices, "radeon");
    FAIL() << "an unusable device was chosen";
  } catch (const VulkanError& e) {
    EXPECT_NE(std::string(e.what()).find("dynamicRendering"), std::string::npos) << e.what();
  }
}

TEST(Check, ErrorCarriesExpressionFileLineAndResult) {
  try {
    VK_CHECK(VK_ERROR_DEVICE_LOST);
    FAIL() << "VK_CHECK did not throw";
  } catch (const VulkanError& e) {
    EXPECT_EQ(e.result(), VK_ERROR_DEVICE_LOST);
    EXPECT_EQ(e.expression(), "VK_ERROR_DEVICE_LOST");
    EXPECT_NE(e.file().find("ContextTest.cpp"), std::string::npos);
    EXPECT_GT(e.line(), 0);
    const std::string what = e.what();
    EXPECT_NE(what.find("failed with VK_ERROR_DEVICE_LOST"), std::string::npos) << what;
    EXPECT_NE(what.find("ContextTest.cpp:"), std::string::npos) << what;
  }
  EXPECT_EQ(VK_CHECK(VK_INCOMPLETE), VK_INCOMPLETE);  // successes with a message pass
  EXPECT_EQ(result_name(VK_SUBOPTIMAL_KHR), "VK_SUBOPTIMAL_KHR");
  EXPECT_EQ(result_name(static_cast<VkResult>(-12345)), "VkResult(-12345)");
}

}  // namespace
}  // namespace sss::vk
