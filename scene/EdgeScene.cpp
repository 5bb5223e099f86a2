// builtin:edge, the decisive end-to-end scene (DESIGN.md §7, issue 3).
//
// Geometry: a 200 x 200 mm slab, 50 mm thick, whose top face is the plane y = 0 (normal
// +y): optically thick for every preset, and wide enough that its sides never enter the
// view or the profile's support. Material: the preset, roughness 1, specular 0 (no
// specular lobe, all light enters), no texture, albedo mode post-scatter with base
// colour 1, so the exitant flux is exactly M(x) = (R * E)(x).
// Camera: orthographic, looking down -y, image right = +x, image up = -z; xmag is the
// half-width in scene units (20 mm = 0.02 m), and ymag follows the image aspect
// (Camera::ortho_half_extent), so z has the same mm per pixel.
// Light: directional, travelling -y (normal incidence), intensity = irradiance = 1,
// masked by the half-space x < 0 (mask (1, 0, 0, 0)): a sharp edge at x = 0 that does
// not depend on a shadow map's resolution.
#include "scene/BuiltinScenes.h"

#include "scene/Shapes.h"

namespace sss::scene {

Scene edge_scene(const EdgeOptions& options) {
  Scene s;
  s.name = "builtin:edge";
  s.mm_per_unit = 1000.0;
  const float mm = float(1.0 / s.mm_per_unit);  // one mm in scene units

  Material slab;
  slab.name = options.preset + " slab";
  slab.base_color = glm::vec4(1.0f);
  slab.metallic = 0.0f;
  slab.roughness = 1.0f;
  slab.specular = 0.0f;
  slab.sss = preset_sss_material(options.preset);
  s.materials.push_back(slab);

  Mesh box = make_box({-100 * mm, -50 * mm, -100 * mm}, {100 * mm, 0.0f, 100 * mm}, 0);
  box.name = "slab";
  s.meshes.push_back(std::move(box));
  s.instances.push_back({0, glm::mat4(1.0f), "slab"});

  Camera cam;
  cam.name = "edge (orthographic, straight down)";
  cam.projection = Projection::Orthographic;
  cam.xmag = float(options.half_width_mm) * mm;
  cam.ymag = cam.xmag;  // for a square image; see Camera::ortho_half_extent
  cam.znear = 10 * mm;
  cam.zfar = 1000 * mm;
  cam.world = look_at_world({0.0f, 100 * mm, 0.0f}, glm::vec3(0.0f), {0.0f, 0.0f, -1.0f});
  s.cameras.push_back(cam);

  Light light = directional_light("edge light", {0.0f, -1.0f, 0.0f}, float(options.irradiance));
  light.mask = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);  // lit where x < 0
  s.lights.push_back(light);
  return s;
}

}  // namespace sss::scene
