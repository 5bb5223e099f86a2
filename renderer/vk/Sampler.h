// Samplers: a plain description with defaults (clamped bilinear), and a comparison mode
// for shadow maps (sampler2DShadow).
#pragma once

#include "renderer/vk/Handle.h"

#include <vulkan/vulkan.h>

#include <string>

namespace sss::vk {

class Context;

struct SamplerDesc {
  SamplerDesc() = default;
  SamplerDesc(VkFilter min_mag, VkSamplerMipmapMode mip,
              VkSamplerAddressMode address_mode = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE)
      : filter(min_mag), mipmap(mip), address(address_mode) {}

  VkFilter filter = VK_FILTER_LINEAR;
  VkSamplerMipmapMode mipmap = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  VkSamplerAddressMode address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VkBorderColor border = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;  // outside a shadow map: lit
  // > 1 asks for anisotropic filtering; clamped to the device limit, ignored when the
  // device lacks samplerAnisotropy.
  float max_anisotropy = 1.0f;
  bool compare = false;  // depth comparison (shadow maps)
  VkCompareOp compare_op = VK_COMPARE_OP_LESS_OR_EQUAL;
  std::string name;
};

SamplerHandle create_sampler(const Context& context, const SamplerDesc& desc = {});

}  // namespace sss::vk
