// MaterialTable: one GpuMaterial per scene material, uploaded to a storage buffer that
// the lighting, SSS and composite passes index with the G-buffer's material id. For an
// SSS material it holds the profile's sum-of-Gaussians fit (gaussians mode) and a
// Jimenez separable kernel built from the exact profile (separable mode), both in object
// mm (the material's scale is folded into the medium, Material::effective_medium).
#pragma once

#include "renderer/RenderOptions.h"
#include "scene/Scene.h"
#include "renderer/vk/Buffer.h"
#include "shaders/shared/frame.h"

#include "profiles/GaussianFit.h"
#include "profiles/KernelFit.h"
#include "profiles/SeparableKernel.h"

#include <optional>
#include <vector>

namespace sss::vk {
class Context;
}

namespace sss::renderer {

struct MaterialProfile {
  profiles::GaussianFit fit;
  profiles::SeparableKernel kernel;
  std::optional<profiles::TransmittanceFit> transmittance;  // slabs (Medium::is_slab) only
};

// The GPU view of the scene's materials; profiles[i] is set for SSS materials. Throws
// std::invalid_argument for more than SSS_MAX_MATERIALS materials or a bad tap count.
// build_material_data is pure CPU work with no shared state: the viewer runs it on a
// worker thread (its cost: renderer/README.md, "Costs") and hands the result to
// Renderer::set_materials(materials, data) on the render thread.
struct MaterialData {
  std::vector<shader::GpuMaterial> gpu;  // encode() of each material
  std::vector<std::optional<MaterialProfile>> profiles;  // one per material
  int max_gaussians = 0;  // over SSS materials
  int separable_taps = 0;  // the kernels' tap count
  // The profiles leave out their once-scattered light (RenderOptions::single_scattering:
  // the lighting pass adds S(1) per pixel; profiles::ModelOptions::single_scattering_apart).
  bool single_scattering = false;

  // The Gaussians material i's fit has (0 when it does not scatter); the CPU's answer,
  // never read back from the GPU packing.
  int gaussian_count(std::size_t material) const {
    return material < profiles.size() ? gaussian_count(profiles[material]) : 0;
  }
  static int gaussian_count(const std::optional<MaterialProfile>& p) {
    return p ? static_cast<int>(p->fit.variances_mm2.size()) : 0;
  }
};

// The one function that knows the GPU layout of a material (shaders/shared/frame.h,
// GpuMaterial): the surface parameters, and for a scattering material (`profile` set) its
// fit, separable kernel, slab transmittance, η, exit normalization and single-scattering
// coefficients.
shader::GpuMaterial encode(const scene::Material& material, const MaterialProfile* profile);
MaterialData build_material_data(const scene::Scene& scene, int separable_taps,
                                 bool single_scattering = RenderOptions{}.single_scattering);
MaterialData build_material_data(const std::vector<scene::Material>& materials,
                                 int separable_taps, bool single_scattering = RenderOptions{}.single_scattering);
// The same, but material i keeps previous.profiles[i] (fit and kernel) instead of being
// refitted where reuse[i] holds: the caller vouches that its model, medium, scale and
// Gaussian count are unchanged. Ignored (everything refitted) unless `previous` was built
// with these taps and single-scattering setting for as many materials. Equal, bit for
// bit, to a full rebuild.
MaterialData build_material_data(const std::vector<scene::Material>& materials,
                                 int separable_taps, const MaterialData& previous,
                                 const std::vector<bool>& reuse, bool single_scattering = RenderOptions{}.single_scattering);

class MaterialTable {
 public:
  MaterialTable(const vk::Context& context, const scene::Scene& scene, int separable_taps,
                bool single_scattering = RenderOptions{}.single_scattering);

  // Uploads `data` (from build_material_data, as many materials as now) into the same
  // buffer, so descriptor sets that reference it stay valid. The buffer must not be in
  // use by the GPU. Throws std::invalid_argument for another material count.
  void replace(const vk::Context& context, MaterialData data);

  const vk::Buffer& buffer() const { return buffer_; }
  const MaterialData& data() const { return data_; }

 private:
  MaterialData data_;
  vk::Buffer buffer_;
};

}  // namespace sss::renderer
