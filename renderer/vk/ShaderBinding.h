// One descriptor binding as a shader declares it, reflected at build time
// (cmake/ShaderReflect.cmake writes `shaders/NAME.STAGE.bindings.h`, one constant per
// binding the shader uses). It converts to its binding number, so a DescriptorWriter
// call names the binding (`.storage_image(lighting_comp::irradiance_img, image)`), and
// DescriptorSetLayoutBuilder::add(kAll) builds the set layout from the shaders.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>

namespace sss::vk {

struct ShaderBinding {
  uint32_t binding;
  VkDescriptorType type;
  uint32_t count;            // array size (1 for a single descriptor)
  VkShaderStageFlags stages;  // the stages of the shader it was reflected from

  constexpr operator uint32_t() const { return binding; }
};

}  // namespace sss::vk
