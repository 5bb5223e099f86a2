#include "renderer/GpuScene.h"

#include "renderer/CameraSetup.h"
#include "renderer/vk/Transfer.h"
#include "shaders/shared/frame.h"

#include <span>

namespace sss::renderer {

GpuScene::GpuScene(const vk::Context& context, const scene::Scene& scene)
    : instances_(scene.instances), materials_(scene.materials) {
  for (const scene::Mesh& mesh : scene.meshes) {
    std::vector<GpuVertex> vertices(mesh.positions.size());
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      const glm::vec3& p = mesh.positions[i];
      const glm::vec3& n = mesh.normals[i];
      vertices[i] = {{p.x, p.y, p.z}, {n.x, n.y, n.z}};
    }
    MeshBuffers b;
    b.index_count = static_cast<std::uint32_t>(mesh.indices.size());
    b.material = mesh.material;
    if (!vertices.empty() && !mesh.indices.empty()) {
      b.vertices = vk::Buffer(context, {vertices.size() * sizeof(GpuVertex),
                                        VK_BUFFER_USAGE_VERTEX_BUFFER_BIT |
                                            VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                        vk::MemoryUsage::DeviceLocal, mesh.name + " vertices"});
      vk::upload_buffer(context, b.vertices, std::span<const GpuVertex>(vertices));
      b.indices = vk::Buffer(context, {mesh.indices.size() * sizeof(std::uint32_t),
                                       VK_BUFFER_USAGE_INDEX_BUFFER_BIT |
                                           VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                       vk::MemoryUsage::DeviceLocal, mesh.name + " indices"});
      vk::upload_buffer(context, b.indices, std::span<const std::uint32_t>(mesh.indices));
    }
    meshes_.push_back(std::move(b));
  }
}

void GpuScene::draw(VkCommandBuffer cmd, VkPipelineLayout layout, int light_index) const {
  for (const scene::Instance& instance : instances_) {
    const MeshBuffers& mesh = meshes_[instance.mesh];
    if (mesh.index_count == 0) continue;
    const scene::Material& material = materials_[mesh.material];
    shader::DrawPush push;
    push.model = to_shader(instance.world);
    push.material = {float(mesh.material), float(light_index), material.roughness, 0.0f};
    push.base_color = {material.base_color.r, material.base_color.g, material.base_color.b,
                       material.base_color.a};
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(push), &push);
    const VkBuffer buffers[] = {mesh.vertices.handle()};
    const VkDeviceSize offsets[] = {0};
    vkCmdBindVertexBuffers(cmd, 0, 1, buffers, offsets);
    vkCmdBindIndexBuffer(cmd, mesh.indices.handle(), 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, mesh.index_count, 1, 0, 0, 0);
  }
}

}  // namespace sss::renderer
