// LayeredProfile: layered media in the Hankel domain. Layered.h states the model and its
// choices; LayeredGrid.h the transform's numerics; LayeredAdding.cpp and
// LayeredDiffusion.cpp the two couplings.
#include "profiles/Layered.h"
#include "profiles/LayeredImpl.h"

#include "profiles/ClassicalDipole.h"
#include "profiles/Fresnel.h"
#include "profiles/McTableProfile.h"
#include "profiles/Multipole.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace sss::profiles {

using namespace layered;

namespace detail {
const std::vector<double>& hankel_grid() { return hankel().x; }
std::vector<double> hankel_forward(const std::vector<double>& f, double L) { return forward(f, L); }
std::vector<double> hankel_inverse(const std::vector<double>& F, double L) { return inverse(F, L); }
}  // namespace detail

std::optional<FieldError> validate_layers(const LayerStack& stack) {
  if (stack.empty()) return FieldError{"layers", "needs at least one layer"};
  if (stack.size() > static_cast<std::size_t>(kMaxLayers))
    return FieldError{"layers", "at most " + std::to_string(kMaxLayers) + " layers, got " +
                                    std::to_string(stack.size())};
  for (std::size_t k = 0; k < stack.size(); ++k) {
    const Medium& m = stack[k];
    const bool last = k + 1 == stack.size();
    if (std::isnan(m.thickness_mm) || !(m.thickness_mm > 0.0))
      return FieldError{layer_field(k, "thickness_mm"),
                        "must be a number > 0 (mm), got " + message_number(m.thickness_mm)};
    if (!last && !m.is_slab())
      return FieldError{layer_field(k, "thickness_mm"),
                        "only the last layer may be semi-infinite; this one needs a thickness"};
    if (auto e = m.validate()) return FieldError{layer_field(k, e->field), e->message};
    // Both couplings put the source (or a layer's own source) one reduced mean free path
    // deep: a finite layer must be thicker than that (Multipole.h).
    if (m.is_slab())
      for (int c = 0; c < 3; ++c) {
        const double mfp = m.channel(c).mfp_reduced();
        if (!(m.thickness_mm > mfp))
          return FieldError{layer_field(k, std::string("thickness_mm[") + kChannelNames[c] + "]"),
                            "a layer must be thicker than one reduced mean free path (1/sigma_t' = " +
                                message_number(mfp) + " mm here), got " +
                                message_number(m.thickness_mm) + " mm"};
      }
    for (int c = 0; c < 3; ++c)
      if (m.eta[c] != stack[0].eta[c])
        return FieldError{layer_field(k, std::string("eta[") + kChannelNames[c] + "]"),
                          "must equal layers[0]'s (" + message_number(stack[0].eta[c]) +
                              "): the interfaces between layers are index-matched"};
  }
  return std::nullopt;
}

std::vector<Layer> channel_layers(const LayerStack& stack, int channel) {
  std::vector<Layer> out;
  for (const Medium& m : stack) out.push_back({m.channel(channel), m.thickness_mm});
  return out;
}

namespace {

// Per-layer checks (validate_layers does the RGB stack; this is the one-channel form).
void check_layers(const std::vector<Layer>& layers) {
  const std::size_t n = layers.size();
  const double eta = layers[0].c.eta;
  for (std::size_t k = 0; k < n; ++k) {
    const Layer& l = layers[k];
    if (auto e = l.c.validate()) throw std::invalid_argument(layer_field(k, e->what()));
    if (l.c.eta != eta)
      throw std::invalid_argument(layer_field(k, "eta") +
                                  ": must equal layers[0]'s: the interfaces between layers are "
                                  "index-matched");
    const bool last = k + 1 == n;
    if (std::isnan(l.thickness_mm) || !(l.thickness_mm > 0.0) ||
        (!last && !std::isfinite(l.thickness_mm)))
      throw std::invalid_argument(layer_field(k, "thickness_mm") +
                                  ": must be a finite number > 0 (only the last layer may be "
                                  "semi-infinite), got " + message_number(l.thickness_mm));
    // Donner & Jensen put the source one reduced mean free path deep: a thinner layer has
    // its source below it (negative transmittance; Multipole.h).
    if (std::isfinite(l.thickness_mm) && !(l.thickness_mm > l.c.mfp_reduced()))
      throw std::invalid_argument(
          layer_field(k, "thickness_mm") + ": the multipole describes a layer thicker than one "
          "reduced mean free path (1/sigma_t' = " + message_number(l.c.mfp_reduced()) +
          " mm here), got " + message_number(l.thickness_mm) + " mm");
  }
}

}  // namespace

LayeredProfile::LayeredProfile(const std::vector<Layer>& layers, const ModelOptions& opt,
                               Model base, LayerCoupling coupling)
    : impl_(std::make_unique<Impl>()) {
  if (base == Model::Multipole || base == Model::MonteCarlo || base == Model::Layered)
    throw std::invalid_argument("model: the base of a stack must be a semi-infinite model "
                                "(dipole, better-dipole, pbd, burley, mc-table, qd), got " +
                                std::string(model_name(base)));
  if (layers.empty()) throw std::invalid_argument("layers: needs at least one layer");
  check_layers(layers);
  impl_->layers = layers;
  if (coupling == LayerCoupling::Diffusion)
    build_diffusion(layers, opt, base);
  else
    impl_->build_adding(layers, opt, base);
}

LayeredProfile::~LayeredProfile() = default;

double LayeredProfile::reflectance(double r) const { return impl_->combined(r); }

double LayeredProfile::transmittance(double r) const {
  const Impl& s = *impl_;
  if (s.one_finite) return s.top_finite->down.transmittance(r);
  if (!s.has_trans) return 0.0;
  return std::max(0.0, at_grid(s.trans, s.L, r));
}

double LayeredProfile::total_reflectance() const { return impl_->total_r; }
double LayeredProfile::total_transmittance() const { return impl_->total_t; }
double LayeredProfile::lowest_frequency_reflectance() const { return impl_->grid_total_r; }
double LayeredProfile::lowest_frequency_transmittance() const { return impl_->grid_total_t; }
double LayeredProfile::diffusion_total_reflectance() const { return impl_->exact_total_r; }
double LayeredProfile::diffusion_total_transmittance() const { return impl_->exact_total_t; }
double LayeredProfile::support_radius() const { return impl_->support; }
double LayeredProfile::inner_radius() const { return impl_->inner; }
std::size_t LayeredProfile::layer_count() const { return impl_->layers.size(); }

std::vector<std::string> layered_g_warnings(const LayerStack& stack, Model base) {
  if (stack.empty() || base != Model::McTable) return {};
  std::vector<std::string> out = mc_table_g_warnings(stack.front());
  for (std::string& w : out) w = "top layer " + w;
  return out;
}

RgbProfile make_layered_rgb_profile(const LayerStack& stack, const ModelOptions& opt,
                                    Model base, LayerCoupling coupling) {
  if (auto e = validate_layers(stack)) throw std::invalid_argument(e->what());
  std::array<std::unique_ptr<RadialProfile>, 3> ch;
  for (int c = 0; c < 3; ++c) {
    try {
      ch[c] = std::make_unique<LayeredProfile>(channel_layers(stack, c), opt, base, coupling);
    } catch (const std::invalid_argument& e) {
      // Name the channel: "layers[0].thickness_mm[G]: ..."
      const std::string what = e.what();
      const auto colon = what.find(": ");
      if (what.rfind("layers[", 0) != 0 || colon == std::string::npos ||
          what.find('[', what.find('.')) < colon)
        throw;
      throw std::invalid_argument(what.substr(0, colon) + "[" + kChannelNames[c] + "]" +
                                  what.substr(colon));
    }
  }
  return RgbProfile(Model::Layered, std::move(ch));
}

}  // namespace sss::profiles
