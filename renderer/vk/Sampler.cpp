#include "renderer/vk/Sampler.h"

#include "renderer/vk/Check.h"
#include "renderer/vk/Context.h"

#include <algorithm>

namespace sss::vk {

SamplerHandle create_sampler(const Context& context, const SamplerDesc& desc) {
  const DeviceInfo& device = context.info();
  VkSamplerCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  info.magFilter = desc.filter;
  info.minFilter = desc.filter;
  info.mipmapMode = desc.mipmap;
  info.addressModeU = desc.address;
  info.addressModeV = desc.address;
  info.addressModeW = desc.address;
  info.borderColor = desc.border;
  if (desc.max_anisotropy > 1.0f && device.sampler_anisotropy) {
    info.anisotropyEnable = VK_TRUE;
    info.maxAnisotropy = std::min(desc.max_anisotropy, device.limits.maxSamplerAnisotropy);
  } else {
    info.maxAnisotropy = 1.0f;
  }
  info.compareEnable = desc.compare ? VK_TRUE : VK_FALSE;
  info.compareOp = desc.compare_op;
  info.minLod = 0.0f;
  info.maxLod = VK_LOD_CLAMP_NONE;
  VkSampler sampler = VK_NULL_HANDLE;
  VK_CHECK(vkCreateSampler(context.device(), &info, nullptr, &sampler));
  if (!desc.name.empty()) context.set_object_name(VK_OBJECT_TYPE_SAMPLER, sampler, desc.name);
  return SamplerHandle(context.device(), sampler);
}

}  // namespace sss::vk
