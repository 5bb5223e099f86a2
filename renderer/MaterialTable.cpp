#include "renderer/MaterialTable.h"

#include "renderer/vk/Transfer.h"

#include "profiles/Fresnel.h"
#include "profiles/Profile.h"

#include <cmath>

#include <span>
#include <stdexcept>
#include <string>
#include <utility>

namespace sss::renderer {

MaterialData build_material_data(const scene::Scene& scene, int separable_taps,
                                 bool single_scattering) {
  return build_material_data(scene.materials, separable_taps, single_scattering);
}

shader::GpuMaterial encode(const scene::Material& m, const MaterialProfile* profile) {
  shader::GpuMaterial g{};  // {}: the scalars too are 0
  g.f0 = 0.04f * m.specular;
  g.metallic = m.metallic;
  g.roughness = m.roughness;
  g.total_reflectance = {1.0f, 1.0f, 1.0f};
  if (!m.sss.enabled || profile == nullptr) return g;
  const MaterialProfile& p = *profile;
  const auto rgb = [](const Rgb& v) { return shader::vec3{float(v[0]), float(v[1]), float(v[2])}; };
  if (p.transmittance) {
    g.slab_transmittance = rgb(p.transmittance->total);
    g.slab_thickness_mm = float(m.sss.effective_thickness_mm());
  }
  const Rgb eta = m.sss.medium.eta;  // the scale leaves η alone
  g.eta = rgb(eta);
  g.exit_norm = rgb({1.0 / profiles::fresnel_exit_normalization(eta[0]),
                     1.0 / profiles::fresnel_exit_normalization(eta[1]),
                     1.0 / profiles::fresnel_exit_normalization(eta[2])});
  // S(1)'s coefficients: the real (not reduced) albedo and g; the scale changes neither.
  const profiles::Medium& medium = m.sss.medium;
  Rgb single{}, phase{};
  for (int c = 0; c < 3; ++c) {
    const double st = medium.sigma_a[c] + medium.sigma_s[c];
    single[c] = st > 0.0 ? medium.sigma_s[c] / st : 0.0;
    phase[c] = medium.g[c];
  }
  g.single_albedo = rgb(single);
  g.phase_g = rgb(phase);
  g.total_reflectance = rgb(p.kernel.total_reflectance);  // the profile's total_reflectance()
  g.scatters = 1;
  const auto count = p.fit.variances_mm2.size();
  g.gaussian_count = int(count);  // read by the shaders only; the CPU asks MaterialData
  for (std::size_t i = 0; i < count; ++i) {
    float* v = &g.variances[i / 4].x;
    v[i % 4] = float(p.fit.variances_mm2[i]);
    g.gauss_weights[i] = {float(p.fit.weights[i][0]), float(p.fit.weights[i][1]),
                          float(p.fit.weights[i][2]), 0.0f};
  }
  g.pre_post = m.sss.albedo_mode == scene::AlbedoMode::PrePost ? 1 : 0;
  g.separable_taps = int(p.kernel.offsets_mm.size());
  g.range_mm = float(p.kernel.range_mm);
  for (std::size_t i = 0; i < p.kernel.offsets_mm.size(); ++i)
    g.taps[i] = {float(p.kernel.weights[i][0]), float(p.kernel.weights[i][1]),
                 float(p.kernel.weights[i][2]), float(p.kernel.offsets_mm[i])};
  return g;
}

namespace {

MaterialData build(const std::vector<scene::Material>& materials, int separable_taps,
                   bool single_scattering, const MaterialData* previous,
                   const std::vector<bool>* reuse) {
  if (materials.size() > shader::kMaxMaterials)
    throw std::invalid_argument("the scene has " + std::to_string(materials.size()) +
                                " materials; the renderer supports " +
                                std::to_string(shader::kMaxMaterials));
  if (separable_taps < 3 || separable_taps % 2 == 0 ||
      separable_taps > static_cast<int>(shader::kMaxTaps))
    throw std::invalid_argument("separable taps must be odd, 3.." +
                                std::to_string(shader::kMaxTaps));
  const bool can_reuse = previous != nullptr && reuse != nullptr &&
                         previous->separable_taps == separable_taps &&
                         previous->single_scattering == single_scattering &&
                         previous->profiles.size() == materials.size() &&
                         reuse->size() == materials.size();
  MaterialData data;
  data.separable_taps = separable_taps;
  data.single_scattering = single_scattering;
  profiles::ModelOptions model_options;
  model_options.single_scattering_apart = single_scattering;
  for (std::size_t index = 0; index < materials.size(); ++index) {
    const scene::Material& m = materials[index];
    std::optional<MaterialProfile> profile;
    if (m.sss.enabled) {
      if (can_reuse && (*reuse)[index] && previous->profiles[index]) {
        profile = *previous->profiles[index];
      } else {
        const profiles::RgbProfile rgb = m.sss.profile(model_options);
        profiles::KernelFit k = profiles::fit_kernel(rgb, m.sss.gaussians, m.sss.transmits());
        profile = MaterialProfile{std::move(k.fit), profiles::make_separable_kernel(rgb, separable_taps),
                                  std::move(k.transmittance)};
      }
      data.max_gaussians = std::max(data.max_gaussians, MaterialData::gaussian_count(profile));
    }
    const shader::GpuMaterial g = encode(m, profile ? &*profile : nullptr);
    data.gpu.push_back(g);
    data.profiles.push_back(std::move(profile));
  }
  if (data.gpu.empty()) data.gpu.emplace_back();  // a storage buffer cannot be empty
  return data;
}

}  // namespace

MaterialData build_material_data(const std::vector<scene::Material>& materials,
                                 int separable_taps, bool single_scattering) {
  return build(materials, separable_taps, single_scattering, nullptr, nullptr);
}

MaterialData build_material_data(const std::vector<scene::Material>& materials,
                                 int separable_taps, const MaterialData& previous,
                                 const std::vector<bool>& reuse, bool single_scattering) {
  return build(materials, separable_taps, single_scattering, &previous, &reuse);
}

MaterialTable::MaterialTable(const vk::Context& context, const scene::Scene& scene,
                             int separable_taps, bool single_scattering)
    : data_(build_material_data(scene, separable_taps, single_scattering)),
      buffer_(context, {data_.gpu.size() * sizeof(shader::GpuMaterial),
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        vk::MemoryUsage::DeviceLocal, "materials"}) {
  vk::upload_buffer(context, buffer_, std::span<const shader::GpuMaterial>(data_.gpu));
}

void MaterialTable::replace(const vk::Context& context, MaterialData data) {
  if (data.gpu.size() != data_.gpu.size())
    throw std::invalid_argument("MaterialTable: " + std::to_string(data.gpu.size()) +
                                " materials replace " + std::to_string(data_.gpu.size()));
  vk::upload_buffer(context, buffer_, std::span<const shader::GpuMaterial>(data.gpu));
  data_ = std::move(data);
}

}  // namespace sss::renderer
