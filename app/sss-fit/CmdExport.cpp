// sss-fit export: a fitted profile as an engine's asset (Unity HDRP's Diffusion Profile,
// Unreal's Subsurface Profile) or as the project's kernel (JSON, C header).
#include "CliSupport.h"
#include "CommandSupport.h"

#include "profiles/EngineProfiles.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace sss::app {

namespace {

std::string stem_of(const std::string& path) { return std::filesystem::path(path).stem().string(); }

std::string replace_extension(const std::string& path, const char* ext) {
  return std::filesystem::path(path).replace_extension(ext).string();
}

// Two files or none: the second failing removes the first.
bool write_pair(const std::string& a, const std::string& a_bytes, const std::string& b,
                const std::string& b_bytes) {
  if (!write_output(a, a_bytes)) return false;
  if (write_output(b, b_bytes)) return true;
  std::error_code ec;
  std::filesystem::remove(a, ec);
  return false;
}

}  // namespace

namespace {

// --format kernel-json | c-header: the fit's own kernel, written by `fit`.
int export_kernel(const ExportArgs& a, const std::string& ext) {
  const bool json = a.format == "kernel-json";
  if (json ? ext != ".json" : (ext != ".h" && ext != ".hpp"))
    return usage_error("--out: --format " + a.format + " writes " + (json ? "a .json file" : "a .h or .hpp file") +
                       ", got '" + a.out + "'");
  FitArgs f;
  f.common = a.common;
  f.gaussians = a.gaussians;
  f.taps = a.taps;
  f.out = a.out;
  if (!a.name.empty()) f.header_prefix = a.name;
  return run_fit(f);
}

// An engine format's --out extension and --world-scale: kExitOk when they are valid,
// otherwise the usage error's exit code (the message printed).
int check_engine_options(const ExportArgs& a, const std::string& ext, bool hdrp, double world_scale) {
  if (hdrp ? ext != ".asset" : ext != ".json")
    return usage_error(std::string("--out: --format ") + a.format + " writes " +
                       (hdrp ? "NAME.asset (and NAME.asset.meta beside it)" : "NAME.json (and NAME.py beside it)") +
                       ", got '" + a.out + "'");
  if (hdrp ? !(std::isfinite(world_scale) && world_scale >= 0.001) : !(std::isfinite(world_scale) && world_scale > 0.0))
    return usage_error(std::string("--world-scale: ") +
                       (hdrp ? "HDRP's worldScale is metres per unit, at least 0.001" : "must be a finite number > 0") +
                       ", got " + message_number(world_scale));
  return kExitOk;
}

// What was written, with the Burley shape's fit: JSON with --json, lines otherwise.
int report_engine_export(const ExportArgs& a, const ProfileSource& src, bool hdrp,
                         const profiles::BurleyShapeFit& fit, const std::vector<std::string>& written) {
  if (a.common.json) {
    nlohmann::json doc = {{"format", a.format},
                          {"model", src.model_name},
                          {"medium", src.description},
                          {"files", written},
                          {"burley_d_mm", to_json(fit.d_mm)},
                          {"burley_relative_error", to_json(fit.relative_error)}};
    std::cout << doc.dump(2) << '\n';
    return kExitOk;
  }
  std::printf("%s profile of %s for %s\n", hdrp ? "Unity HDRP diffusion" : "Unreal subsurface",
              src.model_name.c_str(), src.description.c_str());
  std::printf("Burley d              %.5g %.5g %.5g mm\n", fit.d_mm[0], fit.d_mm[1], fit.d_mm[2]);
  std::printf("relative L2 error    %.3f%% %.3f%% %.3f%%   (of r*R(r)/total against Burley's shape, measure dr)\n",
              100 * fit.relative_error[0], 100 * fit.relative_error[1], 100 * fit.relative_error[2]);
  for (const std::string& w : written) std::printf("wrote %s\n", w.c_str());
  return kExitOk;
}

}  // namespace

int run_export(const ExportArgs& a) {
  const std::string ext = lower_extension(a.out);
  if (a.format == "kernel-json" || a.format == "c-header") return export_kernel(a, ext);
  const bool hdrp = a.format == "hdrp";
  if (!hdrp && a.format != "unreal")
    return usage_error("--format: expected hdrp, unreal, kernel-json or c-header, got '" + a.format + "'");
  const double world_scale = a.world_scale.value_or(hdrp ? 1.0 : 0.1);
  if (const int bad = check_engine_options(a, ext, hdrp, world_scale); bad != kExitOk) return bad;
  const auto opt = model_options(a.common);
  const auto src = resolve_source(a.common, opt, /*with_model=*/true);
  if (!src) return kExitUsage;
  if (src->layers)
    return usage_error("--layers: an engine profile is one medium's (the engines have no layered profile); "
                       "export the stack's kernel with --format kernel-json");
  const profiles::RgbProfile profile = src->make_profile(opt);
  profiles::EngineProfileSource es;
  es.name = a.name.empty() ? stem_of(a.out) : a.name;
  es.medium = src->medium;
  es.world_scale = world_scale;
  profiles::BurleyShapeFit fit;
  std::vector<std::string> written;
  if (hdrp) {
    const auto p = profiles::hdrp_diffusion_profile(es, profile);
    fit = p.fit;
    const std::string meta = a.out + ".meta";
    if (!write_pair(a.out, p.asset, meta, p.meta)) return kExitRuntime;
    written = {a.out, meta};
  } else {
    const auto p = profiles::unreal_subsurface_profile(es, profile);
    fit = p.fit;
    const std::string py = replace_extension(a.out, ".py");
    if (!write_pair(a.out, p.json, py, p.python)) return kExitRuntime;
    written = {a.out, py};
  }
  return report_engine_export(a, *src, hdrp, fit, written);
}

}  // namespace sss::app
