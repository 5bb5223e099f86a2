// Layered media (issue 19): the radial reflectance R(r) and transmittance T(r) of a stack
// of layers, top first, computed in the frequency domain of the radial profiles (the
// Hankel transform of order 0, the 2-D Fourier transform of a radially symmetric
// function), where spreading through the plane is a product.
//
// Two couplings (LayerCoupling below). The default solves the diffusion equation through
// the whole stack; the other is the adding equations of Donner & Jensen 2005 ("Light
// diffusion in multi-layered translucent materials", SIGGRAPH 2005, §3),
//   R12 = R1 + T1 R2 T1 / (1 - R2 R1↑),      T12 = T1 T2 / (1 - R2 R1↑),
// applied from the bottom of the stack up over multipole layers. Against the layered
// Monte Carlo walk (tests/profiles/test_layered_accuracy.cpp, README "Layered
// materials") the adding equations overstate the reflectance of skin-like stacks by ~28%;
// the diffusion coupling is within 2% on every stack tried, R(r) within 11-15% RMS.
//
// The choices, and why:
// - Interfaces between layers are index-matched: every layer of a stack has the same η,
//   so light crosses an internal interface without reflection. The top face sees the
//   outside through η, and so does the bottom face of a stack with a finite last layer.
//   validate_layers refuses a stack whose layers' η differ (naming the layer).
// - Diffusion coupling: fluence and flux continuous across every interface; the classical
//   dipole's source (α' of the top layer, one reduced mean free path deep) and
//   extrapolated boundaries z_b = 2 A(η) D at the faces to the outside. The near-axis
//   profile, where diffusion is poorest, is the base model's semi-infinite profile of the
//   top medium (mc-table by default: 1-2% from Monte Carlo where the dipole is 20-70%
//   off); the stack adds to it what diffusion says the layers below add (or, where they
//   take light away, removes the same fraction). A stack of identical layers is then
//   exactly the base model of that medium, and so is a top layer deep enough to hide
//   what lies below.
// - Adding coupling: each finite layer is the multipole with its own boundary on each
//   face (A(η) to the outside, A(1) to another layer); a layer whose faces differ
//   reflects differently from below (the multipole with its faces swapped); reflectance
//   is the base model's semi-infinite profile times the multipole's finite-thickness
//   factor R_multipole / R_dipole; a semi-infinite base is the base model at η = 1 under
//   another layer. Light crossing an internal interface is treated as a normally incident
//   pencil beam on the next layer, as Donner & Jensen do; that and the free boundary at
//   each internal face are what overstate R.
// - Layers must be thicker than one reduced mean free path (both couplings place a source
//   that deep; Multipole.h).
// - The transforms are sampled on one fixed log-spaced grid (LayeredGrid.h has the numerics
//   and their accuracy). The top medium's own profile is never transformed; only what
//   the stack adds to it, which is smooth, goes through the inverse transform.
#pragma once

#include "profiles/Medium.h"
#include "profiles/Profile.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sss::profiles {

// How the layers are coupled (LayeredAdding.cpp and LayeredDiffusion.cpp have the
// derivations and the measured errors):
// - Diffusion (default): the diffusion equation solved through the whole stack in the
//   frequency domain, with the fluence and its flux continuous across each index-matched
//   interface and an extrapolated boundary at each face to the outside (the layered form
//   of the classical dipole: a stack of identical layers is exactly the dipole). The
//   difference it makes to the top medium's own semi-infinite diffusion profile is
//   carried over to the base model's profile of the top medium (mc-table by default).
// - Adding: Donner & Jensen 2005's adding equations over multipole layers (above). Kept
//   to show what it costs: two identical layers split at 1 mm reflect +38% more in total
//   than the dipole they are (0.846 against 0.614; the diffusion coupling gives the
//   dipole exactly).
enum class LayerCoupling { Diffusion, Adding };

// An RGB stack, top first: each Medium's thickness_mm is that layer's thickness; only the
// last layer may be infinite (a semi-infinite base).
using LayerStack = std::vector<Medium>;

// Checks a stack: at least one and at most kMaxLayers layers, each a valid medium, every
// layer but the last finite, and the same η in every layer (per channel). The field names
// the layer: "layers[1].sigma_a[G]", "layers[0].thickness_mm", "layers[2].eta[R]".
inline constexpr int kMaxLayers = 16;
std::optional<FieldError> validate_layers(const LayerStack& stack);

// One channel of a stack.
std::vector<Layer> channel_layers(const LayerStack& stack, int channel);

class LayeredProfile final : public RadialProfile {
 public:
  // Throws std::invalid_argument naming the layer and field for an invalid stack. `base`
  // is the model of a semi-infinite last layer (any model that make_profile builds from
  // one medium without a thickness; not Multipole, MonteCarlo or Layered).
  LayeredProfile(const std::vector<Layer>& layers, const ModelOptions& opt,
                 Model base = kDefaultModel, LayerCoupling coupling = LayerCoupling::Diffusion);
  ~LayeredProfile() override;
  double reflectance(double r_mm) const override;
  double transmittance(double r_mm) const override;
  double total_reflectance() const override;
  double total_transmittance() const override;
  double support_radius() const override;
  double inner_radius() const override;
  // With LayerCoupling::Adding, total_reflectance and total_transmittance are the scalar
  // adding formula of the layers' totals (with Diffusion, the integrals of the profiles).
  // These are the frequency-domain adding at the grid's lowest frequency
  // (J0 = 1 to 2.5e-5 there), for checks: the same numbers up to the sampling.
  double lowest_frequency_reflectance() const;
  double lowest_frequency_transmittance() const;
  // LayerCoupling::Diffusion: the diffusion solution's totals at k = 0, before the sampled
  // inverse transform and the carry-over to the base model (total_* integrate the
  // profiles as reflectance() and transmittance() return them).
  double diffusion_total_reflectance() const;
  double diffusion_total_transmittance() const;
  std::size_t layer_count() const;

 private:
  void build_diffusion(const std::vector<Layer>& layers, const ModelOptions& opt, Model base);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

namespace detail {
// The sampled Hankel transform pair of LayeredGrid.h, for its tests: the grid x_j (r = L x_j
// and k = x_j / L), and the forward (samples f(L x_j) -> F(x_i / L)) and inverse maps.
const std::vector<double>& hankel_grid();
std::vector<double> hankel_forward(const std::vector<double>& f, double L);
std::vector<double> hankel_inverse(const std::vector<double>& F, double L);
}  // namespace detail

// The stack as an RgbProfile labelled Model::Layered. Throws std::invalid_argument (the
// message names the layer and field) for an invalid stack.
// What the base model's lookup of the stack warns about, a line each prefixed "top layer ":
// the top layer is the medium `base` is built on (with the diffusion coupling), so under
// mc-table a top layer whose g is outside the table's range gets mc_table_g_warnings.
// Empty for other bases and an empty stack.
std::vector<std::string> layered_g_warnings(const LayerStack& stack, Model base = kDefaultModel);

RgbProfile make_layered_rgb_profile(const LayerStack& stack, const ModelOptions& opt = {},
                                    Model base = kDefaultModel,
                                    LayerCoupling coupling = LayerCoupling::Diffusion);

}  // namespace sss::profiles
