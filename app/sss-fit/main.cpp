// sss-fit: diffusion profiles, their sum-of-Gaussians fits, and validation against Monte
// Carlo. The command-line contract is DESIGN.md §4.
#include "CliSupport.h"
#include "Commands.h"

#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

using namespace sss::app;

namespace {

void add_common(CLI::App& cmd, CommonArgs& a, bool with_model) {
  add_medium_options(cmd, a.medium);
  cmd.add_option("--layers", a.layers,
                 "A stack of layers instead of MEDIUM: FILE.json holding {\"layers\": [...]}, "
                 "top first, each {\"sigma_a\", \"sigma_s\", \"g\", \"eta\", \"thickness_mm\"} "
                 "or {\"preset\", \"thickness_mm\"} (mm^-1, mm; sigma as R,G,B arrays or one "
                 "number); only the last layer may leave out thickness_mm (a semi-infinite base), "
                 "and every layer has the same eta; a finite layer must be thicker than its "
                 "reduced mean free path. Implies --model layered" +
                     std::string(with_model ? "" : " (compared with a Monte Carlo walk of the stack "
                                                   "over r = 0.25..8 mm)"))
      ->type_name("FILE.json");
  if (with_model)
    cmd.add_option("--model", a.model,
                   "dipole | better-dipole | pbd | burley | multipole | mc | mc-table | qd "
                   "(default " + std::string(sss::profiles::model_name(sss::profiles::kDefaultModel)) +
                   "); layered with --layers")
        ->each([&a](const std::string&) { a.model_given = true; });
  cmd.add_flag("--json", a.json, "Print one JSON document on stdout and nothing else");
  cmd.add_option("--pbd-samples", a.pbd_samples, "PBD depth samples per strategy (default 32)")
      ->check(CLI::Range(1, 4096));
  cmd.add_option("--photons", a.photons, "Monte Carlo photons per channel")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 40));
  cmd.add_option("--seed", a.seed, "Monte Carlo seed (results are deterministic per seed)");
  cmd.add_option("--threads", a.threads, "Monte Carlo threads (0: all cores)")
      ->check(CLI::Range(0, 1024));
}

// `sss-fit fit`: the Gaussian fit, its kernel files and its plot.
CLI::App* add_fit_command(CLI::App& app, FitArgs& fa) {
  auto* fit = app.add_subcommand("fit", "Fit a sum of Gaussians to a model's profile");
  add_common(*fit, fa.common, true);
  fit->add_option("--gaussians", fa.gaussians, "Number of Gaussians, 1..8 (default 6)");
  fit->add_option("--samples", fa.samples, "Radii sampled for the fit (default 96)")
      ->check(CLI::Range(16, 4096));
  fit->add_option("--out", fa.out, "Write the kernel: FILE.json, or FILE.h for a C header");
  fit->add_option("--plot", fa.plot, "Write an SVG plot of r*R(r), the fit and its error");
  fit->add_flag("--plot-mc", fa.plot_mc, "Add Monte Carlo points (with error bars) to the plot");
  fit->add_option("--taps", fa.taps, "Also export a separable 1D kernel with this many taps (odd)");
  fit->add_option("--prefix", fa.header_prefix, "Identifier prefix in the C header");
  fit->add_option("--resolution", fa.resolution,
                  "Fit R blurred by a Gaussian whose standard deviation is this many inner radii "
                  "(reduced mean free paths for mc-table and the dipoles; default 0.25 for "
                  "mc-table, whose 1/r peak at the source no sum of Gaussians follows, 0 for the "
                  "other models)");
  return fit;
}

// `sss-fit export`: a material's profile in an engine's format.
CLI::App* add_export_command(CLI::App& app, ExportArgs& xa) {
  auto* exp = app.add_subcommand(
      "export", "Write a material's profile for an engine: Unity HDRP's Diffusion Profile "
                "(.asset + .meta), Unreal's Subsurface Profile (.json + an editor .py), or the "
                "kernel (JSON, C header)");
  add_common(*exp, xa.common, true);
  exp->add_option("--format", xa.format, "hdrp | unreal | kernel-json | c-header")->required();
  exp->add_option("--out", xa.out,
                  "hdrp: NAME.asset; unreal: NAME.json; kernel-json: FILE.json; c-header: FILE.h")
      ->required();
  exp->add_option("--name", xa.name, "The asset's name (default: the file's stem); the C header's prefix");
  exp->add_option("--world-scale", xa.world_scale,
                  "hdrp: worldScale, metres per unit (default 1); unreal: WorldUnitScale (default 0.1)");
  exp->add_option("--gaussians", xa.gaussians, "kernel-json, c-header: number of Gaussians, 1..8 (default 6)");
  exp->add_option("--taps", xa.taps, "kernel-json, c-header: also a separable kernel with this many taps (odd)");
  return exp;
}

// `sss-fit mc-table`: regenerating the shipped Monte Carlo tables.
CLI::App* add_mc_table_command(CLI::App& app, McTableArgs& ta) {
  auto* mc_table = app.add_subcommand(
      "mc-table",
      "Regenerate the Monte Carlo profile table of model mc-table (profiles/data/mc_table.bin)");
  mc_table->add_option("--out", ta.out, "Output file (written atomically)")->required();
  mc_table->add_option("--photons", ta.photons,
                       "Random walks shared by every node (default: the shipped budget; a "
                       "multiple of 4096)")
      ->check(CLI::Range(std::uint64_t{8192}, std::uint64_t{1} << 40));
  mc_table->add_option("--seed", ta.seed, "Seed (default 1, the shipped table's)");
  mc_table->add_option("--threads", ta.threads, "Threads (0: all cores); the file does not depend on it")
      ->check(CLI::Range(0, 1024));
  auto* aniso = mc_table->add_flag(
      "--anisotropic", ta.anisotropic,
      "Write the anisotropic layers instead (Henyey-Greenstein walks at g = 0.3, 0.6, 0.8, "
      "0.9, 0.95: profiles/data/mc_table_g.bin)");
  mc_table->add_option("--g", ta.g,
                       "One anisotropic layer at this Henyey-Greenstein g, on the layers' grid "
                       "(a version 3 table; for experiments and tests)")
      ->check(CLI::Range(-0.99, 0.99))
      ->excludes(aniso);
  return mc_table;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "sss-fit: diffusion profiles R(r) of translucent media, sum-of-Gaussians fits for "
      "real-time rendering, and validation against Monte Carlo.\n"
      "Units: coefficients in mm^-1, radii in mm, R(r) in mm^-2.",
      "sss-fit"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "sss-fit 0.1.0");

  bool presets_json = false;
  auto* presets = app.add_subcommand("presets", "List the measured media (Jensen et al. 2001)");
  presets->add_flag("--json", presets_json, "Print JSON");

  ProfileArgs pa;
  auto* profile = app.add_subcommand("profile", "Print R(r) of a model at given radii");
  add_common(*profile, pa.common, true);
  profile->add_option("--radii", pa.radii, "START:STOP:COUNT in mm (linear spacing)")->required();
  profile->add_flag("--log", pa.log_spacing, "Space the radii logarithmically instead");

  FitArgs fa;
  auto* fit = add_fit_command(app, fa);
  ExportArgs xa;
  auto* exp = add_export_command(app, xa);
  CommonArgs va;
  auto* validate = app.add_subcommand(
      "validate", "Every model against Monte Carlo (with --layers: the layered model)");
  add_common(*validate, va, false);

  McTableArgs ta;
  auto* mc_table = add_mc_table_command(app, ta);
  if (const auto stop = parse_command_line(app, argc, argv, "sss-fit")) return *stop;

  try {
    if (presets->parsed()) return run_presets(presets_json);
    if (profile->parsed()) return run_profile(pa);
    if (fit->parsed()) return run_fit(fa);
    if (validate->parsed()) return run_validate(va);
    if (mc_table->parsed()) return run_mc_table(ta);
    if (exp->parsed()) return run_export(xa);
  } catch (const std::invalid_argument& e) {
    return usage_error(e.what());
  } catch (const std::exception& e) {
    std::cerr << "sss-fit: error: " << e.what() << '\n';
    return kExitRuntime;
  }
  return kExitUsage;
}
