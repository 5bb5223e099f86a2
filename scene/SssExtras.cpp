#include "scene/SssExtras.h"

#include "scene/GltfJson.h"
#include "scene/SssLayers.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <limits>
#include <cmath>
#include <sstream>

namespace sss::scene {

namespace {

using nlohmann::json;

constexpr std::array<std::string_view, 17> kKeys = {
    "enabled", "preset", "sigma_a", "sigma_s", "g", "eta", "color",
    "mfp", "thickness", "model", "gaussians", "scale", "albedo_mode", "layers",
    "openpbr", "standard_surface", "albedo_inversion"};

// The keys of extras.sss.openpbr and extras.sss.standard_surface: the specs' own names.
// [0] the weight, [1] colour, [2] radius, [3] radius scale (OpenPBR) or scale (Standard
// Surface), [4] anisotropy, [5] ior.
constexpr std::array<const char*, 6> kOpenPbrKeys = {
    "subsurface_weight", "subsurface_color", "subsurface_radius", "subsurface_radius_scale",
    "subsurface_scatter_anisotropy", "specular_ior"};
constexpr std::array<const char*, 6> kStandardSurfaceKeys = {
    "subsurface", "subsurface_color", "subsurface_radius", "subsurface_scale",
    "subsurface_anisotropy", "specular_IOR"};

const auto str = sss::message_number;

std::string key_list() {
  std::string s;
  for (std::string_view k : kKeys) s += (s.empty() ? "" : ", ") + std::string(k);
  return s;
}

}  // namespace

namespace detail {

// A number or an array of three; `scalar` tells which, so errors can name "g" or "g[1]".
std::optional<FieldError> read_rgb(const json& o, const char* key, Rgb& out, bool& scalar) {
  const json& v = o.at(key);
  scalar = v.is_number();
  if (scalar) {
    out.fill(v.get<double>());
  } else if (v.is_array() && v.size() == 3) {
    for (int c = 0; c < 3; ++c) {
      if (!v[c].is_number())
        return FieldError{std::string(key) + "[" + std::to_string(c) + "]", "must be a number"};
      out[c] = v[c].get<double>();
    }
  } else {
    return FieldError{key, "must be a number or an array of 3 numbers"};
  }
  for (int c = 0; c < 3; ++c)
    if (!std::isfinite(out[c]))
      return FieldError{scalar ? std::string(key) : std::string(key) + "[" + std::to_string(c) + "]",
                        "must be a finite number"};
  return std::nullopt;
}

// profiles names channels "[R]", "[G]", "[B]"; here they are array positions, and a
// field the user gave as a single number (or a derived one, like sigma_t from two
// single numbers) has none.
FieldError as_written(FieldError e, const json& o) {
  const auto bracket = e.field.find('[');
  if (bracket == std::string::npos) return e;
  const std::string base = e.field.substr(0, bracket);
  const auto is_array = [&](const char* k) { return o.contains(k) && o.at(k).is_array(); };
  const bool per_channel = base == "sigma_t" ? is_array("sigma_a") || is_array("sigma_s")
                                             : is_array(base.c_str());
  if (!per_channel) {
    e.field = base;
    return e;
  }
  for (int c = 0; c < 3; ++c)
    if (e.field.compare(bracket, std::string::npos, std::string("[") + kChannelNames[c] + "]") == 0)
      e.field = base + "[" + std::to_string(c) + "]";
  return e;
}

std::optional<FieldError> read_thickness(const json& o, const char* key, double& out) {
  if (!o.contains(key)) return std::nullopt;
  const json& t = o[key];
  const double v = t.is_number() ? t.get<double>() : std::nan("");
  if (!std::isfinite(v) || !(v > 0.0))
    return FieldError{key, "must be a number of mm > 0, got " + t.dump()};
  out = v;
  return std::nullopt;
}

}  // namespace detail

using detail::as_written;
using detail::read_rgb;

namespace {

// extras.sss.openpbr / extras.sss.standard_surface: every key optional (the spec's
// default), colours as 3 numbers (or one for all), errors named "openpbr.subsurface_color[1]".
// `enabled` is cleared by a weight of 0.
// A spec block's fields, read with the block's name in their errors
// ("openpbr.subsurface_radius").
struct SpecFields {
  const json& o;
  const char* block;
  FieldError named(FieldError e) const {
    e.field = std::string(block) + "." + e.field;
    return e;
  }
  std::optional<FieldError> number(const char* key, double& out) const {
    if (!o.contains(key)) return std::nullopt;
    if (!o[key].is_number() || !std::isfinite(o[key].get<double>()))
      return named({key, "must be a finite number"});
    out = o[key].get<double>();
    return std::nullopt;
  }
  std::optional<FieldError> colour(const char* key, Rgb& out) const {
    if (!o.contains(key)) return std::nullopt;
    bool scalar = false;
    if (auto e = read_rgb(o, key, out, scalar)) return named(*e);
    return std::nullopt;
  }
};

// The subsurface weight (keys[0]): 0, no subsurface, or 1.
std::optional<FieldError> read_weight(const SpecFields& f, const char* key, double& weight) {
  weight = 1.0;
  if (auto e = f.number(key, weight)) return e;
  if (!(weight >= 0.0 && weight <= 1.0)) return f.named({key, "must lie in [0, 1], got " + str(weight)});
  if (weight != 0.0 && weight != 1.0)
    return f.named({key, "must be 0 (no subsurface) or 1: the renderer does not mix a diffuse "
                         "and a subsurface lobe, got " + str(weight)});
  return std::nullopt;
}

// Standard Surface's parameters, mapped onto OpenPBR's (p); `off`: type-checked only.
std::optional<FieldError> read_standard_surface(const SpecFields& f, bool off, profiles::OpenPbrSubsurface& p) {
  const auto& keys = kStandardSurfaceKeys;
  profiles::StandardSurfaceSubsurface s;
  if (!off && !f.o.contains(keys[1]))
    return f.named({keys[1], "is required: Standard Surface's default (1, 1, 1) absorbs nothing, "
                             "which has no finite diffusion length"});
  if (auto e = f.colour(keys[1], s.color)) return e;
  if (auto e = f.colour(keys[2], s.radius)) return e;
  if (auto e = f.number(keys[3], s.scale)) return e;
  if (auto e = f.number(keys[4], s.anisotropy)) return e;
  if (auto e = f.number(keys[5], s.ior)) return e;
  if (off) return std::nullopt;
  if (auto e = profiles::validate(s)) return f.named(*e);
  p = profiles::openpbr_from_standard_surface(s);
  return std::nullopt;
}

// OpenPBR's own parameters (p); `off`: type-checked only.
std::optional<FieldError> read_openpbr_fields(const SpecFields& f, bool off, profiles::OpenPbrSubsurface& p) {
  const auto& keys = kOpenPbrKeys;
  if (auto e = f.colour(keys[1], p.color)) return e;
  if (auto e = f.number(keys[2], p.radius_mm)) return e;
  if (auto e = f.colour(keys[3], p.radius_scale)) return e;
  if (auto e = f.number(keys[4], p.anisotropy)) return e;
  if (auto e = f.number(keys[5], p.ior)) return e;
  if (off) return std::nullopt;
  if (auto e = profiles::validate(p)) return f.named(*e);
  return std::nullopt;
}

std::variant<OpenPbrSource, FieldError> read_openpbr(const json& o, bool standard_surface,
                                                     bool& enabled) {
  const char* block = standard_surface ? "standard_surface" : "openpbr";
  const auto& keys = standard_surface ? kStandardSurfaceKeys : kOpenPbrKeys;
  const SpecFields f{o, block};
  if (!o.is_object()) return FieldError{block, "must be a JSON object of the spec's subsurface parameters"};
  for (const auto& item : o.items())
    if (std::find(keys.begin(), keys.end(), item.key()) == keys.end()) {
      std::string list;
      for (const char* k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
      return f.named({item.key(), "unknown field; expected one of " + list});
    }
  double weight = 1.0;
  if (auto e = read_weight(f, keys[0], weight)) return *e;
  // A weight of 0 is no subsurface: every value is still type-checked (a typo is an
  // error), but their ranges are not the renderer's business then (Standard Surface's
  // default colour, 1, describes no finite medium).
  const bool off = weight == 0.0;
  if (off) enabled = false;
  OpenPbrSource source;
  source.standard_surface = standard_surface;
  const auto e = standard_surface ? read_standard_surface(f, off, source.parameters)
                                  : read_openpbr_fields(f, off, source.parameters);
  if (e) return *e;
  return source;
}

}  // namespace

namespace {

// What every way of giving the medium shares: the switch, the model, the fit's size, the
// scale, where the albedo applies, and a thickness.
struct Common {
  bool enabled = true;
  profiles::Model model = profiles::kDefaultModel;
  int gaussians = kDefaultGaussians;
  double scale = 1.0;
  AlbedoMode albedo_mode = AlbedoMode::PostScatter;
  double thickness = std::numeric_limits<double>::infinity();
};

std::variant<Common, FieldError> read_common(const json& o) {
  Common common;
  if (o.contains("enabled")) {
    if (!o["enabled"].is_boolean()) return FieldError{"enabled", "must be true or false"};
    common.enabled = o["enabled"].get<bool>();
  }
  if (o.contains("model")) {
    const json& m = o["model"];
    const auto parsed = m.is_string() ? profiles::parse_model(m.get<std::string>()) : std::nullopt;
    if (!parsed)
      return FieldError{"model", "unknown model " + m.dump() + "; expected one of " +
                                     profiles::model_names()};
    common.model = *parsed;
  }
  if (o.contains("gaussians")) {
    const json& n = o["gaussians"];
    const double v = n.is_number() ? n.get<double>() : std::nan("");
    if (!profiles::valid_gaussian_count(v))
      return FieldError{"gaussians", profiles::gaussian_count_rule() + ", got " + n.dump()};
    common.gaussians = static_cast<int>(v);
  }
  if (o.contains("scale")) {
    if (!o["scale"].is_number()) return FieldError{"scale", "must be a number"};
    common.scale = o["scale"].get<double>();
  }
  if (o.contains("albedo_mode")) {
    const json& a = o["albedo_mode"];
    const auto parsed = a.is_string() ? parse_albedo_mode(a.get<std::string>()) : std::nullopt;
    if (!parsed)
      return FieldError{"albedo_mode", "must be \"post-scatter\" or \"pre-post\", got " + a.dump()};
    common.albedo_mode = *parsed;
  }
  if (auto e = detail::read_thickness(o, "thickness", common.thickness)) return *e;

  return common;
}

// "layers": a stack (SssLayers.h), which is the medium and the model.
std::variant<SssMaterial, FieldError> from_layers(const json& o, const Common& common) {
  for (const char* k : {"preset", "sigma_a", "sigma_s", "g", "eta", "color", "mfp",
                        "thickness", "model", "openpbr", "standard_surface", "albedo_inversion"})
    if (o.contains(k))
      return FieldError{k, "cannot be combined with layers (the layers give the medium, "
                           "their thicknesses, and the model: layered)"};
  auto stack = parse_sss_layers(o["layers"]);
  if (auto* e = std::get_if<FieldError>(&stack)) return *e;
  auto made = make_layered_sss_material(std::get<profiles::LayerStack>(std::move(stack)),
                                        common.gaussians, common.scale, common.albedo_mode);
  if (auto* e = std::get_if<FieldError>(&made)) return *e;
  std::get<SssMaterial>(made).enabled = common.enabled;
  return made;
}

// "openpbr" or "standard_surface": the spec's subsurface block, inverted to a medium.
std::variant<SssMaterial, FieldError> from_openpbr(const json& o, const Common& common) {
  bool enabled = common.enabled;  // read_openpbr: a weight of 0 turns it off
  if (o.contains("openpbr") && o.contains("standard_surface"))
    return FieldError{"standard_surface", "cannot be combined with openpbr: give one of them"};
  for (const char* k : {"preset", "sigma_a", "sigma_s", "g", "eta", "color", "mfp"})
    if (o.contains(k))
      return FieldError{k, "cannot be combined with openpbr or standard_surface (they give the "
                           "medium, its anisotropy and its ior)"};
  const bool standard_surface = o.contains("standard_surface");
  const char* block = standard_surface ? "standard_surface" : "openpbr";
  auto read = read_openpbr(o[block], standard_surface, enabled);
  if (auto* e = std::get_if<FieldError>(&read)) return *e;
  if (!enabled) {
    // A weight of 0: no subsurface. The spec's other values are not read (they need not
    // describe a medium); the material keeps the default source, resolved, as every
    // material without subsurface scattering does, so that it exports and reads back.
    auto off = make_sss_material(PresetSource{"skin1"}, common.model, common.gaussians, common.scale, common.albedo_mode);
    if (auto* e = std::get_if<FieldError>(&off)) return *e;
    std::get<SssMaterial>(off).enabled = false;
    return off;
  }
  OpenPbrSource source = std::get<OpenPbrSource>(std::move(read));
  source.thickness_mm = common.thickness;
  if (o.contains("albedo_inversion")) {
    const json& a = o["albedo_inversion"];
    const auto parsed = a.is_string() ? profiles::parse_albedo_inversion(a.get<std::string>()) : std::nullopt;
    if (!parsed)
      return FieldError{"albedo_inversion", "must be \"van-de-hulst\" (the spec's) or \"model\" "
                                            "(the model's total reflectance), got " + a.dump()};
    source.inversion = *parsed;
  }
  auto made = make_sss_material(std::move(source), common.model, common.gaussians, common.scale, common.albedo_mode);
  if (auto* e = std::get_if<FieldError>(&made)) {
    if (e->field.rfind("subsurface_", 0) == 0) e->field = std::string(block) + "." + e->field;
    return *e;
  }
  std::get<SssMaterial>(made).enabled = enabled;
  return made;
}

// "sigma_a" and "sigma_s" [+ "g", "eta"]: the coefficients, checked per channel.
std::variant<SssSource, FieldError> read_coefficients(const json& o, double thickness) {
  for (const char* k : {"sigma_a", "sigma_s"})
    if (!o.contains(k)) return FieldError{k, "is required with sigma_a and sigma_s"};
  profiles::Medium m;
  m.g.fill(0.0);
  m.eta.fill(1.3);
  m.thickness_mm = thickness;
  bool scalar = false;
  if (auto e = read_rgb(o, "sigma_a", m.sigma_a, scalar)) return *e;
  if (auto e = read_rgb(o, "sigma_s", m.sigma_s, scalar)) return *e;
  if (o.contains("g"))
    if (auto e = read_rgb(o, "g", m.g, scalar)) return *e;
  if (o.contains("eta"))
    if (auto e = read_rgb(o, "eta", m.eta, scalar)) return *e;
  for (int c = 0; c < 3; ++c)
    if (auto e = m.channel(c).validate("[" + std::to_string(c) + "]")) return as_written(*e, o);
  return CoefficientSource{m};
}

// "color" and "mfp" [+ "g", "eta" as single numbers]: an artist's parameters.
std::variant<SssSource, FieldError> read_artist(const json& o, double thickness) {
  for (const char* k : {"color", "mfp"})
    if (!o.contains(k)) return FieldError{k, "is required with color and mfp"};
  profiles::ArtistParameters p;
  p.thickness_mm = thickness;
  bool scalar = false;
  if (auto e = read_rgb(o, "color", p.color, scalar)) return *e;
  for (int c = 0; c < 3; ++c)
    if (!(p.color[c] > 0.0 && p.color[c] < 1.0))
      return FieldError{scalar ? "color" : "color[" + std::to_string(c) + "]",
                        "must lie strictly between 0 and 1, got " + str(p.color[c])};
  if (auto e = read_rgb(o, "mfp", p.mfp_mm, scalar)) return *e;
  for (int c = 0; c < 3; ++c)
    if (!(p.mfp_mm[c] > 0.0))
      return FieldError{scalar ? "mfp" : "mfp[" + std::to_string(c) + "]",
                        "mean free path must be > 0 mm, got " + str(p.mfp_mm[c])};
  for (auto [k, dst] : {std::pair{"g", &p.g}, std::pair{"eta", &p.eta}}) {
    if (!o.contains(k)) continue;
    if (!o[k].is_number())
      return FieldError{k, "must be a single number with color + mfp"};
    *dst = o[k].get<double>();
  }
  if (!(std::fabs(p.g) < 1.0)) return FieldError{"g", "must lie in (-1, 1), got " + str(p.g)};
  if (!(p.eta > 0.0)) return FieldError{"eta", "must be > 0, got " + str(p.eta)};
  return ArtistSource{p};
}

}  // namespace

std::variant<SssMaterial, FieldError> parse_sss_extras(const json& o) {
  if (!o.is_object()) return FieldError{"", "must be a JSON object"};
  for (const auto& item : o.items())
    if (std::find(kKeys.begin(), kKeys.end(), item.key()) == kKeys.end())
      return FieldError{item.key(), "unknown field; expected one of " + key_list()};
  auto read = read_common(o);
  if (auto* e = std::get_if<FieldError>(&read)) return *e;
  const Common& common = std::get<Common>(read);
  if (o.contains("layers")) return from_layers(o, common);
  const bool openpbr = o.contains("openpbr") || o.contains("standard_surface");
  if (o.contains("albedo_inversion") && !openpbr)
    return FieldError{"albedo_inversion", "applies only to openpbr or standard_surface"};
  if (openpbr) return from_openpbr(o, common);

  const bool preset = o.contains("preset");
  const bool coefficients = o.contains("sigma_a") || o.contains("sigma_s");
  const bool artist = o.contains("color") || o.contains("mfp");
  if (int(preset) + int(coefficients) + int(artist) != 1)
    return FieldError{"", std::string(preset || coefficients || artist ? "give only one" : "needs one") +
                              " of: preset; sigma_a + sigma_s; color + mfp; openpbr; standard_surface"};
  SssSource source;
  if (preset) {
    for (const char* k : {"g", "eta"})
      if (o.contains(k)) return FieldError{k, "cannot be combined with a preset (it has its own)"};
    if (!o["preset"].is_string()) return FieldError{"preset", "must be a preset name (a string)"};
    source = PresetSource{o["preset"].get<std::string>()};
  } else {
    auto read_source = coefficients ? read_coefficients(o, common.thickness) : read_artist(o, common.thickness);
    if (auto* e = std::get_if<FieldError>(&read_source)) return *e;
    source = std::get<SssSource>(std::move(read_source));
  }

  auto made = make_sss_material(std::move(source), common.model, common.gaussians, common.scale, common.albedo_mode);
  if (auto* e = std::get_if<FieldError>(&made)) return as_written(*e, o);
  auto& s = std::get<SssMaterial>(made);
  s.enabled = common.enabled;
  if (preset && o.contains("thickness")) s.medium.thickness_mm = common.thickness;
  return s;
}

nlohmann::json sss_extras_json(const SssMaterial& m) {
  json o = json::object();
  o["enabled"] = m.enabled;
  const auto rgb = [](const Rgb& v) { return json::array({v[0], v[1], v[2]}); };
  if (!m.layers.empty()) {
    json layers = json::array();
    for (const profiles::Medium& l : m.layers) {
      json e = {{"sigma_a", rgb(l.sigma_a)}, {"sigma_s", rgb(l.sigma_s)}, {"g", rgb(l.g)},
                {"eta", rgb(l.eta)}};
      if (std::isfinite(l.thickness_mm)) e["thickness_mm"] = l.thickness_mm;  // absent: the base
      layers.push_back(std::move(e));
    }
    o["layers"] = std::move(layers);
    o["gaussians"] = m.gaussians;
    o["scale"] = m.scale;
    o["albedo_mode"] = std::string(albedo_mode_name(m.albedo_mode));
    return o;
  }
  double thickness = m.medium.thickness_mm;
  if (const auto* p = std::get_if<PresetSource>(&m.source)) {
    o["preset"] = p->name;
  } else if (const auto* c = std::get_if<CoefficientSource>(&m.source)) {
    o["sigma_a"] = rgb(c->medium.sigma_a);
    o["sigma_s"] = rgb(c->medium.sigma_s);
    o["g"] = rgb(c->medium.g);
    o["eta"] = rgb(c->medium.eta);
    thickness = c->medium.thickness_mm;
  } else if (const auto* op = std::get_if<OpenPbrSource>(&m.source)) {
    const profiles::OpenPbrSubsurface& pbr = op->parameters;
    if (op->standard_surface) {
      const profiles::StandardSurfaceSubsurface ss = profiles::standard_surface_from_openpbr(pbr);
      o["standard_surface"] = {{"subsurface_color", rgb(ss.color)}, {"subsurface_radius", rgb(ss.radius)},
                               {"subsurface_scale", ss.scale}, {"subsurface_anisotropy", ss.anisotropy},
                               {"specular_IOR", ss.ior}};
    } else {
      o["openpbr"] = {{"subsurface_color", rgb(pbr.color)}, {"subsurface_radius", pbr.radius_mm},
                      {"subsurface_radius_scale", rgb(pbr.radius_scale)},
                      {"subsurface_scatter_anisotropy", pbr.anisotropy}, {"specular_ior", pbr.ior}};
    }
    o["albedo_inversion"] = std::string(profiles::albedo_inversion_name(op->inversion));
    thickness = op->thickness_mm;
  } else {
    const auto& a = std::get<ArtistSource>(m.source).parameters;
    o["color"] = rgb(a.color);
    o["mfp"] = rgb(a.mfp_mm);
    o["g"] = a.g;
    o["eta"] = a.eta;
    thickness = a.thickness_mm;
  }
  if (std::isfinite(thickness)) o["thickness"] = thickness;  // absent: semi-infinite
  o["model"] = std::string(profiles::model_name(m.model));
  o["gaussians"] = m.gaussians;
  o["scale"] = m.scale;
  o["albedo_mode"] = std::string(albedo_mode_name(m.albedo_mode));
  return o;
}

std::variant<SssMaterial, FieldError> parse_sss_extras_text(std::string_view text) {
  if (auto e = check_json_depth(text, kMaxJsonDepth)) return FieldError{"", *e};
  const json o = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
  if (o.is_discarded()) return FieldError{"", "is not valid JSON"};
  return parse_sss_extras(o);
}

}  // namespace sss::scene
