// Compute pipelines from the build's embedded SPIR-V, with every kind of descriptor the
// passes use: storage buffer; sampled image, sampler, storage image, uniform buffer.
#include "VulkanTest.h"
#include "renderer/vk/Barrier.h"
#include "renderer/vk/Buffer.h"
#include "renderer/vk/Commands.h"
#include "renderer/vk/Descriptors.h"
#include "renderer/vk/Image.h"
#include "renderer/vk/Pipeline.h"
#include "renderer/vk/Sampler.h"
#include "renderer/vk/Transfer.h"
#include "shaders/selftest_fill.comp.h"
#include "shaders/selftest_image.comp.h"
#include "shaders/shared/config.h"
#include "shaders/shared/selftest.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <vector>

namespace sss::vk {
namespace {

using testing::VulkanTest;

TEST_F(VulkanTest, ComputeFillsStorageBuffer) {
  constexpr uint32_t kCount = 10007;  // not a multiple of the workgroup size
  const shader::SelftestFillParams params{kCount, 0.5f, -3.0f, 0};

  Buffer values(ctx(), {kCount * sizeof(float),
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                        MemoryUsage::DeviceLocal, "values"});
  DescriptorSetLayoutBuilder bindings;
  bindings.add(0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT);
  const DescriptorSetLayoutHandle set_layout = bindings.build(ctx(), "fill");
  const PipelineLayoutHandle layout = create_pipeline_layout(
      ctx(), set_layout.get(), sizeof(params), VK_SHADER_STAGE_COMPUTE_BIT, "fill");
  const PipelineHandle pipeline =
      create_compute_pipeline(ctx(), layout.get(), sss_spv_selftest_fill_comp, nullptr, "fill");
  DescriptorPool pool(ctx(), bindings, 1);
  const VkDescriptorSet set = pool.allocate(set_layout.get());
  DescriptorWriter(set).storage_buffer(0, values).update(ctx());

  submit_once(ctx(), [&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout.get(), 0, 1, &set, 0,
                            nullptr);
    vkCmdPushConstants(cmd, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(params), &params);
    vkCmdDispatch(cmd, group_count(kCount, shader::kWorkgroup1D), 1, 1);
  });

  const std::vector<float> result = download_buffer_as<float>(ctx(), values, kCount);
  for (uint32_t i = 0; i < kCount; ++i) {
    ASSERT_EQ(result[i], params.scale * static_cast<float>(i) + params.offset) << "at " << i;
  }
}

TEST_F(VulkanTest, ComputeReadsSampledImageWritesStorageImage) {
  constexpr uint32_t kW = 19, kH = 13;  // partial workgroups at both edges
  // rgba32f source with a distinct value per texel; the shader scales it by `gain`.
  std::vector<float> source(kW * kH * 4);
  for (uint32_t i = 0; i < source.size(); ++i) source[i] = static_cast<float>(i % 256) * 0.25f;
  Image src(ctx(), {kW, kH, VK_FORMAT_R32G32B32A32_SFLOAT,
                    VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT});
  upload_image(ctx(), src, std::as_bytes(std::span(source)),
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  Image dst(ctx(), {kW, kH, VK_FORMAT_R16G16B16A16_SFLOAT,
                    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
  const std::array<float, 4> gain = {2.0f, 1.0f, 0.5f, 1.0f};
  Buffer uniforms(ctx(), {sizeof(gain), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUsage::Dynamic});
  uniforms.write(gain.data(), sizeof(gain));
  const SamplerHandle nearest =
      create_sampler(ctx(), {VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});

  DescriptorSetLayoutBuilder bindings;
  bindings.add(0, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT)
      .add(1, VK_DESCRIPTOR_TYPE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT)
      .add(2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT)
      .add(3, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT);
  const DescriptorSetLayoutHandle set_layout = bindings.build(ctx());
  const PipelineLayoutHandle layout = create_pipeline_layout(ctx(), set_layout.get(), 0, 0);
  const PipelineHandle pipeline =
      create_compute_pipeline(ctx(), layout.get(), sss_spv_selftest_image_comp);
  DescriptorPool pool(ctx(), bindings, 1);
  const VkDescriptorSet set = pool.allocate(set_layout.get());
  DescriptorWriter(set)
      .sampled_image(0, src)
      .sampler(1, nearest.get())
      .storage_image(2, dst)
      .uniform_buffer(3, uniforms)
      .update(ctx());

  submit_once(ctx(), [&](VkCommandBuffer cmd) {
    pipeline_barrier(cmd, {image_barrier(dst, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                                         kNothing, kComputeWrite)});
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout.get(), 0, 1, &set, 0,
                            nullptr);
    vkCmdDispatch(cmd, group_count(kW, shader::kWorkgroup2DX),
                  group_count(kH, shader::kWorkgroup2DY), 1);
  });

  const std::vector<std::byte> bytes = download_image(ctx(), dst, VK_IMAGE_LAYOUT_GENERAL);
  ASSERT_EQ(bytes.size(), kW * kH * 8u);
  std::vector<uint16_t> half(kW * kH * 4);
  std::memcpy(half.data(), bytes.data(), bytes.size());
  // Every source value (a multiple of 0.25 below 64) times 2, 1 or 0.5 is exact in fp16.
  const auto to_float = [](uint16_t h) {
    const int exponent = (h >> 10) & 0x1f;
    const int mantissa = h & 0x3ff;
    if (exponent == 0) return std::ldexp(static_cast<float>(mantissa), -24);
    return std::ldexp(static_cast<float>(mantissa | 0x400), exponent - 25);
  };
  for (uint32_t i = 0; i < half.size(); ++i) {
    ASSERT_EQ(to_float(half[i]), source[i] * gain[i % 4]) << "component " << i;
  }
}

}  // namespace
}  // namespace sss::vk
