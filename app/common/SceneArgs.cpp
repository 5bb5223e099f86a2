#include "SceneArgs.h"

#include "CliSupport.h"

#include "scene/BuiltinScenes.h"

#include <utility>

namespace sss::app {

std::variant<scene::Scene, int> load_cli_scene(const std::string& tool, const std::string& name,
                                               const MaterialOverrideArgs& material,
                                               const EnvironmentArgs& environment, std::uint32_t height) {
  auto loaded = scene::load_scene(name);
  if (auto* e = std::get_if<scene::LoadError>(&loaded)) return input_error(tool, e->what());
  scene::Scene s = std::move(std::get<scene::Scene>(loaded));
  scene::add_camera_if_missing(s);
  scene::add_light_if_missing(s);
  auto overridden = apply_material_overrides(s, material);
  if (auto* e = std::get_if<FieldError>(&overridden)) return usage_error(tool, e->what());
  if (auto e = apply_environment(s, environment))
    return e->file ? input_error(tool, e->message) : usage_error(tool, e->message);
  add_material_warnings(s, height);
  print_messages(tool, "warning", s.warnings);
  return s;
}

}  // namespace sss::app
