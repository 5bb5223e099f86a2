// Model `mc-table`: R(r) looked up in the Monte Carlo table of profiles/McTable.h.
//
// One medium is one lookup, done in the constructor:
//  1. Similarity and scale. The table is in optical units (σt' = 1, isotropic scattering
//     at the reduced albedo α' = σs'/σt'), so R_mm(r) = σt'² R_t(σt' r) with σt', α' and η
//     of the medium's Coefficients (a medium with g ≠ 0 is its reduced g = 0 medium).
//  2. Interpolation across (α', η): per annulus, ln(flux/α') is interpolated with cubic
//     Hermite splines whose tangents are those of the parabola through three neighbours
//     (Catmull-Rom on a non-uniform grid), in u = √(1 - α') and in η (bilinear where a
//     node of the cubic stencil is too noisy); the total diffuse reflectance likewise, but
//     in its own value, and the fluxes are then normalised to add up to it. Below the
//     table's first α' the first slice is scaled by α'/α'_0 (single scattering dominates);
//     above its last (0.9999) the α' axis extrapolates with the parabola through the last
//     three nodes. A medium that does not scatter (α' = 0) has R ≡ 0.
//  3. Reconstruction in r: a smooth q(x) = 2π r² R(r) as a function of x = ln r whose
//     integral over every reliable annulus reproduces that annulus' interpolated flux
//     ("histopolation"), with a power law inside the first edge (R ~ 1/r from single
//     scattering at the source) and an exponential tail at the asymptotic transport decay
//     rate past the last reliable annulus. McTableProfile.cpp (lookup, enforced annuli,
//     normalisation) and McTableSpline.cpp (the spline) say how, and why each choice.
//
// Single scattering apart (ModelOptions::single_scattering_apart; issue 18 part 2): the
// profile of the light that scattered twice or more, the renderer adding S(1) in closed
// form. Every node's flux and total become their multiply-scattered parts flux - α' q and
// total - α' q_total (McTable.h: exact for the same walks), with their own standard
// errors; ln(flux/α'²) and total/α'² (in value) are interpolated and the first slice is
// scaled by (α'/α'_0)² below the first node (the part is O(α'²)); inside the first
// reliable annulus R grows like ln(1/r) instead of 1/r (no single scattering left).
// Everything else is as above. With the isotropic table and g ≠ 0 what is left out is the
// once-scattered light of the similarity medium (isotropic, α'), not that of the real
// phase function, which the renderer's S(1) adds: the multiply-scattered totals still
// agree with the analog walk's real-g exits after two or more events within 0.33% on
// skin1 R and B, ketchup R and marble G (tests/profiles/test_single_scattering_apart.cpp).
// With an anisotropic layer (McTableData::g != 0, used by make_mc_table_profile for
// 0 < g <= 0.95) it is the real phase function's once-scattered light, stored per node.
//
// Evaluation is a log, a table index computed from it, a cubic and an exp: no search.
#pragma once

#include "profiles/McTable.h"
#include "profiles/Medium.h"
#include "profiles/Profile.h"

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sss::profiles {

struct McTableSpline;

// The root κ0 in (0, 1) of (α/κ) artanh(κ) = 1: the decay rate (per mean free path) of the
// slowest discrete mode of one-speed transport with isotropic scattering at single-
// scattering albedo α (Case & Zweifel, "Linear Transport Theory", 1967, §4.2: the discrete
// eigenvalues ±ν0 of the dispersion relation 1 = (c ν0/2) ln((ν0+1)/(ν0-1)), κ0 = 1/ν0).
// Far from the source every flux decays like e^{-κ0 r} times a power of r. κ0 → 1 as
// α → 0 and κ0 ≈ √(3(1-α)) as α → 1 (the diffusion limit). Throws std::invalid_argument
// for α outside (0, 1).
double transport_decay_rate(double albedo);

// The interpolated total diffuse reflectance and its standard error alone (what
// McTableProfile::total_reflectance() and total_stderr() return, without building R(r)):
// for the artist mapping, which inverts the total. Same errors as the constructor.
struct McTableTotal {
  double total = 0.0, stderr_ = 0.0;
};
McTableTotal mc_table_total(const Coefficients& c, const McTableData& table,
                            bool single_scattering_apart = false);

// Anisotropic media (issue 18 part 4). The isotropic table (g = 0) and the shipped layers
// of Henyey-Greenstein walks (shipped_mc_table_layers(), g = 0.3, 0.6, 0.8, 0.9, 0.95) are
// nodes on a g axis. A medium is looked up at its reduced coefficients (α', η, σt') in the
// two nodes that bracket its g, and R(r) and the totals are interpolated linearly in
// ln(1 - g) between them (the nodes are nearly uniform in it; McTableGenerator.cpp). At a
// node it is that node's lookup. Outside [0, 0.95] there is no node to interpolate to: a
// medium with g > 0.95 is looked up in the g = 0.95 layer and one with g < 0 in the
// isotropic table, by the similarity relation from there; mc_table_g_warning says so.
struct McTableGBracket {
  const McTableData* lo = nullptr;
  const McTableData* hi = nullptr;  // null: lo alone
  double t = 0.0;                   // R = (1 - t) R_lo + t R_hi
};
McTableGBracket mc_table_g_bracket(double g);
// A one-line warning for a g outside the tabulated [0, 0.95] (what the lookup does
// instead), or nothing.
std::optional<std::string> mc_table_g_warning(double g);
// The same for each channel of a medium, prefixed "g[R]: " etc.; a g shared by several
// channels is said once (under its first channel).
std::vector<std::string> mc_table_g_warnings(const Medium& medium);
// mc_table_total over the g axis (as make_mc_table_profile interpolates it).
McTableTotal mc_table_total_any_g(const Coefficients& c, bool single_scattering_apart = false);
// The profile of model mc-table for a medium of any g: a McTableProfile at a node, else
// the interpolation of two.
std::unique_ptr<RadialProfile> make_mc_table_profile(const Coefficients& c,
                                                     bool single_scattering_apart = false);

class McTableProfile final : public RadialProfile {
 public:
  // With the shipped table (shipped_mc_table()). single_scattering_apart: leave the
  // once-scattered light out (see above).
  explicit McTableProfile(const Coefficients& c, bool single_scattering_apart = false);
  // Throws std::invalid_argument naming the field: "eta: mc-table covers eta in [A, B],
  // got X", or a coefficient error of Coefficients::validate. `table` must outlive the profile only during the
  // constructor (nothing refers to it afterwards).
  McTableProfile(const Coefficients& c, const McTableData& table,
                 bool single_scattering_apart = false);

  double reflectance(double r_mm) const override;
  // The interpolated tabulated total (all exits, also beyond the table's last edge; with
  // single scattering apart, total - α' q_total), not the integral of the reconstruction
  // (which agrees with it within the table's noise).
  double total_reflectance() const override { return total_; }
  // Where r R(r) has fallen below 1e-8 of its peak.
  double support_radius() const override { return support_mfp_ / sigma_tp_; }
  // One reduced mean free path, 1/σt' (as PBD's): the length on which the profile bends.
  double inner_radius() const override { return 1.0 / sigma_tp_; }

  // R is evaluated at max(r, min_radius()): the profile grows like 1/r towards the origin
  // (single scattering of a pencil beam; like ln(1/r) with single scattering apart), an
  // integrable singularity. 1e-9 mean free paths.
  double min_radius() const { return kMinRadiusMfp / sigma_tp_; }
  bool single_scattering_apart() const { return single_scattering_apart_; }
  // The slope d ln(r² R)/d ln r with which R continues inside the first node: the power
  // law's exponent + 2, or with single scattering apart the log law's slope at the node.
  double inner_slope() const { return inner_slope_; }
  // The interpolated standard error of total_reflectance().
  double total_stderr() const { return total_se_; }

  // For tests and diagnostics, in the table's radial bins (optical units):
  // the interpolated flux the reconstruction was made to reproduce (0 where the annulus
  // was unreliable and not enforced), whether it was enforced, and the rate of the
  // exponential tail (per mean free path) with the radius (mfp) where it starts.
  const std::vector<double>& target_flux() const { return target_flux_; }
  const std::vector<char>& enforced() const { return enforced_; }
  double tail_rate_mfp() const { return kappa_; }
  double tail_start_mfp() const { return tail_r_; }
  // The factor that made the enforced fluxes add up to the interpolated total (1 at a
  // node; McTableProfile.cpp). Every flux is scaled by it, so R(r) is too.
  double flux_scale() const { return flux_scale_; }
  // Fixed-point iterations the histopolation took, and its largest remaining |ln(F/I)|.
  int iterations() const { return iterations_; }
  double residual() const { return residual_; }

  static constexpr double kMinRadiusMfp = 1e-9;
  // The start of the constructor's error for a table whose walks are too few at a medium
  // (make_mc_table_profile falls back to another node on it).
  static constexpr std::string_view kTooFewAnnuli = "mc-table: fewer than two annuli";
  // An annulus whose relative standard error exceeds this at any contributing node is
  // not enforced (its flux is too noisy to shape R): see McTableProfile.cpp.
  static constexpr double kMaxRelativeError = 0.3;

 private:
  // The evaluation constants (mm) from the fitted spline.
  void set_evaluation(const McTableSpline& spline);

  double sigma_tp_ = 1.0;
  double total_ = 0.0, total_se_ = 0.0;
  double support_mfp_ = 0.0;
  double kappa_ = 0.0, tail_r_ = 0.0;
  double flux_scale_ = 1.0;
  bool zero_ = false;  // α' = 0: R ≡ 0
  bool single_scattering_apart_ = false;
  double inner_slope_ = 0.0;
  int iterations_ = 0;
  double residual_ = 0.0;
  std::vector<double> target_flux_;
  std::vector<char> enforced_;

  // Evaluation in mm, everything folded in: ψ(u) = ln R_mm at u = ln r_mm.
  // Below u_lo_:   ψ = lo_a_ + lo_b_ (u - u_lo_) + ln(1 + lo_log_ (u_lo_ - u))
  //                (power law inside the first node, or with single scattering apart
  //                lo_b_ = 0 and R ∝ ln(r_c/r))
  // u >= u_lo_:    piece j = floor((u - u_lo_) * inv_du_), t = (u - u_lo_) * inv_du_ - j,
  //                ψ = c0 + t (c1 + t (c2 + t c3)) from coef_[4 j ..]
  // r >= r_tail_:  R = tail_a_ exp(-tail_k_ (r - r_tail_))  (the exponential tail)
  double r_min_mm_ = 0.0;
  double u_lo_ = 0.0, inv_du_ = 0.0;
  double lo_a_ = 0.0, lo_b_ = 0.0, lo_log_ = 0.0;
  double r_tail_ = 0.0, tail_a_ = 0.0, tail_k_ = 0.0;
  std::vector<double> coef_;
};

}  // namespace sss::profiles
