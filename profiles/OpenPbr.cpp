#include "profiles/OpenPbr.h"

#include "profiles/ArtistMapping.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace sss::profiles {

namespace {

const auto str = sss::message_number;

std::string channel_field(const char* key, int c) { return std::string(key) + "[" + std::to_string(c) + "]"; }

}  // namespace

double single_scattering_albedo(double multiscatter, double g) {
  const double c = std::clamp(multiscatter, 0.0, 1.0);
  const double s = 4.09712 + 4.20863 * c - std::sqrt(9.59217 + 41.6808 * c + 17.7126 * c * c);
  return std::clamp((1.0 - s * s) / (1.0 - g * s * s), 0.0, 1.0);
}

double multiscatter_albedo(double single_scattering, double g) {
  const double a = std::clamp(single_scattering, 0.0, 1.0);
  const double s = std::sqrt((1.0 - a) / (1.0 - a * g));
  return (1.0 - s) * (1.0 - 0.139 * s) / (1.0 + 1.17 * s);
}

std::string_view albedo_inversion_name(AlbedoInversion inversion) {
  return inversion == AlbedoInversion::Model ? "model" : "van-de-hulst";
}

std::optional<AlbedoInversion> parse_albedo_inversion(std::string_view name) {
  if (name == "van-de-hulst") return AlbedoInversion::VanDeHulst;
  if (name == "model") return AlbedoInversion::Model;
  return std::nullopt;
}

Rgb OpenPbrSubsurface::mean_free_path_mm() const {
  return {radius_mm * radius_scale[0], radius_mm * radius_scale[1], radius_mm * radius_scale[2]};
}

OpenPbrSubsurface openpbr_from_standard_surface(const StandardSurfaceSubsurface& s) {
  OpenPbrSubsurface p;
  p.color = s.color;
  const double longest = std::max({s.radius[0], s.radius[1], s.radius[2]});
  p.radius_mm = s.scale * longest;
  for (int c = 0; c < 3; ++c) p.radius_scale[c] = longest > 0.0 ? s.radius[c] / longest : 0.0;
  p.anisotropy = s.anisotropy;
  p.ior = s.ior;
  return p;
}

StandardSurfaceSubsurface standard_surface_from_openpbr(const OpenPbrSubsurface& p) {
  StandardSurfaceSubsurface s;
  s.color = p.color;
  s.radius = p.radius_scale;
  s.scale = p.radius_mm;
  s.anisotropy = p.anisotropy;
  s.ior = p.ior;
  return s;
}

std::optional<FieldError> validate(const OpenPbrSubsurface& p) {
  for (int c = 0; c < 3; ++c)
    if (!(p.color[c] > 0.0 && p.color[c] < 1.0))
      return FieldError{channel_field("subsurface_color", c),
                        "must lie strictly between 0 and 1 (0 scatters nothing; 1 absorbs nothing "
                        "and has no finite diffusion length), got " + str(p.color[c])};
  if (!(std::isfinite(p.radius_mm) && p.radius_mm > 0.0))
    return FieldError{"subsurface_radius", "must be a finite number of mm > 0, got " + str(p.radius_mm)};
  for (int c = 0; c < 3; ++c)
    if (!(p.radius_scale[c] > 0.0 && p.radius_scale[c] <= 1.0))
      return FieldError{channel_field("subsurface_radius_scale", c),
                        "must lie in (0, 1] (0 is an infinite extinction), got " + str(p.radius_scale[c])};
  const Rgb r = p.mean_free_path_mm();
  for (int c = 0; c < 3; ++c)
    if (r[c] < 10.0 / kMaxCoefficient || r[c] > 1.0 / kMinSigmaTReduced)
      return FieldError{channel_field("subsurface_radius_scale", c),
                        "gives a mean free path of " + str(r[c]) + " mm, outside [" +
                            str(10.0 / kMaxCoefficient) + ", " + str(1.0 / kMinSigmaTReduced) + "] mm"};
  if (!(std::fabs(p.anisotropy) < 1.0))
    return FieldError{"subsurface_scatter_anisotropy", "must lie in (-1, 1), got " + str(p.anisotropy)};
  if (!(p.ior >= kEtaMin && p.ior <= kEtaMax))
    return FieldError{"specular_ior", "must lie in [" + str(kEtaMin) + ", " + str(kEtaMax) +
                                          "] (the index the models' Fresnel fits cover), got " + str(p.ior)};
  return std::nullopt;
}

std::optional<FieldError> validate(const StandardSurfaceSubsurface& s) {
  for (int c = 0; c < 3; ++c)
    if (!(s.radius[c] > 0.0 && std::isfinite(s.radius[c])))
      return FieldError{channel_field("subsurface_radius", c),
                        "must be a finite number > 0 (a mean free path), got " + str(s.radius[c])};
  if (!(s.scale > 0.0 && std::isfinite(s.scale)))
    return FieldError{"subsurface_scale", "must be a finite number of mm > 0, got " + str(s.scale)};
  auto e = validate(openpbr_from_standard_surface(s));
  if (!e) return e;
  // OpenPBR's field → Standard Surface's (its radius_scale is the radius colour).
  static const std::pair<const char*, const char*> kNames[] = {
      {"subsurface_radius_scale", "subsurface_radius"}, {"subsurface_radius", "subsurface_scale"},
      {"subsurface_scatter_anisotropy", "subsurface_anisotropy"}, {"specular_ior", "specular_IOR"}};
  for (const auto& [openpbr, standard] : kNames) {
    const std::size_t n = std::string_view(openpbr).size();
    if (e->field.compare(0, n, openpbr) == 0 && (e->field.size() == n || e->field[n] == '[')) {
      e->field = standard + e->field.substr(n);
      break;
    }
  }
  return e;
}

std::variant<Medium, FieldError> medium_from_openpbr(const OpenPbrSubsurface& p,
                                                     AlbedoInversion inversion, Model model,
                                                     const ModelOptions& opt) {
  if (auto e = validate(p)) return *e;
  if (inversion == AlbedoInversion::Model && model == Model::Layered)
    return FieldError{"model", "layered describes a stack, not one medium: choose a model of one "
                               "medium to invert the subsurface colour through"};
  const Model through = model == Model::MonteCarlo ? Model::McTable : model;
  const Rgb r = p.mean_free_path_mm();
  Medium m;
  for (int c = 0; c < 3; ++c) {
    double alpha = 0.0;
    if (inversion == AlbedoInversion::VanDeHulst) {
      alpha = single_scattering_albedo(p.color[c], p.anisotropy);
    } else {
      auto inverted = invert_total_reflectance(through, p.color[c], p.ior, p.anisotropy,
                                               std::numeric_limits<double>::infinity(), opt);
      if (auto* e = std::get_if<FieldError>(&inverted)) {
        if (e->field == "color") e->field = "subsurface_color";
        e->field += "[" + std::to_string(c) + "]";
        return *e;
      }
      // The reduced albedo α' = α(1 - g) / (1 - α g), solved for α.
      const double ap = std::get<double>(inverted);
      alpha = ap / (1.0 - p.anisotropy + ap * p.anisotropy);
    }
    const double sigma_t = 1.0 / r[c];
    m.sigma_s[c] = alpha * sigma_t;
    m.sigma_a[c] = (1.0 - alpha) * sigma_t;
    m.g[c] = p.anisotropy;
    m.eta[c] = p.ior;
    // A colour so close to 1 that nothing absorbs within the coefficients' range.
    if (auto e = m.channel(c).validate())
      return FieldError{channel_field("subsurface_color", c),
                        str(p.color[c]) + " gives a medium the models cannot take (" + e->what() + ")"};
  }
  return m;
}

OpenPbrSubsurface openpbr_from_medium(const Medium& m) {
  OpenPbrSubsurface p;
  Rgb r{};
  double g = 0.0, eta = 0.0;
  for (int c = 0; c < 3; ++c) {
    r[c] = 1.0 / (m.sigma_a[c] + m.sigma_s[c]);
    g += m.g[c] / 3.0;
    eta += m.eta[c] / 3.0;
  }
  p.radius_mm = std::max({r[0], r[1], r[2]});
  for (int c = 0; c < 3; ++c) {
    p.radius_scale[c] = r[c] / p.radius_mm;
    p.color[c] = multiscatter_albedo(m.sigma_s[c] / (m.sigma_a[c] + m.sigma_s[c]), g);
  }
  p.anisotropy = g;
  p.ior = eta;
  return p;
}

}  // namespace sss::profiles
