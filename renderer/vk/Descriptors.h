// Descriptor set layouts, pools and updates, kept explicit: a pass lists its bindings
// once (the layout), the pool is sized from that list, and each frame's set is written
// with the resources by binding number.
//
//   DescriptorSetLayoutBuilder bindings;
//   bindings.add(0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT)
//           .add(1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT);
//   auto layout = bindings.build(ctx, "sss blur");
//   DescriptorPool pool(ctx, bindings, kFramesInFlight);
//   VkDescriptorSet set = pool.allocate(layout.get());
//   DescriptorWriter(set).storage_image(0, output).combined_image(1, input, sampler).update(ctx);
#pragma once

#include "renderer/vk/Handle.h"

#include "renderer/vk/ShaderBinding.h"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace sss::vk {

class Buffer;
class Context;
class Image;

class DescriptorSetLayoutBuilder {
 public:
  DescriptorSetLayoutBuilder& add(uint32_t binding, VkDescriptorType type,
                                  VkShaderStageFlags stages, uint32_t count = 1);
  // Every binding one shader uses (its generated kAll). A binding that another shader of
  // the same pipeline already added gains this one's stages; a different type or count
  // there throws std::logic_error (the two shaders disagree).
  DescriptorSetLayoutBuilder& add(std::span<const ShaderBinding> shader);
  DescriptorSetLayoutHandle build(const Context& context, std::string_view name = {}) const;
  const std::vector<VkDescriptorSetLayoutBinding>& bindings() const { return bindings_; }

 private:
  std::vector<VkDescriptorSetLayoutBinding> bindings_;
};

class DescriptorPool {
 public:
  DescriptorPool(const Context& context, uint32_t max_sets,
                 std::span<const VkDescriptorPoolSize> sizes, std::string_view name = {});
  // Room for `sets` sets of the layout described by `bindings`.
  DescriptorPool(const Context& context, const DescriptorSetLayoutBuilder& bindings, uint32_t sets,
                 std::string_view name = {});

  VkDescriptorPool handle() const { return pool_.get(); }
  // Throws VulkanError (VK_ERROR_OUT_OF_POOL_MEMORY) when the pool is full.
  VkDescriptorSet allocate(VkDescriptorSetLayout layout);
  // Frees every set allocated from the pool at once (none may be in use by the GPU).
  void reset();

 private:
  DescriptorPoolHandle pool_;
};

// The device's alignment for the offset of a uniform (minUniformBufferOffsetAlignment)
// or storage (minStorageBufferOffsetAlignment) buffer descriptor; 1 for other types. Code
// that places several ranges in one buffer rounds their offsets up to it (align_up).
VkDeviceSize descriptor_offset_alignment(const Context& context, VkDescriptorType type);

// Collects writes to one set and applies them in one vkUpdateDescriptorSets. update()
// refuses (std::invalid_argument naming the binding, the limit and its value) a buffer
// range whose offset breaks the device's offset alignment or whose size exceeds
// maxUniformBufferRange / maxStorageBufferRange.
class DescriptorWriter {
 public:
  explicit DescriptorWriter(VkDescriptorSet set) : set_(set) {}

  DescriptorWriter& buffer(uint32_t binding, VkDescriptorType type,
                           const VkDescriptorBufferInfo& info, uint32_t element = 0);
  DescriptorWriter& image(uint32_t binding, VkDescriptorType type,
                          const VkDescriptorImageInfo& info, uint32_t element = 0);

  DescriptorWriter& uniform_buffer(uint32_t binding, const Buffer& buffer, VkDeviceSize offset = 0,
                                   VkDeviceSize range = VK_WHOLE_SIZE);
  DescriptorWriter& storage_buffer(uint32_t binding, const Buffer& buffer, VkDeviceSize offset = 0,
                                   VkDeviceSize range = VK_WHOLE_SIZE);
  // Storage images are read and written in the GENERAL layout.
  DescriptorWriter& storage_image(uint32_t binding, const Image& image);
  DescriptorWriter& sampled_image(uint32_t binding, const Image& image,
                                  VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  DescriptorWriter& combined_image(uint32_t binding, const Image& image, VkSampler sampler,
                                   VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  DescriptorWriter& sampler(uint32_t binding, VkSampler sampler);

  void update(const Context& context) const;

 private:
  struct Pending {
    uint32_t binding;
    uint32_t element;
    VkDescriptorType type;
    bool is_image;
    std::size_t index;  // into buffers_ or images_
    VkDeviceSize range = 0;  // bytes the descriptor covers; 0: not known (VK_WHOLE_SIZE)
  };
  void check_buffer_limits(const Context& context, const Pending& p) const;

  VkDescriptorSet set_;
  std::vector<Pending> writes_;
  std::vector<VkDescriptorBufferInfo> buffers_;
  std::vector<VkDescriptorImageInfo> images_;
};

}  // namespace sss::vk
