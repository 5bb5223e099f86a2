#include "profiles/EngineProfiles.h"

#include "profiles/GaussianFit.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace sss::profiles {

namespace {

// r·R_d(r) of Burley's normalized shape (unit integral): finite at r = 0.
double burley_r_times_shape(double r, double d) {
  return (std::exp(-r / d) + std::exp(-r / (3.0 * d))) / (8.0 * std::numbers::pi * d);
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') out += '\\';
    out += ch;
  }
  return out + "\"";
}

std::uint64_t fnv1a64(const std::string& s, std::uint64_t h) {
  for (unsigned char ch : s) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  return h;
}

double mean(const Rgb& v) { return (v[0] + v[1] + v[2]) / 3.0; }

// The minimum of f over [u0, u1]: a scan of 200 steps brackets it, golden section refines
// the bracket to 1e-12 (at most 100 steps); the bracket's midpoint.
template <typename F>
double scan_then_golden_section(F&& f, double u0, double u1) {
  constexpr int kScan = 200;
  int best = 0;
  double best_e = HUGE_VAL;
  for (int k = 0; k <= kScan; ++k) {
    const double e = f(u0 + (u1 - u0) * k / kScan);
    if (e < best_e) {
      best_e = e;
      best = k;
    }
  }
  double a = u0 + (u1 - u0) * std::max(best - 1, 0) / kScan;
  double b = u0 + (u1 - u0) * std::min(best + 1, kScan) / kScan;
  const double phi = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = b - phi * (b - a), x2 = a + phi * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < 100 && b - a > 1e-12; ++it) {
    if (f1 < f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - phi * (b - a);
      f1 = f(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + phi * (b - a);
      f2 = f(x2);
    }
  }
  return 0.5 * (a + b);
}

}  // namespace

std::string engine_asset_name(const std::string& name) {
  std::string out;
  for (char ch : name) out += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  if (out.empty()) out = "SssProfile";
  if (std::isdigit(static_cast<unsigned char>(out[0]))) out.insert(0, "SSS_");
  return out;
}

BurleyShapeFit fit_burley_shape(const RgbProfile& profile) {
  const FitTarget target = make_fit_target(profile, 160, 0.0);
  BurleyShapeFit fit;
  const double r_lo = target.r_mm.front(), r_hi = target.r_mm.back();
  for (int c = 0; c < 3; ++c) {
    const double total = target.total_reflectance[c];
    if (!(total > 0.0)) throw std::invalid_argument("profile: total reflectance of channel " +
                                                    std::string(kChannelNames[c]) + " is not > 0");
    double norm = 0.0;
    for (std::size_t i = 0; i < target.r_mm.size(); ++i) {
      const double t = target.r_mm[i] * target.R[i][c] / total;
      norm += target.dr[i] * t * t;
    }
    const auto error2 = [&](double log_d) {
      const double d = std::exp(log_d);
      double e = 0.0;
      for (std::size_t i = 0; i < target.r_mm.size(); ++i) {
        const double t = target.r_mm[i] * target.R[i][c] / total;
        const double diff = t - burley_r_times_shape(target.r_mm[i], d);
        e += target.dr[i] * diff * diff;
      }
      return e / norm;
    };
    const double u = scan_then_golden_section(error2, std::log(r_lo), std::log(r_hi));
    fit.d_mm[c] = std::exp(u);
    fit.relative_error[c] = std::sqrt(std::max(error2(u), 0.0));
  }
  return fit;
}

HdrpDiffusionProfile hdrp_diffusion_profile(const EngineProfileSource& source, const RgbProfile& profile) {
  if (!(std::isfinite(source.world_scale) && source.world_scale >= 0.001))
    throw std::invalid_argument("world scale: HDRP's worldScale must be at least 0.001 m per unit, got " +
                                num(source.world_scale));
  HdrpDiffusionProfile out;
  out.fit = fit_burley_shape(profile);
  const Rgb& d = out.fit.d_mm;
  const double multiplier = std::max({d[0], d[1], d[2]});
  const Medium& m = source.medium;
  const bool slab = m.is_slab();
  const Rgb transmitted = profile.total_transmittance();
  if (slab && transmitted[0] + transmitted[1] + transmitted[2] > 0.0)
    for (int c = 0; c < 3; ++c) {
      const double t = m.thickness_mm;
      const double hdrp = 0.25 * (std::exp(-t / d[c]) + 3.0 * std::exp(-t / (3.0 * d[c])));
      out.transmission_tint[c] = hdrp > 0.0 ? transmitted[c] / hdrp : 1.0;
    }
  const double ior = std::clamp(mean(m.eta), 1.0, 2.0);
  const std::string name = engine_asset_name(source.name);
  // HDRP stores the hash as the bits of a float (unverified: a normal float, exponent 127,
  // is what its own generator is assumed to keep); 0 would be reassigned on Reset().
  std::uint32_t hash = static_cast<std::uint32_t>(fnv1a64(name, 14695981039346656037ull));
  hash = (hash & 0x807FFFFFu) | (127u << 23);

  std::ostringstream a;
  const auto colour = [](const Rgb& v) {
    return "{r: " + num(v[0]) + ", g: " + num(v[1]) + ", b: " + num(v[2]) + ", a: 1}";
  };
  a << "%YAML 1.1\n%TAG !u! tag:unity3d.com,2011:\n--- !u!114 &11400000\nMonoBehaviour:\n"
    << "  m_ObjectHideFlags: 0\n  m_CorrespondingSourceObject: {fileID: 0}\n"
    << "  m_PrefabInstance: {fileID: 0}\n  m_PrefabAsset: {fileID: 0}\n  m_GameObject: {fileID: 0}\n"
    << "  m_Enabled: 1\n  m_EditorHideFlags: 0\n"
    << "  m_Script: {fileID: 11500000, guid: b2686e09ec7aef44bad2843e4416f057, type: 3}\n"
    << "  m_Name: " << name << "\n  m_EditorClassIdentifier: \n  profile:\n"
    << "    scatteringDistance: " << colour({d[0] / multiplier, d[1] / multiplier, d[2] / multiplier}) << "\n"
    << "    scatteringDistanceMultiplier: " << num(multiplier) << "\n"
    << "    transmissionTint: " << colour(out.transmission_tint) << "\n"
    << "    texturingMode: " << (source.pre_post_albedo ? 0 : 1) << "\n"
    << "    smoothnessMultipliers: {x: 1, y: 1}\n    lobeMix: 0.5\n    diffuseShadingPower: 1\n"
    << "    transmissionMode: " << (slab ? 1 : 0) << "\n"
    << "    thicknessRemap: {x: 0, y: " << num(slab ? m.thickness_mm : 5.0) << "}\n"
    << "    worldScale: " << num(source.world_scale) << "\n"
    << "    ior: " << num(ior) << "\n"
    << "    hash: " << hash << "\n"
    << "  m_Version: 2\n";
  out.asset = a.str();
  char guid[33];
  std::snprintf(guid, sizeof guid, "%016llx%016llx",
                static_cast<unsigned long long>(fnv1a64(out.asset, 14695981039346656037ull)),
                static_cast<unsigned long long>(fnv1a64(out.asset, 0x84222325cbf29ce4ull)));
  out.meta = std::string("fileFormatVersion: 2\nguid: ") + guid +
             "\nNativeFormatImporter:\n  externalObjects: {}\n  mainObjectFileID: 11400000\n"
             "  userData: \n  assetBundleName: \n  assetBundleVariant: \n";
  return out;
}

UnrealSubsurfaceProfile unreal_subsurface_profile(const EngineProfileSource& source,
                                                  const RgbProfile& profile,
                                                  const std::string& content_path) {
  if (!(std::isfinite(source.world_scale) && source.world_scale > 0.0))
    throw std::invalid_argument("world unit scale: must be a finite number > 0, got " + num(source.world_scale));
  UnrealSubsurfaceProfile out;
  out.fit = fit_burley_shape(profile);
  const Medium& m = source.medium;
  Rgb mfp_cm{};
  for (int c = 0; c < 3; ++c) mfp_cm[c] = 0.1 / (m.sigma_a[c] + m.sigma_s[c]);
  const double distance = std::max({mfp_cm[0], mfp_cm[1], mfp_cm[2]});
  const Rgb colour{mfp_cm[0] / distance, mfp_cm[1] / distance, mfp_cm[2] / distance};
  const Rgb albedo = profile.total_reflectance();
  const double ior = mean(m.eta);
  const std::string name = engine_asset_name(source.name);
  const auto arr = [](const Rgb& v) { return "[" + num(v[0]) + ", " + num(v[1]) + ", " + num(v[2]) + "]"; };

  std::ostringstream j;
  j << "{\n  \"name\": " << json_string(name) << ",\n"
    << "  \"SurfaceAlbedo\": " << arr(albedo) << ",\n"
    << "  \"MeanFreePathColor\": " << arr(colour) << ",\n"
    << "  \"MeanFreePathDistance\": " << num(distance) << ",\n"
    << "  \"WorldUnitScale\": " << num(source.world_scale) << ",\n"
    << "  \"IOR\": " << num(ior) << ",\n"
    << "  \"bEnableBurley\": true,\n  \"bEnableMeanFreePath\": true,\n"
    << "  \"Tint\": [1, 1, 1],\n  \"TransmissionTintColor\": [1, 1, 1],\n"
    << "  \"sss_viewer\": {\"mean_free_path_cm\": " << arr(mfp_cm) << ", \"burley_d_mm\": "
    << arr(out.fit.d_mm) << ", \"burley_relative_error\": " << arr(out.fit.relative_error) << "}\n}\n";
  out.json = j.str();

  const auto lc = [](const Rgb& v) {
    return "unreal.LinearColor(" + num(v[0]) + ", " + num(v[1]) + ", " + num(v[2]) + ", 1.0)";
  };
  std::ostringstream p;
  p << "# Creates the Subsurface Profile " << name << " in Unreal's editor (Python Editor Script\n"
    << "# Plugin): run it from the editor's Python console or with -ExecutePythonScript.\n"
    << "# Written by sss-viewer / sss-fit; the same values are in " << name << ".json.\n"
    << "import unreal\n\n"
    << "NAME = " << json_string(name) << "\nPATH = " << json_string(content_path) << "\n\n"
    << "tools = unreal.AssetToolsHelpers.get_asset_tools()\n"
    << "factory = unreal.SubsurfaceProfileFactory() if hasattr(unreal, \"SubsurfaceProfileFactory\") else None\n"
    << "profile = tools.create_asset(NAME, PATH, unreal.SubsurfaceProfile, factory)\n"
    << "settings = profile.get_editor_property(\"settings\")\n"
    << "settings.set_editor_property(\"surface_albedo\", " << lc(albedo) << ")\n"
    << "settings.set_editor_property(\"mean_free_path_color\", " << lc(colour) << ")\n"
    << "settings.set_editor_property(\"mean_free_path_distance\", " << num(distance) << ")\n"
    << "settings.set_editor_property(\"world_unit_scale\", " << num(source.world_scale) << ")\n"
    << "settings.set_editor_property(\"ior\", " << num(ior) << ")\n"
    << "settings.set_editor_property(\"enable_burley\", True)\n"
    << "settings.set_editor_property(\"enable_mean_free_path\", True)\n"
    << "profile.set_editor_property(\"settings\", settings)\n"
    << "unreal.EditorAssetLibrary.save_loaded_asset(profile)\n"
    << "unreal.log(\"created \" + PATH + \"/\" + NAME)\n";
  out.python = p.str();
  return out;
}

}  // namespace sss::profiles
