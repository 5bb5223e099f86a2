#include "renderer/vk/Descriptors.h"

#include "renderer/vk/Buffer.h"
#include "renderer/vk/Check.h"
#include "renderer/vk/Context.h"
#include "renderer/vk/Image.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>

namespace sss::vk {

DescriptorSetLayoutBuilder& DescriptorSetLayoutBuilder::add(uint32_t binding, VkDescriptorType type,
                                                            VkShaderStageFlags stages,
                                                            uint32_t count) {
  for (const VkDescriptorSetLayoutBinding& b : bindings_) {
    if (b.binding == binding) {
      throw std::logic_error("descriptor set layout: binding " + std::to_string(binding) +
                             " added twice");
    }
  }
  bindings_.push_back({binding, type, count, stages, nullptr});
  return *this;
}

DescriptorSetLayoutBuilder& DescriptorSetLayoutBuilder::add(std::span<const ShaderBinding> shader) {
  for (const ShaderBinding& s : shader) {
    const auto same = std::find_if(bindings_.begin(), bindings_.end(),
                                   [&](const VkDescriptorSetLayoutBinding& b) {
                                     return b.binding == s.binding;
                                   });
    if (same == bindings_.end()) {
      bindings_.push_back({s.binding, s.type, s.count, s.stages, nullptr});
      continue;
    }
    if (same->descriptorType != s.type || same->descriptorCount != s.count)
      throw std::logic_error("descriptor set layout: binding " + std::to_string(s.binding) +
                             " has another type or count in another stage");
    same->stageFlags |= s.stages;
  }
  return *this;
}

DescriptorSetLayoutHandle DescriptorSetLayoutBuilder::build(const Context& context,
                                                            std::string_view name) const {
  VkDescriptorSetLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  info.bindingCount = static_cast<uint32_t>(bindings_.size());
  info.pBindings = bindings_.data();
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorSetLayout(context.device(), &info, nullptr, &layout));
  if (!name.empty()) context.set_object_name(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, layout, name);
  return DescriptorSetLayoutHandle(context.device(), layout);
}

DescriptorPool::DescriptorPool(const Context& context, uint32_t max_sets,
                               std::span<const VkDescriptorPoolSize> sizes, std::string_view name) {
  VkDescriptorPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  info.maxSets = max_sets;
  info.poolSizeCount = static_cast<uint32_t>(sizes.size());
  info.pPoolSizes = sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorPool(context.device(), &info, nullptr, &pool));
  pool_ = DescriptorPoolHandle(context.device(), pool);
  if (!name.empty()) context.set_object_name(VK_OBJECT_TYPE_DESCRIPTOR_POOL, pool, name);
}

namespace {
std::vector<VkDescriptorPoolSize> pool_sizes(const DescriptorSetLayoutBuilder& bindings,
                                             uint32_t sets) {
  std::map<VkDescriptorType, uint32_t> counts;
  for (const VkDescriptorSetLayoutBinding& b : bindings.bindings()) {
    counts[b.descriptorType] += b.descriptorCount * sets;
  }
  std::vector<VkDescriptorPoolSize> sizes;
  for (const auto& [type, count] : counts) sizes.push_back({type, count});
  return sizes;
}
}  // namespace

DescriptorPool::DescriptorPool(const Context& context, const DescriptorSetLayoutBuilder& bindings,
                               uint32_t sets, std::string_view name)
    : DescriptorPool(context, sets, pool_sizes(bindings, sets), name) {}

VkDescriptorSet DescriptorPool::allocate(VkDescriptorSetLayout layout) {
  VkDescriptorSetAllocateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  info.descriptorPool = pool_.get();
  info.descriptorSetCount = 1;
  info.pSetLayouts = &layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateDescriptorSets(pool_.device(), &info, &set));
  return set;
}

void DescriptorPool::reset() { VK_CHECK(vkResetDescriptorPool(pool_.device(), pool_.get(), 0)); }

DescriptorWriter& DescriptorWriter::buffer(uint32_t binding, VkDescriptorType type,
                                           const VkDescriptorBufferInfo& info, uint32_t element) {
  buffers_.push_back(info);
  writes_.push_back({binding, element, type, false, buffers_.size() - 1,
                     info.range == VK_WHOLE_SIZE ? 0 : info.range});
  return *this;
}

namespace {
// The bytes a descriptor of [offset, offset + range) of `b` covers.
VkDescriptorBufferInfo checked_range(uint32_t binding, const Buffer& b, VkDeviceSize offset,
                                     VkDeviceSize range) {
  if (offset >= b.size() || (range != VK_WHOLE_SIZE && range > b.size() - offset)) {
    throw std::out_of_range("descriptor binding " + std::to_string(binding) + ": range at " +
                            std::to_string(offset) + " is outside the buffer of " +
                            std::to_string(b.size()) + " bytes");
  }
  return b.descriptor(offset, range);
}
}  // namespace

VkDeviceSize descriptor_offset_alignment(const Context& context, VkDescriptorType type) {
  const VkPhysicalDeviceLimits& limits = context.info().limits;
  switch (type) {
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC:
      return std::max<VkDeviceSize>(1, limits.minUniformBufferOffsetAlignment);
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC:
      return std::max<VkDeviceSize>(1, limits.minStorageBufferOffsetAlignment);
    default: return 1;
  }
}

DescriptorWriter& DescriptorWriter::image(uint32_t binding, VkDescriptorType type,
                                          const VkDescriptorImageInfo& info, uint32_t element) {
  images_.push_back(info);
  writes_.push_back({binding, element, type, true, images_.size() - 1});
  return *this;
}

DescriptorWriter& DescriptorWriter::uniform_buffer(uint32_t binding, const Buffer& b,
                                                   VkDeviceSize offset, VkDeviceSize range) {
  buffer(binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, checked_range(binding, b, offset, range));
  writes_.back().range = range == VK_WHOLE_SIZE ? b.size() - offset : range;
  return *this;
}
DescriptorWriter& DescriptorWriter::storage_buffer(uint32_t binding, const Buffer& b,
                                                   VkDeviceSize offset, VkDeviceSize range) {
  buffer(binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, checked_range(binding, b, offset, range));
  writes_.back().range = range == VK_WHOLE_SIZE ? b.size() - offset : range;
  return *this;
}
DescriptorWriter& DescriptorWriter::storage_image(uint32_t binding, const Image& i) {
  return image(binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, i.descriptor(VK_IMAGE_LAYOUT_GENERAL));
}
DescriptorWriter& DescriptorWriter::sampled_image(uint32_t binding, const Image& i,
                                                  VkImageLayout layout) {
  return image(binding, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, i.descriptor(layout));
}
DescriptorWriter& DescriptorWriter::combined_image(uint32_t binding, const Image& i, VkSampler s,
                                                   VkImageLayout layout) {
  return image(binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, i.descriptor(layout, s));
}
DescriptorWriter& DescriptorWriter::sampler(uint32_t binding, VkSampler s) {
  return image(binding, VK_DESCRIPTOR_TYPE_SAMPLER, {s, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED});
}

void DescriptorWriter::check_buffer_limits(const Context& context, const Pending& p) const {
  const VkPhysicalDeviceLimits& limits = context.info().limits;
  const bool uniform = p.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER ||
                       p.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC;
  const bool storage = p.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER ||
                       p.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC;
  if (!uniform && !storage) return;
  const std::string where = "descriptor binding " + std::to_string(p.binding) + ": ";
  const VkDeviceSize alignment = descriptor_offset_alignment(context, p.type);
  const VkDeviceSize offset = buffers_[p.index].offset;
  if (offset % alignment != 0) {
    throw std::invalid_argument(
        where + (uniform ? "uniform" : "storage") + " buffer offset " + std::to_string(offset) +
        " is not a multiple of " +
        (uniform ? "minUniformBufferOffsetAlignment (" : "minStorageBufferOffsetAlignment (") +
        std::to_string(alignment) + ") of " + context.info().name);
  }
  const VkDeviceSize max_range = uniform ? limits.maxUniformBufferRange : limits.maxStorageBufferRange;
  if (p.range > max_range) {
    throw std::invalid_argument(where + std::to_string(p.range) + " bytes exceed " +
                                (uniform ? "maxUniformBufferRange (" : "maxStorageBufferRange (") +
                                std::to_string(max_range) + ") of " + context.info().name);
  }
}

void DescriptorWriter::update(const Context& context) const {
  // The info arrays are complete now, so the pointers into them are stable.
  std::vector<VkWriteDescriptorSet> writes;
  writes.reserve(writes_.size());
  for (const Pending& p : writes_) {
    VkWriteDescriptorSet w{};
    w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    w.dstSet = set_;
    w.dstBinding = p.binding;
    w.dstArrayElement = p.element;
    w.descriptorCount = 1;
    w.descriptorType = p.type;
    if (p.is_image) {
      w.pImageInfo = &images_[p.index];
    } else {
      w.pBufferInfo = &buffers_[p.index];
      check_buffer_limits(context, p);
    }
    writes.push_back(w);
  }
  vkUpdateDescriptorSets(context.device(), static_cast<uint32_t>(writes.size()), writes.data(), 0,
                         nullptr);
}

}  // namespace sss::vk
