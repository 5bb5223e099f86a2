// The sss-fit commands. Each returns the process exit code: 0 success, 2 bad usage
// or input (message on stderr), 1 a runtime failure such as an unwritable output file.
#pragma once

#include "ExitCodes.h"
#include "MediumArgs.h"

#include <cstdint>
#include <optional>
#include <string>

namespace sss::app {

struct CommonArgs {
  MediumArgs medium;
  // --layers FILE.json: a stack of layers (scene/SssLayers.h) instead of MEDIUM;
  // implies --model layered.
  std::string layers;
  std::string model{profiles::model_name(profiles::kDefaultModel)};
  bool model_given = false;  // --model was on the command line
  bool json = false;
  int pbd_samples = 0;  // 0: the library default
  std::uint64_t photons = 1u << 20;
  std::uint64_t seed = 1;
  int threads = 0;
};

struct ProfileArgs {
  CommonArgs common;
  std::string radii;  // START:STOP:COUNT
  bool log_spacing = false;
};

struct FitArgs {
  CommonArgs common;
  int gaussians = 6;
  int samples = 96;
  int taps = 0;  // > 0: also a separable kernel with this many taps
  double resolution = -1.0;  // fit resolution in inner radii (mfp); < 0: the model's default
  std::string out, plot;
  bool plot_mc = false;
  std::string header_prefix = "sss_kernel";
};

struct McTableArgs {
  std::string out;
  std::uint64_t photons = 0;  // 0: the shipped budget
  std::uint64_t seed = 1;
  int threads = 0;
  bool anisotropic = false;       // every shipped layer, as a set
  std::optional<double> g;        // one layer at g
};

struct ExportArgs {
  CommonArgs common;
  std::string format;  // hdrp | unreal | kernel-json | c-header
  std::string out, name;
  std::optional<double> world_scale;  // hdrp: m per unit (1); unreal: WorldUnitScale (0.1)
  int gaussians = 6;
  int taps = 0;
};

int run_presets(bool json);
int run_profile(const ProfileArgs& a);
int run_fit(const FitArgs& a);
int run_validate(const CommonArgs& a);
int run_mc_table(const McTableArgs& a);
int run_export(const ExportArgs& a);

// "sss-fit: error: FIELD: message" on stderr.
int usage_error(const FieldError& e);
int usage_error(const std::string& message);

}  // namespace sss::app
