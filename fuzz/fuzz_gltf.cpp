// sss_fuzz_gltf: a glTF or GLB file from anywhere (FuzzTargets.h).
#include "FuzzSupport.h"
#include "FuzzTargets.h"

#include "scene/GltfLoader.h"
#include "scene/UvAtlas.h"

#include <cmath>
#include <cstring>

namespace {

using sss::fuzz::fuzz_check;

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// What the renderer relies on in a scene the loader accepted (Scene.h, Mesh.h).
void check_scene(const sss::scene::Scene& s) {
  for (const auto& m : s.meshes) {
    const std::size_t n = m.positions.size();
    fuzz_check(m.indices.size() % 3 == 0, "mesh indices come in triangles");
    for (std::uint32_t i : m.indices) fuzz_check(i < n, "mesh index < vertex count");
    fuzz_check(m.normals.size() == n, "one normal per position");
    fuzz_check(m.uv0.empty() || m.uv0.size() == n, "uv0 empty or one per position");
    fuzz_check(m.tangents.empty() || m.tangents.size() == n, "tangents empty or one per position");
    fuzz_check(m.uv_atlas.empty() || m.uv_atlas.size() == n, "uv_atlas empty or one per position");
    fuzz_check(m.material < s.materials.size(), "mesh material < material count");
    for (const auto& p : m.positions) fuzz_check(finite(p), "positions are finite");
    for (const auto& v : m.normals) fuzz_check(finite(v), "normals are finite");
  }
  for (const auto& inst : s.instances) {
    fuzz_check(inst.mesh < s.meshes.size(), "instance mesh < mesh count");
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) fuzz_check(std::isfinite(inst.world[c][r]), "instance transform is finite");
  }
  for (const auto& mat : s.materials) {
    if (mat.base_color_texture) fuzz_check(*mat.base_color_texture < s.textures.size(), "base colour texture index");
    if (mat.normal_texture) fuzz_check(*mat.normal_texture < s.textures.size(), "normal texture index");
  }
  for (const auto& t : s.textures) {
    fuzz_check(t.image != nullptr, "texture has an image");
    fuzz_check(t.image->pixels.size() == std::size_t{t.image->width} * t.image->height * 4,
               "texture pixels are width * height * 4");
  }
}

}  // namespace

int sss_fuzz_gltf(const std::uint8_t* data, std::size_t size) {
  // load_gltf takes a path: the bytes go to the process's private scratch folder. The
  // loader parses GLB by magic, whatever the name, so the name only follows the magic.
  const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string name = glb ? "input.glb" : "input.gltf";
  const std::string path = sss::fuzz::write_scratch(name, data, size);

  // Small caps keep every run fast; the checks are the same as with the defaults.
  sss::scene::LoadOptions options;
  options.max_file_bytes = 1u << 20;
  options.max_json_bytes = 1u << 20;
  options.max_external_bytes = 1u << 20;
  options.max_scene_bytes = 64u << 20;
  options.max_nodes = 4096;
  options.image_limits.max_side = 1024;
  options.image_limits.max_pixels = 1u << 20;
  auto loaded = sss::scene::load_gltf(path, options);
  sss::fuzz::remove_scratch(name);

  if (auto* scene = std::get_if<sss::scene::Scene>(&loaded)) {
    check_scene(*scene);
    // What load_scene does next for the texture-space path (BuiltinScenes.cpp).
    sss::scene::ensure_sss_atlases(*scene, {1024, 12});
    check_scene(*scene);
    sss::fuzz::count_accepted();
  }
  return 0;
}
