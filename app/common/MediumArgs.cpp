#include "MediumArgs.h"

#include "profiles/ArtistMapping.h"
#include "profiles/OpenPbr.h"
#include "profiles/Presets.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdlib>
#include <span>
#include <sstream>

namespace sss::app {

using profiles::Medium;

void add_medium_options(CLI::App& cmd, MediumArgs& a) {
  cmd.add_option("--preset", a.preset, "Measured medium of Jensen et al. 2001 (see `presets`)");
  cmd.add_option("--sigma-a", a.sigma_a, "Absorption coefficient, mm^-1, (0, 1e6]: R,G,B or one value");
  cmd.add_option("--sigma-s", a.sigma_s, "Scattering coefficient, mm^-1, [0, 1e6]: R,G,B or one value");
  cmd.add_option("--color", a.color,
                 "Artist mode: diffuse colour (total reflectance) R,G,B in (0,1)");
  cmd.add_option("--mfp", a.mfp, "Artist mode: reduced mean free path 1/sigma_t', mm, [1e-5, 1e6]: R,G,B");
  cmd.add_option("--subsurface-color", a.subsurface_color,
                 "OpenPBR / Standard Surface mode: subsurface_color R,G,B in (0,1), linear Rec.709");
  cmd.add_option("--subsurface-radius", a.subsurface_radius,
                 "OpenPBR: subsurface_radius, mm (one number); Standard Surface: subsurface_radius "
                 "R,G,B (the mean free path per channel, times --subsurface-scale)");
  cmd.add_option("--subsurface-radius-scale", a.subsurface_radius_scale,
                 "OpenPBR: subsurface_radius_scale R,G,B in (0,1] (default 1,0.5,0.25)");
  cmd.add_option("--subsurface-scale", a.subsurface_scale,
                 "Standard Surface: subsurface_scale, mm (default 1)");
  cmd.add_option("--albedo-inversion", a.albedo_inversion,
                 "How --subsurface-color becomes an albedo: van-de-hulst (the spec's, default) or "
                 "model (the model's total reflectance at --eta)");
  cmd.add_option("--g", a.g, "Henyey-Greenstein anisotropy in (-1,1) (default 0)");
  cmd.add_option("--eta", a.eta, "Refractive index of the medium, 1..2.5 (default 1.3; preset's own)");
  cmd.add_option("--thickness", a.thickness, "Slab thickness, mm (default: semi-infinite)");
}

std::variant<double, FieldError> parse_number(const std::string& option,
                                              const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (text.empty() || end == begin || *end != '\0' || errno == ERANGE)
    return FieldError{option, "expected a number, got '" + text + "'"};
  return v;
}

std::variant<Rgb, FieldError> parse_rgb(const std::string& option, const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) parts.push_back(item);
  if (!text.empty() && text.back() == ',') parts.push_back("");
  if (parts.size() != 1 && parts.size() != 3)
    return FieldError{option, "expected R,G,B or one number, got '" + text + "'"};
  Rgb out{};
  for (int c = 0; c < 3; ++c) {
    auto v = parse_number(option, parts[parts.size() == 1 ? 0 : c]);
    if (auto* e = std::get_if<FieldError>(&v)) {
      e->message = "expected R,G,B or one number, got '" + text + "'";
      return *e;
    }
    out[c] = std::get<double>(v);
  }
  return out;
}

namespace {

// `e` with its field's leading spec name ("subsurface_radius_scale[1]") replaced by the
// option that set it ("--subsurface-radius-scale[1]"): the first prefix that matches, so
// a longer name must come before a name it starts with.
FieldError named_by_option(FieldError e, std::span<const std::pair<const char*, const char*>> options) {
  for (const auto& [spec, option] : options)
    if (e.field.rfind(spec, 0) == 0) {
      e.field = option + e.field.substr(std::strlen(spec));
      break;
    }
  return e;
}

std::string rgb_text(const Rgb& v) {
  std::ostringstream s;
  s << v[0] << ',' << v[1] << ',' << v[2];
  return s.str();
}

}  // namespace

namespace {

// --g, --eta and --thickness, shared by every way of giving a medium.
struct Scalars {
  double g = 0.0, eta = 1.3, thickness = std::numeric_limits<double>::infinity();
  bool eta_given = false;
};

std::variant<Scalars, FieldError> parse_scalars(const MediumArgs& a) {
  Scalars out;
  if (!a.g.empty()) {
    auto v = parse_number("--g", a.g);
    if (auto* e = std::get_if<FieldError>(&v)) return *e;
    out.g = std::get<double>(v);
  }
  out.eta_given = !a.eta.empty();
  if (out.eta_given) {
    auto v = parse_number("--eta", a.eta);
    if (auto* e = std::get_if<FieldError>(&v)) return *e;
    out.eta = std::get<double>(v);
  }
  if (!a.thickness.empty()) {
    auto v = parse_number("--thickness", a.thickness);
    if (auto* e = std::get_if<FieldError>(&v)) return *e;
    out.thickness = std::get<double>(v);
  }
  return out;
}

// --preset NAME [--eta]: a preset's reduced coefficients.
std::optional<FieldError> from_preset(const MediumArgs& a, const Scalars& k, ResolvedMedium& out,
                                      std::ostringstream& desc) {
  const bool eta_given = k.eta_given;
  const double eta = k.eta;
  const profiles::Preset* p = profiles::find_preset(a.preset);
  if (!p)
    return FieldError{"--preset", "unknown preset '" + a.preset +
                                      "'; known: " + profiles::preset_names()};
  if (!a.g.empty())
    return FieldError{"--g", "presets give the reduced scattering σs' only (g = 0); "
                             "use --sigma-a/--sigma-s with --g instead"};
  out.medium = profiles::preset_medium(*p);
  if (eta_given) out.medium.eta = {eta, eta, eta};
  desc << "preset " << p->name;
  if (eta_given) desc << ", eta " << eta;
  return std::nullopt;
}

// --sigma-a and --sigma-s [--g] [--eta].
std::optional<FieldError> from_coefficients(const MediumArgs& a, const Scalars& k, ResolvedMedium& out,
                                            std::ostringstream& desc) {
  const double g = k.g, eta = k.eta;
  if (a.sigma_a.empty()) return FieldError{"--sigma-a", "is required with --sigma-s"};
  if (a.sigma_s.empty()) return FieldError{"--sigma-s", "is required with --sigma-a"};
  auto sa = parse_rgb("--sigma-a", a.sigma_a);
  if (auto* e = std::get_if<FieldError>(&sa)) return *e;
  auto ss = parse_rgb("--sigma-s", a.sigma_s);
  if (auto* e = std::get_if<FieldError>(&ss)) return *e;
  out.medium.sigma_a = std::get<Rgb>(sa);
  out.medium.sigma_s = std::get<Rgb>(ss);
  out.medium.g = {g, g, g};
  out.medium.eta = {eta, eta, eta};
  desc << "sigma_a " << rgb_text(out.medium.sigma_a) << " sigma_s "
       << rgb_text(out.medium.sigma_s) << " /mm, g " << g << ", eta " << eta;
  return std::nullopt;
}

// Standard Surface's subsurface (--subsurface-radius R,G,B or --subsurface-scale) as
// OpenPBR's, or the option that is wrong.
std::variant<profiles::OpenPbrSubsurface, FieldError> from_standard_surface_args(
    const MediumArgs& a, const Rgb& color, const Rgb& radius, double g, double ior) {
  profiles::StandardSurfaceSubsurface ss;
  ss.color = color;
  ss.radius = radius;
  if (!a.subsurface_scale.empty()) {
    auto v = parse_number("--subsurface-scale", a.subsurface_scale);
    if (auto* e = std::get_if<FieldError>(&v)) return *e;
    ss.scale = std::get<double>(v);
  }
  ss.anisotropy = g;
  ss.ior = ior;
  if (auto e = profiles::validate(ss)) {
    // Standard Surface's field → the option that set it.
    static const std::pair<const char*, const char*> kOptions[] = {
        {"subsurface_color", "--subsurface-color"}, {"subsurface_radius", "--subsurface-radius"},
        {"subsurface_scale", "--subsurface-scale"}, {"subsurface_anisotropy", "--g"},
        {"specular_IOR", "--eta"}};
    return named_by_option(std::move(*e), kOptions);
  }
  return profiles::openpbr_from_standard_surface(ss);
}

// OpenPBR's subsurface: one radius, an optional radius scale.
std::variant<profiles::OpenPbrSubsurface, FieldError> from_openpbr_args(
    const MediumArgs& a, const Rgb& color, const Rgb& radius, double g, double ior) {
  profiles::OpenPbrSubsurface p;
  p.color = color;
  p.radius_mm = radius[0];
  if (!a.subsurface_radius_scale.empty()) {
    auto v = parse_rgb("--subsurface-radius-scale", a.subsurface_radius_scale);
    if (auto* e = std::get_if<FieldError>(&v)) return *e;
    p.radius_scale = std::get<Rgb>(v);
  }
  p.anisotropy = g;
  p.ior = ior;
  return p;
}

// OpenPBR's or Standard Surface's --subsurface-* parameters, inverted to coefficients.
std::optional<FieldError> from_openpbr(const MediumArgs& a, const Scalars& k, profiles::Model model,
                                       const profiles::ModelOptions& opt, ResolvedMedium& out,
                                       std::ostringstream& desc) {
  const double g = k.g, eta = k.eta;
  const bool eta_given = k.eta_given;
  if (a.subsurface_color.empty()) return FieldError{"--subsurface-color", "is required with --subsurface-radius"};
  if (a.subsurface_radius.empty()) return FieldError{"--subsurface-radius", "is required with --subsurface-color"};
  auto col = parse_rgb("--subsurface-color", a.subsurface_color);
  if (auto* e = std::get_if<FieldError>(&col)) return *e;
  auto radius = parse_rgb("--subsurface-radius", a.subsurface_radius);
  if (auto* e = std::get_if<FieldError>(&radius)) return *e;
  // Standard Surface's radius is a colour; OpenPBR's one length.
  const bool standard_surface =
      !a.subsurface_scale.empty() || a.subsurface_radius.find(',') != std::string::npos;
  if (standard_surface && !a.subsurface_radius_scale.empty())
    return FieldError{"--subsurface-radius-scale",
                      "is OpenPBR's; with Standard Surface's --subsurface-radius R,G,B or "
                      "--subsurface-scale the radius is the colour"};
  profiles::AlbedoInversion inversion = profiles::AlbedoInversion::VanDeHulst;
  if (!a.albedo_inversion.empty()) {
    const auto parsed = profiles::parse_albedo_inversion(a.albedo_inversion);
    if (!parsed)
      return FieldError{"--albedo-inversion", "expected van-de-hulst or model, got '" + a.albedo_inversion + "'"};
    inversion = *parsed;
  }
  // Both default to OpenPBR's specular_ior, 1.5.
  const double ior = eta_given ? eta : 1.5;
  auto params = standard_surface
                    ? from_standard_surface_args(a, std::get<Rgb>(col), std::get<Rgb>(radius), g, ior)
                    : from_openpbr_args(a, std::get<Rgb>(col), std::get<Rgb>(radius), g, ior);
  if (auto* e = std::get_if<FieldError>(&params)) return *e;
  const profiles::OpenPbrSubsurface p = std::get<profiles::OpenPbrSubsurface>(params);
  auto m = profiles::medium_from_openpbr(p, inversion, model, opt);
  if (auto* e = std::get_if<FieldError>(&m)) {
    // The spec's field → the option that set it.
    static const std::pair<const char*, const char*> kOptions[] = {
        {"subsurface_color", "--subsurface-color"}, {"subsurface_radius_scale", "--subsurface-radius-scale"},
        {"subsurface_radius", "--subsurface-radius"}, {"subsurface_scatter_anisotropy", "--g"},
        {"specular_ior", "--eta"}};
    return named_by_option(std::move(*e), kOptions);
  }
  out.medium = std::get<Medium>(m);
  out.openpbr = p;
  out.inversion = inversion;
  out.standard_surface = standard_surface;
  const Rgb mfp = p.mean_free_path_mm();
  desc << (standard_surface ? "Standard Surface" : "OpenPBR") << " subsurface color "
       << rgb_text(p.color) << ", mean free path " << rgb_text(mfp) << " mm via "
       << profiles::albedo_inversion_name(inversion);
  if (inversion == profiles::AlbedoInversion::Model)
    desc << " (" << profiles::model_name(model == profiles::Model::MonteCarlo ? profiles::Model::McTable : model) << ")";
  desc << ", g " << p.anisotropy << ", ior " << p.ior << " = sigma_a " << rgb_text(out.medium.sigma_a)
       << " sigma_s " << rgb_text(out.medium.sigma_s) << " /mm";
  return std::nullopt;
}

// --color and --mfp, an artist's colour and mean free path, inverted through the model.
std::optional<FieldError> from_artist(const MediumArgs& a, const Scalars& k, profiles::Model model,
                                      const profiles::ModelOptions& opt, ResolvedMedium& out,
                                      std::ostringstream& desc) {
  const double g = k.g, eta = k.eta, thickness = k.thickness;
  if (a.color.empty()) return FieldError{"--color", "is required with --mfp"};
  if (a.mfp.empty()) return FieldError{"--mfp", "is required with --color"};
  auto col = parse_rgb("--color", a.color);
  if (auto* e = std::get_if<FieldError>(&col)) return *e;
  auto mfp = parse_rgb("--mfp", a.mfp);
  if (auto* e = std::get_if<FieldError>(&mfp)) return *e;
  profiles::ArtistParameters ap{std::get<Rgb>(col), std::get<Rgb>(mfp), eta, g, thickness};
  // mc has no total to invert before its walk has run: it inverts through mc-table,
  // whose total is the same Monte Carlo tabulated (within 0.2%, README "How right is
  // each model?").
  const profiles::Model inversion =
      model == profiles::Model::MonteCarlo ? profiles::Model::McTable : model;
  auto m = profiles::medium_from_artist(inversion, ap, opt);
  if (auto* e = std::get_if<FieldError>(&m)) {
    e->field = "--" + e->field;
    return *e;
  }
  out.medium = std::get<Medium>(m);
  // The coefficients it came to, so that the user sees what was rendered or fitted.
  desc << "color " << rgb_text(ap.color) << ", mfp " << rgb_text(ap.mfp_mm) << " mm via "
       << profiles::model_name(inversion) << ", g " << g << ", eta " << eta << " = sigma_a "
       << rgb_text(out.medium.sigma_a) << " sigma_s " << rgb_text(out.medium.sigma_s) << " /mm";
  return std::nullopt;
}

// The medium's own field (Medium::validate) as the option the user typed, e.g. "sigma_a[G]"
// as "--sigma-a[G]".
std::string option_of_field(const std::string& field, const MediumArgs& a, bool by_preset) {
  std::string f = field;
  for (const char* key : {"sigma_a", "sigma_s"})
    if (f.rfind(key, 0) == 0) f = std::string(by_preset ? "--preset " + a.preset + ": " : "--") +
                                   (key[6] == 'a' ? "sigma-a" : "sigma-s") + f.substr(7);
  if (f.rfind("thickness", 0) == 0) f = "--thickness";
  if (f.rfind("eta", 0) == 0) f = "--eta" + f.substr(3);
  if (f.rfind("g[", 0) == 0) f = "--g" + f.substr(1);
  // sigma_t[C] is made of both options (and --g for the reduced one).
  if (f.rfind("sigma_t", 0) == 0)
    f = std::string(by_preset ? "--preset " + a.preset + ": " : "") + "--sigma-a/--sigma-s" +
        f.substr(7);
  return f;
}

}  // namespace

std::variant<ResolvedMedium, FieldError> resolve_medium(const MediumArgs& a,
                                                        profiles::Model model,
                                                        const profiles::ModelOptions& opt) {
  const bool by_preset = !a.preset.empty();
  const bool by_coeff = !a.sigma_a.empty() || !a.sigma_s.empty();
  const bool by_artist = !a.color.empty() || !a.mfp.empty();
  const bool by_openpbr = !a.subsurface_color.empty() || !a.subsurface_radius.empty() ||
                          !a.subsurface_radius_scale.empty() || !a.subsurface_scale.empty();
  if (by_preset + by_coeff + by_artist + by_openpbr == 0)
    return FieldError{"MEDIUM", "give --preset NAME, or --sigma-a and --sigma-s, or --color and --mfp, "
                                "or --subsurface-color and --subsurface-radius"};
  if (by_preset + by_coeff + by_artist + by_openpbr > 1)
    return FieldError{"MEDIUM", "--preset, --sigma-a/--sigma-s, --color/--mfp and --subsurface-* "
                                "exclude each other"};
  if (!a.albedo_inversion.empty() && !by_openpbr)
    return FieldError{"--albedo-inversion", "applies only to --subsurface-color"};
  auto scalars = parse_scalars(a);
  if (auto* e = std::get_if<FieldError>(&scalars)) return *e;
  const Scalars& k = std::get<Scalars>(scalars);

  ResolvedMedium out;
  std::ostringstream desc;
  const std::optional<FieldError> error =
      by_preset    ? from_preset(a, k, out, desc)
      : by_coeff   ? from_coefficients(a, k, out, desc)
      : by_openpbr ? from_openpbr(a, k, model, opt, out, desc)
                   : from_artist(a, k, model, opt, out, desc);
  if (error) return *error;
  out.medium.thickness_mm = k.thickness;
  if (out.medium.is_slab()) desc << ", slab " << k.thickness << " mm";
  if (auto e = out.medium.validate()) {
    e->field = option_of_field(e->field, a, by_preset);
    return *e;
  }
  out.description = desc.str();
  return out;
}

}  // namespace sss::app
