// The Tools window's Export: the materials' extras.sss, their kernels for engines.
#include "Tools.h"

#include "profiles/EngineProfiles.h"

#include "CliSupport.h"
#include "InputFiles.h"
#include "PanelWindow.h"
#include "ToolsText.h"

#include "renderer/FrameTargets.h"
#include "renderer/Renderer.h"
#include "image/AtomicFile.h"
#include "image/HeatMap.h"
#include "image/Tonemap.h"
#include "scene/GltfExport.h"
#include "scene/SssExtras.h"
#include "renderer/vk/Transfer.h"
#include "profiles/KernelExport.h"

#include <imgui.h>
#include <imgui_internal.h>  // the title bar's rect (a click on it opens the window)
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>
#include <variant>

namespace sss::app {

using namespace tools_text;

namespace {

// A C identifier for the header's prefix.
std::string c_identifier(std::string name) {
  for (char& c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) c = '_';
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) name.insert(0, "k_");
  return name;
}

std::string sanitized(std::string name) {
  for (char& c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_')) c = '_';
  return name.empty() ? std::string("material") : name;
}

// "skin (preset skin1, mc-table, scale 1)": what the kernel files record.
std::string describe(const scene::Material& m) {
  std::ostringstream out;
  out << "material '" << m.name << "': ";
  if (const auto* p = std::get_if<scene::PresetSource>(&m.sss.source))
    out << "preset " << p->name;
  else if (std::holds_alternative<scene::CoefficientSource>(m.sss.source))
    out << "coefficients";
  else if (const auto* o = std::get_if<scene::OpenPbrSource>(&m.sss.source))
    out << (o->standard_surface ? "Standard Surface" : "OpenPBR") << " subsurface ("
        << profiles::albedo_inversion_name(o->inversion) << " inversion)";
  else
    out << "artist colour + mfp";
  const profiles::Medium e = m.sss.effective_medium();
  out << ", scale " << m.sss.scale << "; effective sigma_a [" << e.sigma_a[0] << ", "
      << e.sigma_a[1] << ", " << e.sigma_a[2] << "] sigma_s [" << e.sigma_s[0] << ", "
      << e.sigma_s[1] << ", " << e.sigma_s[2] << "] /mm";
  return out.str();
}

}  // namespace

std::string write_new_file(const std::string& path, const std::string& bytes, bool replace,
                           const std::vector<std::filesystem::path>* inputs) {
  if (path.empty()) return "no file name given";
  if (inputs != nullptr)
    if (auto refused = refuse_input_overwrite(path, *inputs)) return *refused;
  if (!replace && exists(path))
    return path + " exists: tick 'replace existing files' or change the name";
  try {
    image::write_file_atomically(path, bytes);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "saved " + path;
}

std::string export_materials(const LiveState& live, const std::string& path, bool replace) {
  if (path.empty()) return "no file name given";
  if (is_builtin(live.source)) {
    nlohmann::ordered_json doc;
    doc["scene"] = live.source;
    doc["materials"] = nlohmann::ordered_json::array();
    for (const scene::Material& m : live.materials) {
      nlohmann::ordered_json entry = {{"name", m.name}};
      if (m.sss.enabled)
        entry["extras"]["sss"] = nlohmann::ordered_json::parse(scene::sss_extras_json(m.sss).dump());
      doc["materials"].push_back(entry);
    }
    return write_new_file(path, doc.dump(2) + "\n", replace, live.inputs);
  }
  if (live.inputs != nullptr)
    if (auto refused = refuse_input_overwrite(path, *live.inputs)) return *refused;
  auto bytes = scene::gltf_with_sss_materials(live.source, live.materials, path);
  if (auto* e = std::get_if<scene::LoadError>(&bytes)) return e->what();
  return write_new_file(path, std::get<std::string>(bytes), replace, live.inputs);
}

std::string export_kernel(const renderer::Renderer& r, const LiveState& live, std::size_t material,
                          const std::string& path, bool replace) {
  if (material >= live.materials.size() || material >= r.materials().profiles.size() ||
      !r.materials().profiles[material])
    return "material " + std::to_string(material) + " has no fitted SSS profile";
  const renderer::MaterialProfile& profile = *r.materials().profiles[material];
  const scene::Material& m = live.materials[material];
  const profiles::KernelInfo info{std::string(profiles::model_name(m.sss.model)), describe(m)};
  std::string bytes;
  try {
    if (lower_extension(path) == ".h")
      bytes = profiles::kernel_to_c_header(
          profile.fit, info, &profile.kernel,
          c_identifier(std::filesystem::path(path).stem().string()));
    else
      bytes = profiles::kernel_to_json(profile.fit, info, &profile.kernel);
  } catch (const std::exception& e) {
    return e.what();
  }
  return write_new_file(path, bytes, replace, live.inputs);
}

std::string export_engine_profile(const LiveState& live, std::size_t material, const std::string& base,
                                  bool hdrp, bool replace) {
  if (material >= live.materials.size() || !live.materials[material].sss.enabled)
    return "material " + std::to_string(material) + " has no subsurface scattering";
  const scene::Material& m = live.materials[material];
  if (!m.sss.layers.empty())
    return "material '" + m.name + "' is a stack of layers: the engines' profiles hold one medium "
           "(save its kernel instead)";
  profiles::EngineProfileSource es;
  es.name = m.name.empty() ? "material_" + std::to_string(material) : m.name;
  es.medium = m.sss.effective_medium();
  es.pre_post_albedo = m.sss.albedo_mode == scene::AlbedoMode::PrePost;
  es.world_scale = hdrp ? std::max(0.001, (live.scene ? live.scene->mm_per_unit : 1000.0) / 1000.0) : 0.1;
  std::string first, first_bytes, second, second_bytes;
  profiles::BurleyShapeFit fit;
  try {
    const profiles::RgbProfile profile = m.sss.profile();
    if (hdrp) {
      const auto p = profiles::hdrp_diffusion_profile(es, profile);
      first = base + ".asset";
      first_bytes = p.asset;
      second = first + ".meta";
      second_bytes = p.meta;
      fit = p.fit;
    } else {
      const auto p = profiles::unreal_subsurface_profile(es, profile);
      first = base + "-unreal.json";
      first_bytes = p.json;
      second = base + "-unreal.py";
      second_bytes = p.python;
      fit = p.fit;
    }
  } catch (const std::exception& e) {
    return e.what();
  }
  if (!replace)
    for (const std::string& f : {first, second})
      if (std::filesystem::exists(f)) return f + " exists (tick 'replace existing files')";
  std::string msg = write_new_file(first, first_bytes, replace, live.inputs);
  if (msg.rfind("saved ", 0) != 0) return msg;
  const std::string msg2 = write_new_file(second, second_bytes, replace, live.inputs);
  if (msg2.rfind("saved ", 0) != 0) {
    std::error_code ec;
    std::filesystem::remove(first, ec);
    return msg2;
  }
  char err[96];
  std::snprintf(err, sizeof err, "; Burley fit error %.1f/%.1f/%.1f%%", 100 * fit.relative_error[0],
                100 * fit.relative_error[1], 100 * fit.relative_error[2]);
  return "saved " + first + " and " + second + err;
}

ViewerTools::KernelSaves ViewerTools::draw_kernel_exports(const LiveState& live, const std::vector<int>& sss) {
  KernelSaves saves;
  if (sss.empty()) return saves;
  kernel_material_ = std::clamp(kernel_material_, 0, int(sss.size()) - 1);
  const scene::Material& km = live.materials[std::size_t(sss[std::size_t(kernel_material_)])];
  if (ImGui::BeginCombo("kernel of", km.name.c_str())) {
    for (int k = 0; k < int(sss.size()); ++k)
      if (ImGui::Selectable(live.materials[std::size_t(sss[std::size_t(k)])].name.c_str(),
                            k == kernel_material_)) {
        kernel_material_ = k;
        kernel_path_[0] = '\0';
      }
    ImGui::EndCombo();
  }
  if (kernel_path_[0] == '\0')
    copy_to(kernel_path_, sizeof kernel_path_,
            scene::unused_path(sanitized(file_stem(live.source) + "-" + km.name) + "-kernel"));
  ImGui::InputText("##kernel", kernel_path_, sizeof kernel_path_);
  ImGui::TextDisabled("(.json and .h are added)");
  saves.json = ImGui::Button("Save kernel JSON");
  ImGui::SameLine();
  saves.header = ImGui::Button("Save C header");
  saves.hdrp = ImGui::Button("Save HDRP profile");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Unity HDRP Diffusion Profile (.asset + .meta): Burley's d fitted to this "
                      "material's profile, its ior, and for a slab its thickness and tint");
  ImGui::SameLine();
  saves.unreal = ImGui::Button("Save Unreal profile");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Unreal Subsurface Profile settings (-unreal.json) and an editor Python "
                      "script that creates the asset (-unreal.py)");
  return saves;
}

void ViewerTools::draw_export(const renderer::Renderer& r, const LiveState& live) {
  if (!ImGui::CollapsingHeader("Export")) return;
  const bool builtin = is_builtin(live.source);
  ImGui::TextWrapped(builtin ? "SSS blocks of every material (a built-in scene has no glTF)"
                             : "A copy of the glTF with every material's extras.sss");
  ImGui::InputText("##gltf", gltf_path_, sizeof gltf_path_);
  ImGui::SameLine();
  const bool save_gltf = ImGui::Button(builtin ? "Save JSON" : "Save glTF");

  std::vector<int> sss;
  for (std::size_t i = 0; i < live.materials.size(); ++i)
    if (live.materials[i].sss.enabled) sss.push_back(int(i));
  const KernelSaves saves = draw_kernel_exports(live, sss);
  ImGui::Checkbox("replace existing files", &replace_);

  if (save_gltf) {
    const std::string out = gltf_path_;
    export_message_ = export_materials(live, out, replace_);
    if (export_message_.rfind("saved ", 0) == 0)  // the next save gets a new name
      copy_to(gltf_path_, sizeof gltf_path_,
              builtin ? scene::unused_path(out) : scene::default_export_path(live.source));
  }
  if (saves.json || saves.header) {
    const std::size_t index = std::size_t(sss[std::size_t(kernel_material_)]);
    export_message_ = export_kernel(r, live, index,
                                    std::string(kernel_path_) + (saves.json ? ".json" : ".h"), replace_);
  }
  if (saves.hdrp || saves.unreal)
    export_message_ = export_engine_profile(live, std::size_t(sss[std::size_t(kernel_material_)]),
                                            kernel_path_, saves.hdrp, replace_);
  if (!export_message_.empty()) ImGui::TextWrapped("%s", export_message_.c_str());
}

}  // namespace sss::app
