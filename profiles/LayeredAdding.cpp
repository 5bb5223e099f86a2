// LayerCoupling::Adding: the layers' multipoles combined by Donner & Jensen's adding
// equations in the frequency domain.
#include "profiles/LayeredImpl.h"

#include "profiles/Profile.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace sss::profiles {

using namespace layered;

// The layers as profiles: the finite ones as multipoles both ways up (FiniteLayer), the
// semi-infinite base as `base`; and the grid's scale L from their radii.
LayeredProfile::Impl::Built LayeredProfile::Impl::make_layers(const std::vector<Layer>& layers,
                                                              const ModelOptions& opt, Model base) {
  const std::size_t n = layers.size();
  const double eta = layers[0].c.eta;
  ModelOptions semi_opt = opt;
  const bool pure = base == Model::Dipole;
  // Index: the lit face of layer k sees the outside (eta) for k = 0, another layer (1)
  // below; its far face sees the outside when it is the last layer.
  auto make_finite = [&](std::size_t k) {
    const Layer& l = layers[k];
    const double top = k == 0 ? eta : 1.0;
    const double bottom = k + 1 == n ? eta : 1.0;
    auto f = std::unique_ptr<FiniteLayer>(new FiniteLayer{
        Multipole(l.c, l.thickness_mm, opt.multipole_pairs, top, bottom),
        Multipole(l.c, l.thickness_mm, opt.multipole_pairs, bottom, top),
        ClassicalDipole(with_eta(l.c, top)), ClassicalDipole(with_eta(l.c, bottom)),
        make_profile(base, with_eta(l.c, top), kInfinity, semi_opt),
        make_profile(base, with_eta(l.c, bottom), kInfinity, semi_opt), pure});
    return f;
  };
  auto make_semi = [&](std::size_t k) {
    return make_profile(base, with_eta(layers[k].c, k == 0 ? eta : 1.0), kInfinity, semi_opt);
  };

  Built built;
  built.finite.resize(n);
  std::vector<std::unique_ptr<FiniteLayer>>& finite = built.finite;
  std::unique_ptr<RadialProfile>& base_profile = built.base;
  double smallest = kInfinity, widest = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    if (std::isfinite(layers[k].thickness_mm)) {
      finite[k] = make_finite(k);
      smallest = std::min({smallest, layers[k].thickness_mm, finite[k]->down.inner_radius()});
      widest = std::max(widest, finite[k]->down.support_radius());
      if (!pure) widest = std::max(widest, finite[k]->semi_down->support_radius());
    } else {
      base_profile = make_semi(k);
      smallest = std::min(smallest, base_profile->inner_radius());
      widest = std::max(widest, base_profile->support_radius());
    }
  }
  support = widest;
  inner = smallest;
  L = std::max(smallest, widest * 1e-4);
  return built;
}

// LayerCoupling::Adding: the layers' multipoles combined by the adding equations in the
// frequency domain (Donner & Jensen 2005).
void LayeredProfile::Impl::build_adding(const std::vector<Layer>& layers, const ModelOptions& opt,
                                        Model base) {
  const std::size_t n = layers.size();
  const bool pure = base == Model::Dipole;
  Built built = make_layers(layers, opt, base);
  std::vector<std::unique_ptr<FiniteLayer>>& finite = built.finite;
  std::unique_ptr<RadialProfile>& base_profile = built.base;
  // Transforms of the corrected layer reflectances (both directions), kept for the adding.
  std::vector<std::vector<double>> hat_down(n), hat_up(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (!finite[k]) continue;
    FiniteLayer& f = *finite[k];
    if (pure && n == 1) break;  // the multipole alone: nothing to transform
    hat_down[k] = sample([&](double r) { return f.reflectance_down(r); });
    if (k + 1 < n) hat_up[k] = sample([&](double r) { return f.reflectance_up(r); });
    // At the lowest frequency, 10^-2 / (widest support) or below, J0 is 1 to 2.5e-5.
    f.tot_down = hat_down[k].front();
    if (k + 1 < n) f.tot_up = hat_up[k].front();
  }

  // Scalar adding of the totals, bottom up.
  double tot_r = base_profile ? base_profile->total_reflectance() : finite[n - 1]->total_down();
  double tot_t = base_profile ? 0.0 : finite[n - 1]->down.total_transmittance();
  for (std::size_t k = n - 1; k-- > 0;) {
    const FiniteLayer& f = *finite[k];
    const double t = f.down.total_transmittance();
    const double denom = 1.0 - tot_r * f.total_up();
    tot_t = t * tot_t / denom;
    tot_r = f.total_down() + t * t * tot_r / denom;
  }
  total_r = tot_r;
  total_t = tot_t;

  if (n == 1) {
    if (base_profile) top_semi = std::move(base_profile);
    else top_finite = std::move(finite[0]), one_finite = true;
    grid_total_r = total_r, grid_total_t = total_t;
    return;
  }

  add_in_frequency(built, hat_down, hat_up);
}

// The stack in the frequency domain, bottom up: R and T of the layers below, the top's
// added reflectance (`added`) and the stack's transmittance (`trans`, a finite bottom).
void LayeredProfile::Impl::add_in_frequency(Built& built, const std::vector<std::vector<double>>& hat_down,
                                            const std::vector<std::vector<double>>& hat_up) {
  std::vector<std::unique_ptr<FiniteLayer>>& finite = built.finite;
  const std::unique_ptr<RadialProfile>& base_profile = built.base;
  const std::size_t n = finite.size();
  std::vector<double> R, T;
  if (base_profile) {
    R = sample([&](double r) { return base_profile->reflectance(r); });
    T.assign(kNodes, 0.0);
  } else {
    const FiniteLayer& f = *finite[n - 1];
    R = hat_down[n - 1];
    T = sample([&](double r) { return f.down.transmittance(r); });
  }
  for (std::size_t k = n - 1; k-- > 0;) {
    const FiniteLayer& f = *finite[k];
    const auto Tk = sample([&](double r) { return f.down.transmittance(r); });
    const std::vector<double>& Rup = hat_up[k];
    const std::vector<double>& Rdown = hat_down[k];
    std::vector<double> added(kNodes), Rn(kNodes), Tn(kNodes);
    const bool top = k == 0;
    for (int i = 0; i < kNodes; ++i) {
      const double denom = 1.0 - R[i] * Rup[i];
      added[i] = Tk[i] * Tk[i] * R[i] / denom;
      Tn[i] = Tk[i] * T[i] / denom;
      if (!top) Rn[i] = Rdown[i] + added[i];
    }
    T = std::move(Tn);
    if (top) {
      this->added = inverse(added, L);
      cut_tail(this->added);
      has_added = true;
      grid_total_r = f.total_down() + added.front();
    } else {
      R = std::move(Rn);
    }
  }
  top_finite = std::move(finite[0]);
  if (!base_profile) {
    this->trans = inverse(T, L);
    cut_tail(this->trans);
    has_trans = true;
    grid_total_t = T.front();
  }
}

}  // namespace sss::profiles
