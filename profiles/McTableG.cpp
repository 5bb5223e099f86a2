// mc-table along the Henyey–Greenstein g axis: the bracketing anisotropic layers, the
// warnings outside them, and the profile blended between two layers' (McTableProfile.h).
#include "profiles/McTableProfile.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace sss::profiles {

namespace {

const auto str = sss::message_number;
constexpr std::string_view kTooFewAnnuli = McTableProfile::kTooFewAnnuli;

}  // namespace

McTableGBracket mc_table_g_bracket(double g) {
  const McTableData& iso = shipped_mc_table();
  const std::vector<McTableData>& layers = shipped_mc_table_layers();
  McTableGBracket b;
  b.lo = &iso;
  if (!(g > 0.0)) return b;  // g <= 0 (and NaN, which Coefficients::validate refuses)
  double g_prev = 0.0;
  for (const McTableData& layer : layers) {
    if (g == layer.g) {
      b.lo = &layer;
      return b;
    }
    if (g < layer.g) {
      b.hi = &layer;
      b.t = (std::log1p(-g) - std::log1p(-g_prev)) / (std::log1p(-layer.g) - std::log1p(-g_prev));
      return b;
    }
    b.lo = &layer;
    g_prev = layer.g;
  }
  return b;  // above the last layer: that layer alone
}

std::optional<std::string> mc_table_g_warning(double g) {
  const std::vector<McTableData>& layers = shipped_mc_table_layers();
  const double g_max = layers.empty() ? 0.0 : layers.back().g;
  if (g < 0.0)
    return "g " + str(g) + " < 0: mc-table tabulates 0 <= g <= " + str(g_max) +
           "; looked up in the isotropic table by the similarity relation (sigma_s' = sigma_s "
           "(1 - g))";
  if (g > g_max)
    return "g " + str(g) + " > " + str(g_max) + ": mc-table tabulates 0 <= g <= " + str(g_max) +
           "; looked up in the g = " + str(g_max) +
           " layer by the similarity relation (its reduced coefficients)";
  return std::nullopt;
}

std::vector<std::string> mc_table_g_warnings(const Medium& medium) {
  std::vector<std::string> out;
  for (int c = 0; c < 3; ++c) {
    bool said = false;
    for (int k = 0; k < c; ++k) said |= medium.g[k] == medium.g[c];
    if (said) continue;
    if (const auto w = mc_table_g_warning(medium.g[c]))
      out.push_back(std::string("g[") + "RGB"[c] + "]: " + *w);
  }
  return out;
}

McTableTotal mc_table_total_any_g(const Coefficients& c, bool single_scattering_apart) {
  const McTableGBracket b = mc_table_g_bracket(c.g);
  const McTableTotal lo = mc_table_total(c, *b.lo, single_scattering_apart);
  if (!b.hi) return lo;
  const McTableTotal hi = mc_table_total(c, *b.hi, single_scattering_apart);
  // The layers' walks share their seed, so their errors may be correlated: the weighted
  // sum bounds the interpolated error whatever the correlation.
  return {(1.0 - b.t) * lo.total + b.t * hi.total,
          (1.0 - b.t) * lo.stderr_ + b.t * hi.stderr_};
}

namespace {

// R(r) between two g nodes: (1 - t) R_lo + t R_hi, every quantity likewise.
class McTableGBlend final : public RadialProfile {
 public:
  McTableGBlend(std::unique_ptr<McTableProfile> lo, std::unique_ptr<McTableProfile> hi, double t)
      : lo_(std::move(lo)), hi_(std::move(hi)), t_(t) {}
  double reflectance(double r) const override {
    return (1.0 - t_) * lo_->reflectance(r) + t_ * hi_->reflectance(r);
  }
  double total_reflectance() const override {
    return (1.0 - t_) * lo_->total_reflectance() + t_ * hi_->total_reflectance();
  }
  double support_radius() const override {
    return std::max(lo_->support_radius(), hi_->support_radius());
  }
  double inner_radius() const override { return lo_->inner_radius(); }

 private:
  std::unique_ptr<McTableProfile> lo_, hi_;
  double t_;
};

// The lookup in table t, or null where t's walks are too few to shape R(r) there (the
// constructor's kTooFewAnnuli error); any other error propagates.
std::unique_ptr<McTableProfile> try_profile(const Coefficients& c, const McTableData& t,
                                            bool apart) {
  try {
    return std::make_unique<McTableProfile>(c, t, apart);
  } catch (const std::invalid_argument& e) {
    if (std::string_view(e.what()).starts_with(kTooFewAnnuli)) return nullptr;
    throw;
  }
}

}  // namespace

std::unique_ptr<RadialProfile> make_mc_table_profile(const Coefficients& c,
                                                     bool single_scattering_apart) {
  if (auto e = c.validate()) throw std::invalid_argument(e->what());
  const McTableGBracket b = mc_table_g_bracket(c.g);
  // A layer's walks (2^18, a sixteenth of the isotropic table's) can be too few to shape
  // R(r) at its darkest nodes for a high η and g: at α' = 0.01 and g = 0.95 a walk's real
  // albedo is 0.17 and HG sends almost nothing back up, and at η = 2.5 little of that
  // leaves. Where a layer's lookup finds fewer than two reliable annuli, the next node
  // towards g = 0 stands in for it (ultimately the isotropic table, 2^22 walks, whose
  // errors propagate), so every medium that had a profile before the layers still has
  // one. Each profile is built once.
  std::unique_ptr<McTableProfile> hi =
      b.hi ? try_profile(c, *b.hi, single_scattering_apart) : nullptr;
  const McTableData* node = b.lo;
  std::unique_ptr<McTableProfile> lo;
  const std::vector<McTableData>& layers = shipped_mc_table_layers();
  while (node != &shipped_mc_table() && !(lo = try_profile(c, *node, single_scattering_apart))) {
    const auto k = static_cast<std::size_t>(node - layers.data());
    node = k == 0 ? &shipped_mc_table() : &layers[k - 1];
    hi.reset();  // no longer the neighbour of the node in use
  }
  if (!lo) lo = std::make_unique<McTableProfile>(c, *node, single_scattering_apart);
  if (!hi) return lo;
  return std::make_unique<McTableGBlend>(std::move(lo), std::move(hi), b.t);
}

}  // namespace sss::profiles
