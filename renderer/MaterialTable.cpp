#include "renderer/MaterialTable.h"

#include "renderer/vk/Transfer.h"

#include "profiles/Nnls.h"
#include "profiles/Profile.h"

#include <Eigen/Core>

#include <cmath>

#include <span>
#include <stdexcept>
#include <string>
#include <utility>

namespace sss::renderer {

MaterialData build_material_data(const scene::Scene& scene, int separable_taps) {
  return build_material_data(scene.materials, separable_taps);
}

TransmittanceFit fit_transmittance(const profiles::RgbProfile& rgb, const profiles::FitTarget& target,
                                   const std::vector<double>& variances_mm2) {
  const auto rows = static_cast<Eigen::Index>(target.r_mm.size());
  const auto n = static_cast<Eigen::Index>(variances_mm2.size());
  TransmittanceFit out;
  out.weights.assign(variances_mm2.size(), Rgb{});
  const Rgb total = rgb.total_transmittance();
  Eigen::MatrixXd A(rows + 1, n);
  Eigen::VectorXd b(rows + 1);
  // Rows weighted by √dr·r: the least squares of r(T − T̃) in dr, the fit's own norm. The
  // Gaussian rows are the same for every channel; only the energy row and b change.
  for (Eigen::Index j = 0; j < rows; ++j) {
    const double s = std::sqrt(target.dr[j]) * target.r_mm[j];
    for (Eigen::Index i = 0; i < n; ++i)
      A(j + 1, i) = s * profiles::gaussian_2d(variances_mm2[i], target.r_mm[j]);
  }
  for (int c = 0; c < 3; ++c) {
    double norm2 = 0.0;
    for (Eigen::Index j = 0; j < rows; ++j) {
      const double s = std::sqrt(target.dr[j]) * target.r_mm[j];
      b(j + 1) = s * rgb.channel(c).transmittance(target.r_mm[j]);
      norm2 += b(j + 1) * b(j + 1);
    }
    if (!(total[c] > 0.0) || !(norm2 > 0.0)) continue;  // nothing transmitted
    // The energy row Σ_i u_i = total, weighted far above the rest (then made exact).
    const double k = 1e4 * std::sqrt(norm2) / total[c];
    A.row(0).setConstant(k);
    b(0) = k * total[c];
    const Eigen::VectorXd u = profiles::nnls(A, b);
    const double sum = u.sum();
    if (!(sum > 0.0)) continue;
    double err2 = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) out.weights[i][c] = u(i) * total[c] / sum;
    for (Eigen::Index j = 0; j < rows; ++j) {
      double fitted = 0.0;
      for (Eigen::Index i = 0; i < n; ++i) fitted += out.weights[i][c] * A(j + 1, i);
      err2 += (fitted - b(j + 1)) * (fitted - b(j + 1));
    }
    out.total[c] = total[c];
    out.relative_error[c] = std::sqrt(err2 / norm2);
  }
  return out;
}

namespace {

MaterialData build(const std::vector<scene::Material>& materials, int separable_taps,
                   const MaterialData* previous, const std::vector<bool>* reuse) {
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
                         previous->profiles.size() == materials.size() &&
                         reuse->size() == materials.size();
  MaterialData data;
  data.separable_taps = separable_taps;
  for (std::size_t index = 0; index < materials.size(); ++index) {
    const scene::Material& m = materials[index];
    shader::GpuMaterial g;
    g.surface = {0.04f * m.specular, m.metallic, m.roughness, 0.0f};
    g.reflectance = {1.0f, 1.0f, 1.0f, 0.0f};
    std::optional<MaterialProfile> profile;
    if (m.sss.enabled) {
      MaterialProfile p;
      if (can_reuse && (*reuse)[index] && previous->profiles[index]) {
        p = *previous->profiles[index];
      } else {
        const profiles::RgbProfile rgb(m.sss.model, m.sss.effective_medium());
        profiles::FitOptions options;
        options.gaussians = m.sss.gaussians;
        const profiles::FitTarget target = profiles::make_fit_target(rgb);
        p = {profiles::fit_gaussians(target, options),
             profiles::make_separable_kernel(rgb, separable_taps), std::nullopt};
        if (m.sss.effective_medium().is_slab())
          p.transmittance = fit_transmittance(rgb, target, p.fit.variances_mm2);
      }
      if (p.transmittance) {
        const Rgb t = p.transmittance->total;
        g.transmit = {float(t[0]), float(t[1]), float(t[2]),
                      float(m.sss.effective_medium().thickness_mm)};
      }
      const Rgb total = p.kernel.total_reflectance;  // the profile's total_reflectance()
      g.reflectance = {float(total[0]), float(total[1]), float(total[2]), 1.0f};
      const auto count = p.fit.variances_mm2.size();
      g.surface.w = float(count);
      for (std::size_t i = 0; i < count; ++i) {
        float* v = &g.variances[i / 4].x;
        v[i % 4] = float(p.fit.variances_mm2[i]);
        g.gauss_weights[i] = {float(p.fit.weights[i][0]), float(p.fit.weights[i][1]),
                              float(p.fit.weights[i][2]), 0.0f};
      }
      const bool pre_post = m.sss.albedo_mode == scene::AlbedoMode::PrePost;
      g.kernel = {float(p.kernel.offsets_mm.size()), float(p.kernel.range_mm),
                  pre_post ? 1.0f : 0.0f, 0.0f};
      for (std::size_t i = 0; i < p.kernel.offsets_mm.size(); ++i)
        g.taps[i] = {float(p.kernel.weights[i][0]), float(p.kernel.weights[i][1]),
                     float(p.kernel.weights[i][2]), float(p.kernel.offsets_mm[i])};
      data.max_gaussians = std::max(data.max_gaussians, static_cast<int>(count));
      profile = std::move(p);
    }
    data.gpu.push_back(g);
    data.profiles.push_back(std::move(profile));
  }
  if (data.gpu.empty()) data.gpu.emplace_back();  // a storage buffer cannot be empty
  return data;
}

}  // namespace

MaterialData build_material_data(const std::vector<scene::Material>& materials,
                                 int separable_taps) {
  return build(materials, separable_taps, nullptr, nullptr);
}

MaterialData build_material_data(const std::vector<scene::Material>& materials,
                                 int separable_taps, const MaterialData& previous,
                                 const std::vector<bool>& reuse) {
  return build(materials, separable_taps, &previous, &reuse);
}

MaterialTable::MaterialTable(const vk::Context& context, const scene::Scene& scene,
                             int separable_taps)
    : data_(build_material_data(scene, separable_taps)),
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
