// RadialProfile: the radially symmetric diffusion profile R(r) of one channel, and the
// factory that builds one for any model. RgbProfile bundles three channels.
//
// Conventions (DESIGN.md §3): r in mm, R(r) in mm^-2 = exitant flux per unit area per
// unit power *entering* the medium at the origin (normal incidence; the specular
// reflection at entry is not part of R). ∫ 2πr R(r) dr is the total diffuse reflectance.
#pragma once

#include "profiles/Medium.h"

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string_view>

namespace sss::profiles {

// Layered is a stack of media (profiles/Layered.h), not one medium: it is not in
// kAllModels (the models make_profile builds from one medium) and make_profile refuses it.
enum class Model { Dipole, BetterDipole, Pbd, Burley, Multipole, MonteCarlo, McTable, Qd, Layered };

inline constexpr std::array<Model, 8> kAllModels = {
    Model::Dipole,    Model::BetterDipole, Model::Pbd,     Model::Burley,
    Model::Multipole, Model::MonteCarlo,   Model::McTable, Model::Qd};

// The model used wherever none is named: sss-fit --model, sss-viewer and sss-reference
// (scenes and --color/--mfp inversion), glTF extras.sss without "model", the viewer's
// editor and fit worker. mc-table, because against Monte Carlo (README "How right is each
// model?") its R(r) is within 1-2% RMS (the Monte Carlo noise) on skin1, marble, ketchup
// and cream where the former default, better-dipole, is off by 23-71% RMS; its total
// reflectance within 0.2% where better-dipole's is off by 4-10%; its 6-Gaussian fit at
// the default fit resolution (GaussianFit.h default_fit_resolution, 0.25 mfp) within 2x
// of the dipole's fit error (0.5-2.3%); and a lookup costs 1.2x the dipole's closed form.
// Change this one line to change the default everywhere.
inline constexpr Model kDefaultModel = Model::McTable;

// CLI names: dipole | better-dipole | pbd | burley | multipole | mc | mc-table | qd, and
// layered (which parse_model does not accept: a stack is given as layers, not as a model
// of one medium)
std::string_view model_name(Model m);
std::optional<Model> parse_model(std::string_view name);
// A comma-separated list of every model name, for messages.
std::string model_names();

// Whether one R(r) or T(r) call is costly enough that callers who evaluate it many times
// tabulate it first (the separable kernel's quadrature, the references' profile tables):
// pbd (64 beam samples a call), multipole (up to hundreds of dipole pairs), qd (~100
// Gaussians, 33x the dipole; bench_profiles BM_Model*). The closed forms and the
// Monte Carlo tables are cheap already.
inline bool model_is_costly(Model m) { return m == Model::Pbd || m == Model::Multipole || m == Model::Qd; }

struct ModelOptions {
  // Photon beam diffusion: samples along the refracted beam *per strategy* (exponential
  // and equiangular, combined with MIS). 32 reaches 1% everywhere: docs/PBD_CONVERGENCE.md.
  int pbd_samples = 32;
  // Multipole: dipole pairs i in [-n, n]; -1 (Multipole::kAutoPairs) sizes n so the
  // omitted poles weigh less than e^-25 (needed for bright thin slabs).
  int multipole_pairs = -1;
  // Monte Carlo (Model::MonteCarlo tabulates a random-walk run).
  std::uint64_t mc_photons = 1u << 20;
  std::uint64_t mc_seed = 1;
  int mc_threads = 0;  // 0: all hardware threads
  // Model mc: called with the fraction of the walk done, from its worker threads (never
  // overlapping, rising; MonteCarloOptions::progress). RgbProfile passes each channel's
  // run as a third of the whole. An exception it throws (a cancellation) stops the walk
  // and leaves the profile's constructor. Empty: silent.
  std::function<void(double)> mc_progress;
  // Leave out the light that leaves after exactly one scattering event: the renderers add
  // single scattering S(1) apart, in closed form with the real g and the exit direction
  // (profiles/SingleScattering.h), so a profile that contains it must not count it again
  // (issue 18 part 2). mc-table subtracts the table's stored once-scattered flux, mc drops
  // first-order exits, pbd drops its single-scattering term; the diffusion models (dipole,
  // better-dipole, multipole, burley, qd) contain none and are unchanged.
  bool single_scattering_apart = false;
};

class RadialProfile {
 public:
  virtual ~RadialProfile() = default;
  // R(r) in mm^-2, for r >= 0. Finite at r = 0 for every model except those whose
  // profile has an integrable 1/r singularity (PBD single scattering, Burley), which
  // clamp r to a tiny positive radius instead of dividing by zero.
  virtual double reflectance(double r_mm) const = 0;
  // ∫ 2πr R(r) dr, closed form where one exists.
  virtual double total_reflectance() const = 0;
  // Transmittance profile at the far face of a finite slab (0 for semi-infinite media).
  virtual double transmittance(double /*r_mm*/) const { return 0.0; }
  virtual double total_transmittance() const { return 0.0; }
  // A radius (mm) beyond which r R(r) is negligible (< 1e-8 of its scale): the outer end
  // of integration and fitting ranges.
  virtual double support_radius() const = 0;
  // The smallest length (mm) on which the profile changes shape (about one reduced mean
  // free path): the inner end of log-spaced grids is a small fraction of it.
  virtual double inner_radius() const = 0;
};

// Builds one channel's profile. `thickness_mm` matters only to Multipole (which requires
// it finite) and MonteCarlo (slab or semi-infinite); the semi-infinite models (dipole,
// better-dipole, pbd, burley, mc-table) ignore it. Throws std::invalid_argument for a
// model that cannot be built from these inputs (e.g. multipole without a thickness).
std::unique_ptr<RadialProfile> make_profile(Model model, const Coefficients& c,
                                            double thickness_mm, const ModelOptions& opt);

class RgbProfile {
 public:
  RgbProfile(Model model, const Medium& medium, const ModelOptions& opt = {});
  // Three prepared channels (GaussianSumProfile.h: a material's Gaussian fit), labelled
  // with the model they stand for. Throws std::invalid_argument for a null channel.
  RgbProfile(Model model, std::array<std::unique_ptr<RadialProfile>, 3> channels);
  Model model() const { return model_; }
  const RadialProfile& channel(int c) const { return *channels_[c]; }
  Rgb reflectance(double r_mm) const;
  Rgb transmittance(double r_mm) const;
  Rgb total_reflectance() const;
  Rgb total_transmittance() const;
  double support_radius() const;  // max over channels
  double inner_radius() const;    // min over channels

 private:
  Model model_;
  std::array<std::unique_ptr<RadialProfile>, 3> channels_;
};

}  // namespace sss::profiles
