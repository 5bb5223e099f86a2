// LayeredProfile's state (Layered.h), shared by the files that build it: Layered.cpp,
// LayeredAdding.cpp (LayerCoupling::Adding) and LayeredDiffusion.cpp. Internal to profiles/.
#pragma once

#include "profiles/LayeredGrid.h"

#include <memory>
#include <vector>

namespace sss::profiles {

struct LayeredProfile::Impl {
  using FiniteLayer = layered::FiniteLayer;
  std::vector<Layer> layers;
  std::unique_ptr<RadialProfile> top_semi;    // a one-layer semi-infinite stack
  std::unique_ptr<FiniteLayer> top_finite;    // the top layer when finite
  double L = 1.0;
  std::vector<double> added;     // R12 - R1 on the grid
  std::vector<double> trans;     // T of the stack on the grid (finite bottom only)
  bool has_added = false, has_trans = false, one_finite = false;
  double total_r = 0.0, total_t = 0.0;  // scalar adding of the layers' totals
  double grid_total_r = 0.0, grid_total_t = 0.0;
  double exact_total_r = 0.0, exact_total_t = 0.0;  // Diffusion: the k = 0 solve
  double support = 0.0, inner = 0.0;

  // LayerCoupling::Diffusion: the top medium's classical dipole, to scale what the stack
  // removes (reflectance()).
  std::unique_ptr<ClassicalDipole> top_dipole;

  double top_reflectance(double r) const {
    return top_semi ? top_semi->reflectance(r) : top_finite->reflectance_down(r);
  }
  // The stack's reflectance from the top profile and the added part at r.
  double combined(double r) const {
    const double top = top_reflectance(r);
    if (!has_added) return top;
    const double d = layered::at_grid(added, L, r);
    if (d >= 0.0 || !top_dipole) return std::max(0.0, top + d);
    // Light the stack takes away (an absorbing base): the same fraction of the top
    // profile as of the top medium's diffusion profile, so that it stays >= 0.
    const double dip = top_dipole->reflectance(r);
    return dip > 0.0 ? top * std::max(0.0, 1.0 + d / dip) : 0.0;
  }

  // LayerCoupling::Adding, in stages.
  struct Built {
    std::vector<std::unique_ptr<FiniteLayer>> finite;  // per layer, null for the base
    std::unique_ptr<RadialProfile> base;               // a semi-infinite base
  };
  void build_adding(const std::vector<Layer>& layers, const ModelOptions& opt, Model base);
  Built make_layers(const std::vector<Layer>& layers, const ModelOptions& opt, Model base);
  void add_in_frequency(Built& built, const std::vector<std::vector<double>>& hat_down,
                        const std::vector<std::vector<double>>& hat_up);
  // The Hankel transform of f sampled on the grid (scale L).
  template <class F>
  std::vector<double> sample(F&& f) const {
    const auto& x = layered::hankel().x;
    std::vector<double> v(layered::kNodes);
    for (int j = 0; j < layered::kNodes; ++j) v[j] = f(L * x[j]);
    return layered::forward(v, L);
  }
};

}  // namespace sss::profiles
