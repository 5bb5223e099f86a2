#include "scene/KhrMaterials.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <string_view>

namespace sss::scene {

namespace {

using nlohmann::json;

const auto str = sss::message_number;

constexpr const char* kVolume = "KHR_materials_volume";
constexpr const char* kVolumeScatter = "KHR_materials_volume_scatter";
constexpr const char* kScatter = "KHR_materials_scatter";
constexpr const char* kIor = "KHR_materials_ior";
constexpr const char* kTransmission = "KHR_materials_transmission";
constexpr const char* kDiffuseTransmission = "KHR_materials_diffuse_transmission";

std::string field(const char* ext, std::string_view key) { return std::string(ext) + "." + std::string(key); }

// o[key] as a finite number in [lo, hi] (open ends where asked).
std::optional<FieldError> read_number(const json& o, const char* ext, const char* key, double lo,
                                      double hi, bool lo_open, bool hi_open, double& out) {
  const json& v = o.at(key);
  if (!v.is_number()) return FieldError{field(ext, key), "must be a number"};
  const double x = v.get<double>();
  const bool ok = std::isfinite(x) && (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  if (!ok)
    return FieldError{field(ext, key), std::string("must lie in ") + (lo_open ? "(" : "[") + str(lo) +
                                           ", " + str(hi) + (hi_open ? ")" : "]") + ", got " + str(x)};
  out = x;
  return std::nullopt;
}

// o[key] as 3 numbers, each in [lo, 1] (lo open where asked).
std::optional<FieldError> read_colour(const json& o, const char* ext, const char* key, bool lo_open,
                                      Rgb& out) {
  const json& v = o.at(key);
  if (!v.is_array() || v.size() != 3) return FieldError{field(ext, key), "must be an array of 3 numbers"};
  for (int c = 0; c < 3; ++c) {
    const std::string name = field(ext, key) + "[" + std::to_string(c) + "]";
    if (!v[c].is_number()) return FieldError{name, "must be a number"};
    const double x = v[c].get<double>();
    if (!(std::isfinite(x) && (lo_open ? x > 0.0 : x >= 0.0) && x <= 1.0))
      return FieldError{name, std::string("must lie in ") + (lo_open ? "(0, 1]" : "[0, 1]") + ", got " + str(x)};
    out[c] = x;
  }
  return std::nullopt;
}

// The first of `keys` that `o` has (drafts renamed their fields), or nullptr.
const char* first_of(const json& o, std::initializer_list<const char*> keys) {
  for (const char* k : keys)
    if (o.contains(k)) return k;
  return nullptr;
}

void note_textures(const json& o, const char* ext, std::initializer_list<const char*> keys,
                   std::vector<std::string>& ignored) {
  for (const char* k : keys)
    if (o.contains(k)) ignored.push_back(field(ext, k));
}

using MaybeError = std::optional<FieldError>;

// KHR_materials_volume's thickness and attenuation.
MaybeError read_volume(const json& v, KhrMedium& k) {
  k.volume = true;
  if (v.contains("thicknessFactor"))
    if (auto e = read_number(v, kVolume, "thicknessFactor", 0.0, HUGE_VAL, false, true, k.thickness_factor)) return e;
  if (v.contains("attenuationDistance"))
    if (auto e = read_number(v, kVolume, "attenuationDistance", 0.0, HUGE_VAL, true, true, k.attenuation_distance))
      return e;
  if (v.contains("attenuationColor"))
    if (auto e = read_colour(v, kVolume, "attenuationColor", true, k.attenuation_color)) return e;
  note_textures(v, kVolume, {"thicknessTexture"}, k.ignored);
  return std::nullopt;
}

// The scatter draft `ext` (KHR_materials_scatter or the older volume_scatter), s its block.
MaybeError read_scatter(const json& s, const char* ext, KhrMedium& k) {
  const bool newer = ext == std::string_view(kScatter);
  k.scatter = newer ? KhrMedium::Scatter::Scatter : KhrMedium::Scatter::VolumeScatter;
  k.multiscatter = newer ? Rgb{1.0, 1.0, 1.0} : Rgb{0.0, 0.0, 0.0};
  if (const char* key = first_of(s, {"multiscatterColorFactor", "multiscatterColor", "scatterAlbedo"}))
    if (auto e = read_colour(s, ext, key, false, k.multiscatter)) return e;
  if (s.contains("scatterAnisotropy"))
    if (auto e = read_number(s, ext, "scatterAnisotropy", -1.0, 1.0, true, true, k.anisotropy)) return e;
  if (newer) {
    k.strength = 0.0;
    if (const char* key = first_of(s, {"scatterStrengthFactor", "scatterFactor", "scatterWeight"}))
      if (auto e = read_number(s, ext, key, 0.0, 1.0, false, false, k.strength)) return e;
    note_textures(s, ext, {"scatterStrengthTexture"}, k.ignored);
  }
  note_textures(s, ext, {"multiscatterColorTexture"}, k.ignored);
  return std::nullopt;
}

// KHR_materials_transmission and KHR_materials_diffuse_transmission, where present.
MaybeError read_transmissions(const json& extensions, KhrMedium& k) {
  if (extensions.contains(kTransmission)) {
    const json& t = extensions[kTransmission];
    double f = 0.0;
    if (t.contains("transmissionFactor"))
      if (auto e = read_number(t, kTransmission, "transmissionFactor", 0.0, 1.0, false, false, f)) return e;
    k.transmission = f;
    note_textures(t, kTransmission, {"transmissionTexture"}, k.ignored);
  }
  if (extensions.contains(kDiffuseTransmission)) {
    const json& t = extensions[kDiffuseTransmission];
    double f = 0.0;
    if (t.contains("diffuseTransmissionFactor"))
      if (auto e = read_number(t, kDiffuseTransmission, "diffuseTransmissionFactor", 0.0, 1.0, false, false, f))
        return e;
    k.diffuse_transmission = f;
    if (t.contains("diffuseTransmissionColorFactor"))
      if (auto e = read_colour(t, kDiffuseTransmission, "diffuseTransmissionColorFactor", false,
                               k.diffuse_transmission_color))
        return e;
    note_textures(t, kDiffuseTransmission, {"diffuseTransmissionTexture", "diffuseTransmissionColorTexture"},
                  k.ignored);
  }
  return std::nullopt;
}

// KHR_materials_ior's block: its ior, 1.5 when left out.
MaybeError read_ior(const json& i, KhrMedium& k) {
  k.ior = 1.5;
  if (!i.contains("ior")) return std::nullopt;
  if (!i["ior"].is_number()) return FieldError{field(kIor, "ior"), "must be a number"};
  const double ior = i["ior"].get<double>();
  if (!(std::isfinite(ior) && (ior == 0.0 || ior >= 1.0)))
    return FieldError{field(kIor, "ior"), "must be 0 or at least 1, got " + str(ior)};
  k.ior = ior;
  return std::nullopt;
}

}  // namespace

std::variant<KhrMedium, FieldError> parse_khr_medium(const json& extensions) {
  KhrMedium k;
  if (!extensions.is_object()) return k;
  if (extensions.contains(kVolume))
    if (auto e = read_volume(extensions[kVolume], k)) return *e;
  // The newer draft wins where a file carries both.
  const char* ext = extensions.contains(kScatter) ? kScatter : extensions.contains(kVolumeScatter) ? kVolumeScatter : nullptr;
  if (ext != nullptr) {
    if (extensions.contains(kScatter) && extensions.contains(kVolumeScatter)) k.ignored.push_back(kVolumeScatter);
    if (auto e = read_scatter(extensions[ext], ext, k)) return *e;
  }
  if (auto e = read_transmissions(extensions, k)) return *e;
  if (extensions.contains(kIor))
    if (auto e = read_ior(extensions[kIor], k)) return *e;
  return k;
}

json khr_extensions_json(const SssMaterial& material, double mm_per_unit) {
  json out = json::object();
  if (!material.layers.empty()) return out;
  const profiles::Medium m = material.effective_medium();
  double st_max = 0.0, g = 0.0, eta = 0.0;
  for (int c = 0; c < 3; ++c) {
    st_max = std::max(st_max, m.sigma_a[c] + m.sigma_s[c]);
    g += m.g[c] / 3.0;
    eta += m.eta[c] / 3.0;
  }
  if (!(st_max > 0.0)) return out;
  const double d_mm = 1.0 / st_max;
  json colour = json::array(), multiscatter = json::array();
  for (int c = 0; c < 3; ++c) {
    const double st = m.sigma_a[c] + m.sigma_s[c];
    colour.push_back(std::exp(-st * d_mm));
    multiscatter.push_back(multiscatter_albedo(m.sigma_s[c] / st, 0.0));
  }
  const double thickness_mm = m.is_slab() ? m.thickness_mm : d_mm;
  out[kVolume] = {{"thicknessFactor", thickness_mm / mm_per_unit},
                  {"attenuationDistance", d_mm / mm_per_unit},
                  {"attenuationColor", colour}};
  out[kVolumeScatter] = {{"multiscatterColorFactor", multiscatter}, {"scatterAnisotropy", g}};
  out[kIor] = {{"ior", eta}};
  out["KHR_materials_diffuse_transmission"] = {{"diffuseTransmissionFactor", 1.0}};
  return out;
}

std::vector<std::string> khr_transmission_notes(const KhrMedium& khr) {
  std::vector<std::string> notes;
  if (!khr.transmission && !khr.diffuse_transmission) {
    notes.push_back(std::string(kVolume) + " without " + kTransmission + " or " + kDiffuseTransmission +
                    " lets no light in by its spec; scattered here as if diffuseTransmissionFactor were 1");
    return notes;
  }
  const double entering = std::max(khr.transmission.value_or(0.0), khr.diffuse_transmission.value_or(0.0));
  if (entering > 0.0 && entering < 1.0)
    notes.push_back("a transmission factor of " + str(entering) +
                    " is taken as 1: all light not reflected specularly enters the medium");
  if (khr.diffuse_transmission_color != Rgb{1.0, 1.0, 1.0})
    notes.push_back(field(kDiffuseTransmission, "diffuseTransmissionColorFactor") +
                    " (the boundary's tint) is not applied");
  if (khr.scatter == KhrMedium::Scatter::Scatter && khr.diffuse_transmission)
    notes.push_back(std::string(kScatter) + " forbids " + kDiffuseTransmission + "; it is ignored");
  return notes;
}

double ior_f0(double ior) {
  const double r = (ior - 1.0) / (ior + 1.0);
  return r * r;
}

namespace {

// Why the extensions describe no scattering medium (empty when they do): thin-walled, no
// light entering, no extinction, no scattering strength.
std::string why_not_a_medium(const KhrMedium& khr, const char* ext) {
  if (!khr.volume || khr.thickness_factor == 0.0)
    return std::string(ext) + " without a volume (" + kVolume +
           ".thicknessFactor 0 or absent) is thin-walled, a surface BSDF rather than a "
           "medium: not given subsurface scattering";
  if ((khr.transmission || khr.diffuse_transmission) && khr.transmission.value_or(0.0) == 0.0 &&
      khr.diffuse_transmission.value_or(0.0) == 0.0)
    return std::string(kTransmission) + ".transmissionFactor and " + kDiffuseTransmission +
           ".diffuseTransmissionFactor are 0 or absent: no light enters the volume (Khronos' "
           "sample renderer draws it opaque): not given subsurface scattering";
  if (khr.attenuation_distance == 0.0)
    return std::string(kVolume) + ".attenuationDistance is absent (infinite): the medium has "
           "no extinction, nothing scatters: not given subsurface scattering";
  if (khr.scatter == KhrMedium::Scatter::Scatter && khr.strength == 0.0)
    return std::string(kScatter) + ".scatterStrengthFactor is 0 (its default): nothing "
           "scatters: not given subsurface scattering";
  return {};
}

// The medium's coefficients per mm from the extensions' attenuation and multi-scatter
// colour, by each draft's own albedo inversion; nullopt (why_not set) for a channel with
// no extinction or no absorption.
std::optional<profiles::Medium> khr_coefficients(const KhrMedium& khr, const char* ext, double mm_per_unit,
                                                 std::string& why_not) {
  profiles::Medium m;
  for (int c = 0; c < 3; ++c) {
    if (khr.attenuation_color[c] >= 1.0) {
      why_not = field(kVolume, "attenuationColor") + "[" + std::to_string(c) +
                "] is 1: no extinction in that channel, so no diffusion: not given subsurface "
                "scattering";
      return std::nullopt;
    }
    // σt per scene unit (the file's, metres for glTF), then per mm.
    const double sigma_t = -std::log(khr.attenuation_color[c]) / khr.attenuation_distance / mm_per_unit;
    const double rho_ms = khr.strength * khr.multiscatter[c];
    // Each draft's own inversion: the older one's is g-free (g = 0 in the g-aware form).
    const double g = khr.scatter == KhrMedium::Scatter::Scatter ? khr.anisotropy : 0.0;
    const double rho_ss = single_scattering_albedo(rho_ms, g);
    // ρms = 1 is ρss = 1 exactly (s = 0 with the unrounded constants; the rounded ones
    // leave 1 - ρss ~ 1e-11): no absorption, so no finite diffusion length.
    if (1.0 - rho_ss < 1e-9) {
      why_not = std::string(ext) + ": a multi-scatter colour of 1 in channel " + std::to_string(c) +
                " means no absorption, which has no finite diffusion length: not given "
                "subsurface scattering";
      return std::nullopt;
    }
    m.sigma_s[c] = rho_ss * sigma_t;
    m.sigma_a[c] = (1.0 - rho_ss) * sigma_t;
    m.g[c] = khr.anisotropy;
    m.eta[c] = khr.ior && *khr.ior >= 1.0 ? *khr.ior : 1.5;  // glTF's default ior
  }
  return m;
}

}  // namespace

std::optional<SssMaterial> khr_sss_material(const KhrMedium& khr, double mm_per_unit,
                                            std::string& why_not) {
  why_not.clear();
  if (khr.scatter == KhrMedium::Scatter::None) return std::nullopt;
  const char* ext = khr.scatter == KhrMedium::Scatter::Scatter ? kScatter : kVolumeScatter;
  why_not = why_not_a_medium(khr, ext);
  if (!why_not.empty()) return std::nullopt;
  const std::optional<profiles::Medium> m = khr_coefficients(khr, ext, mm_per_unit, why_not);
  if (!m) return std::nullopt;
  auto made = make_sss_material(CoefficientSource{*m});
  if (auto* e = std::get_if<FieldError>(&made)) {
    // Values the extensions allow that the models cannot take (no absorption at all: a
    // multi-scatter colour of 1; an ior outside the models' η range): the material stays
    // opaque, with the reason.
    why_not = std::string(ext) + " + " + kVolume + " give a medium the models cannot take (" +
              e->what() + "): not given subsurface scattering";
    return std::nullopt;
  }
  return std::optional<SssMaterial>(std::get<SssMaterial>(std::move(made)));
}

}  // namespace sss::scene
