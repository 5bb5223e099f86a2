#include "profiles/Profile.h"

#include "profiles/BetterDipole.h"
#include "profiles/Burley.h"
#include "profiles/ClassicalDipole.h"
#include "profiles/McTableProfile.h"
#include "profiles/QuantizedDiffusion.h"
#include "profiles/MonteCarlo.h"
#include "profiles/Multipole.h"
#include "profiles/PhotonBeamDiffusion.h"
#include "profiles/TabulatedProfile.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace sss::profiles {

std::string_view model_name(Model m) {
  switch (m) {
    case Model::Dipole: return "dipole";
    case Model::BetterDipole: return "better-dipole";
    case Model::Pbd: return "pbd";
    case Model::Burley: return "burley";
    case Model::Multipole: return "multipole";
    case Model::MonteCarlo: return "mc";
    case Model::McTable: return "mc-table";
    case Model::Qd: return "qd";
    case Model::Layered: return "layered";
  }
  return "?";
}

std::optional<Model> parse_model(std::string_view name) {
  for (Model m : kAllModels)
    if (model_name(m) == name) return m;
  return std::nullopt;
}

std::string model_names() {
  std::string s;
  for (Model m : kAllModels) {
    if (!s.empty()) s += ", ";
    s += model_name(m);
  }
  return s;
}

namespace {

// The Monte Carlo "model": a random walk tabulated on log-spaced annuli from 1% of a
// reduced mean free path out to where the classical diffusion tail has decayed by e^-20.
std::unique_ptr<RadialProfile> make_monte_carlo(const Coefficients& c, double thickness_mm,
                                                const ModelOptions& opt) {
  MonteCarloOptions mc;
  mc.photons = opt.mc_photons;
  mc.seed = opt.mc_seed;
  mc.threads = opt.mc_threads;
  mc.progress = opt.mc_progress;
  mc.thickness_mm = thickness_mm;
  const double mfp = c.mfp_reduced();
  const double outer = 20.0 / c.sigma_tr_classical() + 10.0 * mfp;
  mc.bin_edges_mm = log_bin_edges(0.01 * mfp, outer, 96);
  // Single scattering apart: exits after one scattering event are not tallied (the
  // renderer adds them in closed form, SingleScattering.h).
  if (opt.single_scattering_apart) mc.min_scattering_order = 2;
  const MonteCarloResult result = run_monte_carlo(c, mc);
  try {
    return std::make_unique<TabulatedProfile>(TabulatedProfile::from_monte_carlo(result));
  } catch (const std::invalid_argument& e) {
    // A dark medium (albedo near 0) sends too few photons back to tabulate R(r).
    throw std::invalid_argument(
        "photons: " + std::to_string(opt.mc_photons) + " Monte Carlo photons left too few annuli with "
        "reflectance to tabulate the profile (albedo " + message_number(c.albedo()) +
        "; raise the photon count) [" + e.what() + "]");
  }
}

}  // namespace

std::unique_ptr<RadialProfile> make_profile(Model model, const Coefficients& c,
                                            double thickness_mm, const ModelOptions& opt) {
  if (auto e = c.validate()) throw std::invalid_argument(e->what());
  switch (model) {
    case Model::Dipole: return std::make_unique<ClassicalDipole>(c);
    case Model::BetterDipole: return std::make_unique<BetterDipole>(c);
    case Model::Pbd:
      return std::make_unique<PhotonBeamDiffusion>(c, opt.pbd_samples, BeamSampling::Mis,
                                                   opt.single_scattering_apart);
    case Model::Burley: return std::make_unique<Burley>(c);
    case Model::Multipole:
      if (!(thickness_mm < std::numeric_limits<double>::infinity()))
        throw std::invalid_argument(
            "thickness: the multipole model describes a finite slab and needs a thickness "
            "(--thickness MM)");
      // Donner & Jensen put the source one reduced mean free path deep; a slab thinner
      // than that has its source outside and yields negative transmittance.
      if (!(thickness_mm > c.mfp_reduced()))
        throw std::invalid_argument(
            "thickness: the multipole model needs a slab thicker than one reduced mean free "
            "path (1/sigma_t' = " + std::to_string(c.mfp_reduced()) + " mm here), got " +
            std::to_string(thickness_mm) + " mm");
      return std::make_unique<Multipole>(c, thickness_mm, opt.multipole_pairs);
    case Model::MonteCarlo: return make_monte_carlo(c, thickness_mm, opt);
    // The table describes a semi-infinite medium. A finite thickness is ignored, as the
    // dipole, better dipole, PBD and Burley ignore it, rather than refused: scenes carry a
    // thickness for the slab model and for transmission (the viewer's builtin slab scene,
    // glTF "thickness"), and a user who switches such a material to mc-table in the
    // viewer's menu expects its reflectance profile, as with the other semi-infinite
    // models, not an error. The multipole is the model for a slab's own profile.
    // Any g: the isotropic table and the anisotropic layers (McTableProfile.h).
    case Model::McTable: return make_mc_table_profile(c, opt.single_scattering_apart);
    // Quantized diffusion (d'Eon & Irving 2011): semi-infinite, as the dipoles.
    case Model::Qd: return std::make_unique<QuantizedDiffusion>(c);
    case Model::Layered:
      throw std::invalid_argument(
          "model: layered describes a stack of layers, not one medium: give the layers "
          "(sss-fit --layers FILE.json, glTF extras.sss.layers)");
  }
  throw std::invalid_argument("unknown model");
}

RgbProfile::RgbProfile(Model model, const Medium& medium, const ModelOptions& opt)
    : model_(model) {
  if (auto e = medium.validate()) throw std::invalid_argument(e->what());
  for (int c = 0; c < 3; ++c) {
    ModelOptions channel_opt = opt;  // a channel's walk is a third of the progress
    if (opt.mc_progress) channel_opt.mc_progress = [&opt, c](double f) { opt.mc_progress((c + f) / 3.0); };
    try {
      channels_[c] = make_profile(model, medium.channel(c), medium.thickness_mm, channel_opt);
    } catch (const std::invalid_argument& e) {
      // mc-table's range errors name a field of one channel ("albedo: ...", "eta: ..."):
      // say which channel ("albedo[R]: ...", as Medium::validate does).
      const std::string what = e.what();
      const auto colon = what.find(": ");
      if (model != Model::McTable || colon == std::string::npos ||
          what.find('[') < colon)
        throw;
      throw std::invalid_argument(what.substr(0, colon) + "[" + kChannelNames[c] + "]" +
                                  what.substr(colon));
    }
  }
}

RgbProfile::RgbProfile(Model model, std::array<std::unique_ptr<RadialProfile>, 3> channels)
    : model_(model), channels_(std::move(channels)) {
  for (int c = 0; c < 3; ++c)
    if (!channels_[c]) throw std::invalid_argument(std::string("RgbProfile: channel ") + kChannelNames[c] + " is null");
}

Rgb RgbProfile::reflectance(double r) const {
  return {channels_[0]->reflectance(r), channels_[1]->reflectance(r),
          channels_[2]->reflectance(r)};
}

Rgb RgbProfile::transmittance(double r) const {
  return {channels_[0]->transmittance(r), channels_[1]->transmittance(r),
          channels_[2]->transmittance(r)};
}

Rgb RgbProfile::total_reflectance() const {
  return {channels_[0]->total_reflectance(), channels_[1]->total_reflectance(),
          channels_[2]->total_reflectance()};
}

Rgb RgbProfile::total_transmittance() const {
  return {channels_[0]->total_transmittance(), channels_[1]->total_transmittance(),
          channels_[2]->total_transmittance()};
}

double RgbProfile::support_radius() const {
  return std::max({channels_[0]->support_radius(), channels_[1]->support_radius(),
                   channels_[2]->support_radius()});
}

double RgbProfile::inner_radius() const {
  return std::min({channels_[0]->inner_radius(), channels_[1]->inner_radius(),
                   channels_[2]->inner_radius()});
}

}  // namespace sss::profiles
