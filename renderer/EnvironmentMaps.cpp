#include "renderer/EnvironmentMaps.h"

#include "scene/SplitSum.h"
#include "renderer/vk/Context.h"
#include "renderer/vk/Transfer.h"

#include <cstdint>
#include <span>
#include <vector>

namespace sss::renderer {

EnvironmentMaps::EnvironmentMaps(const vk::Context& context) : context_(context) {
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  vk::ImageDesc levels(scene::kSpecularWidth, scene::kSpecularHeight, VK_FORMAT_R32G32B32A32_SFLOAT, usage,
                       "environment specular");
  levels.array_layers = scene::kSpecularLevels;
  levels.view_type = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
  specular_ = vk::Image(context, levels);
  dfg_ = vk::Image(context, {scene::kDfgSize, scene::kDfgSize, VK_FORMAT_R32G32_SFLOAT, usage, "dfg"});
  // Zeros until an environment needs the table: building it takes ~0.16 s, which every
  // renderer without an environment (most tests) would pay at start-up.
  const std::vector<glm::vec2> zeros(std::size_t(scene::kDfgSize) * scene::kDfgSize, glm::vec2(0.0f));
  vk::upload_image(context, dfg_, std::as_bytes(std::span(zeros)), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

void EnvironmentMaps::upload(const std::optional<scene::Environment>& environment) {
  if (environment && !dfg_uploaded_) {
    const std::vector<glm::vec2>& table = scene::dfg_table();
    vk::upload_image(context_, dfg_, std::as_bytes(std::span(table)), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    dfg_uploaded_ = true;
  }
  const std::size_t texels = std::size_t(scene::kSpecularWidth) * scene::kSpecularHeight * scene::kSpecularLevels;
  std::vector<float> rgba(texels * 4, 0.0f);
  if (environment && environment->specular.size() == texels)
    for (std::size_t i = 0; i < texels; ++i)
      for (int c = 0; c < 3; ++c) rgba[i * 4 + c] = environment->specular[i][c];
  vk::upload_image(context_, specular_, std::as_bytes(std::span(rgba)), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);

  const bool image = environment && !environment->uniform();
  const std::uint32_t w = image ? std::uint32_t(environment->width) : 1;
  const std::uint32_t h = image ? std::uint32_t(environment->height) : 1;
  std::vector<float> radiance(std::size_t(w) * h * 4, 0.0f);
  for (std::size_t i = 0; i < std::size_t(w) * h; ++i)
    for (int c = 0; c < 3; ++c)
      radiance[i * 4 + c] = image ? environment->image[i][c] : environment ? environment->colour[c] : 0.0f;
  if (!background_ || background_.width() != w || background_.height() != h) {
    vk::ImageDesc desc(w, h, VK_FORMAT_R32G32B32A32_SFLOAT,
                       VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, "environment background");
    desc.view_type = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    background_ = vk::Image(context_, desc);
  }
  vk::upload_image(context_, background_, std::as_bytes(std::span(radiance)), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

}  // namespace sss::renderer
