// GpuScene: the scene's meshes in device-local vertex and index buffers, and the draw of
// every instance with its DrawPush (model matrix, material index, roughness, colour).
// The G-buffer and the shadow maps draw the same list.
#pragma once

#include "renderer/scene/Scene.h"
#include "renderer/vk/Buffer.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace sss::vk {
class Context;
}

namespace sss::renderer {

struct GpuVertex {
  float position[3];
  float normal[3];
};

class GpuScene {
 public:
  GpuScene(const vk::Context& context, const scene::Scene& scene);

  // Binds the vertex/index buffers and draws each instance; push constants go to
  // `layout` (vertex and fragment stages). light_index is written into DrawPush for the
  // shadow pass (ignored elsewhere).
  void draw(VkCommandBuffer cmd, VkPipelineLayout layout, int light_index = -1) const;

 private:
  struct MeshBuffers {
    vk::Buffer vertices;
    vk::Buffer indices;
    std::uint32_t index_count = 0;
    std::uint32_t material = 0;
  };
  std::vector<MeshBuffers> meshes_;
  std::vector<scene::Instance> instances_;
  std::vector<scene::Material> materials_;
};

}  // namespace sss::renderer
