// Staging uploads and downloads: every byte comes back as it went in.
#include "renderer/vk/Transfer.h"

#include "VulkanTest.h"
#include "renderer/vk/Buffer.h"
#include "renderer/vk/Check.h"
#include "renderer/vk/Image.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace sss::vk {
namespace {

using testing::VulkanTest;

std::vector<std::byte> pattern(std::size_t n, uint32_t seed) {
  std::vector<std::byte> bytes(n);
  uint32_t x = seed;
  for (std::byte& b : bytes) {
    x = x * 1664525u + 1013904223u;
    b = static_cast<std::byte>(x >> 24);
  }
  return bytes;
}

TEST_F(VulkanTest, BufferRoundTripThroughStaging) {
  const std::vector<std::byte> data = pattern(100003, 7);
  Buffer buffer(ctx(), {data.size() + 64,
                        VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT});
  upload_buffer(ctx(), buffer, std::span<const std::byte>(data), 64);
  EXPECT_EQ(download_buffer(ctx(), buffer, 64, data.size()), data);
  EXPECT_THROW(upload_buffer(ctx(), buffer, std::span<const std::byte>(data), 65),
               std::out_of_range);
}

TEST_F(VulkanTest, HostVisibleBufferWritesAndReads) {
  Buffer buffer(ctx(), {256, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUsage::Dynamic});
  ASSERT_TRUE(buffer.host_visible());
  const std::vector<std::byte> data = pattern(100, 3);
  buffer.write(data.data(), data.size(), 10);
  std::vector<std::byte> back(100);
  buffer.read(back.data(), back.size(), 10);
  EXPECT_EQ(back, data);
  EXPECT_THROW(buffer.write(data.data(), data.size(), 200), std::out_of_range);
  Buffer device_only(ctx(), {256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT});
  if (!device_only.host_visible()) {
    EXPECT_THROW(device_only.write(data.data(), 1), std::logic_error);
  }
}

class ImageRoundTrip : public VulkanTest, public ::testing::WithParamInterface<VkFormat> {};

TEST_P(ImageRoundTrip, UploadThenDownloadIsExact) {
  const VkFormat format = GetParam();
  const uint32_t texel = format == VK_FORMAT_R32G32B32A32_SFLOAT ? 16 : 8;
  constexpr uint32_t kW = 37, kH = 23, kLayers = 2;  // odd sizes: no row padding assumed
  // Bytes that are finite, non-NaN floats either way: halves/floats built from small ints.
  std::vector<std::byte> data(kW * kH * kLayers * texel);
  for (std::size_t i = 0; i < data.size() / texel * 4; ++i) {
    const float value = static_cast<float>(i % 2048) * 0.5f - 100.0f;
    if (texel == 16) {
      std::memcpy(data.data() + i * 4, &value, 4);
    } else {
      // fp16 of value, exact: |value| < 1024 with one fractional bit.
      const float a = value < 0 ? -value : value;
      uint16_t h = 0;
      if (a != 0.0f) {
        int e = 0;
        const float m = std::frexp(a, &e);  // a = m·2^e, m in [0.5, 1)
        h = static_cast<uint16_t>(((e + 14) << 10) | (static_cast<uint32_t>(m * 2048.0f) & 0x3ff));
      }
      if (value < 0) h |= 0x8000;
      std::memcpy(data.data() + i * 2, &h, 2);
    }
  }
  ImageDesc desc(kW, kH, format,
                 VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                     VK_IMAGE_USAGE_SAMPLED_BIT,
                 "round trip");
  desc.array_layers = kLayers;
  desc.view_type = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
  Image image(ctx(), desc);
  upload_image(ctx(), image, data, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(download_image(ctx(), image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL), data);
  // A second download from the same layout (the first restored it).
  EXPECT_EQ(download_image(ctx(), image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL), data);
  EXPECT_THROW(upload_image(ctx(), image, std::span(data).first(data.size() - 1),
                            VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL),
               std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Formats, ImageRoundTrip,
                         ::testing::Values(VK_FORMAT_R16G16B16A16_SFLOAT,
                                           VK_FORMAT_R32G32B32A32_SFLOAT),
                         [](const auto& param_info) {
                           return param_info.param == VK_FORMAT_R16G16B16A16_SFLOAT ? "rgba16f"
                                                                                    : "rgba32f";
                         });

TEST_F(VulkanTest, ImageDescriptionErrorsAreNamed) {
  EXPECT_THROW(Image(ctx(), {0, 4, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT}),
               std::invalid_argument);
  const uint32_t too_big = ctx().info().limits.maxImageDimension2D + 1;
  try {
    Image image(ctx(), {too_big, 4, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT, "huge"});
    FAIL() << "an image over the size limit was created";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("huge"), std::string::npos) << e.what();
  }
  // A format the device cannot use as a storage image (lavapipe: no ETC2 at all).
  EXPECT_THROW(Image(ctx(), {4, 4, VK_FORMAT_ETC2_R8G8B8_UNORM_BLOCK, VK_IMAGE_USAGE_STORAGE_BIT}),
               VulkanError);
}

TEST_F(VulkanTest, OversizedBufferNamesTheLimit) {
  // Over both limits; the first one checked is named, before Vulkan sees the request.
  const VkDeviceSize too_big =
      std::max(ctx().info().max_memory_allocation_size, ctx().info().max_buffer_size) + 1;
  try {
    Buffer buffer(ctx(),
                  {too_big, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::DeviceLocal, "huge"});
    FAIL() << "a buffer over the device limits was created";
  } catch (const VulkanError& e) {
    const std::string what = e.what();
    EXPECT_TRUE(what.find("maxBufferSize") != std::string::npos ||
                what.find("maxMemoryAllocationSize") != std::string::npos)
        << what;
    EXPECT_NE(what.find("huge"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace sss::vk
