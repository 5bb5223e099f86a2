// sss_fuzz_medium_args: the MEDIUM options and material overrides of the command-line
// tools (app/common; FuzzTargets.h).
#include "FuzzSupport.h"
#include "FuzzTargets.h"

#include "MaterialOverrides.h"
#include "MediumArgs.h"

#include "profiles/Profile.h"
#include "scene/BuiltinScenes.h"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace {

// The bytes as an argv: tokens separated by NUL or ASCII whitespace, at most 64 of them
// (more options only repeat what fewer already reach).
std::vector<std::string> split_args(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args;
  std::string cur;
  bool in_token = false;
  for (std::size_t i = 0; i < size && args.size() < 64; ++i) {
    const char c = static_cast<char>(data[i]);
    if (c == '\0' || c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f') {
      if (in_token) args.push_back(cur);
      cur.clear();
      in_token = false;
    } else {
      cur.push_back(c);
      in_token = true;
    }
  }
  if (in_token && args.size() < 64) args.push_back(cur);
  return args;
}

// CLI11 parses from the back of the vector it is given (CLI::App::parse(std::vector&)).
// Returns false for a usage error, exactly what parse_command_line (CliSupport.h) turns
// into exit code 2; --help and --version are CLI::Success, a ParseError too.
bool parse(CLI::App& app, const std::vector<std::string>& args) {
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError&) {
    return false;
  }
  return true;
}

void check_medium(const sss::profiles::Medium& m, const char* what) {
  sss::fuzz::fuzz_check(!m.validate(), what);
}

}  // namespace

int sss_fuzz_medium_args(const std::uint8_t* data, std::size_t size) {
  using namespace sss;
  const std::vector<std::string> args = split_args(data, size);

  // sss-fit COMMAND: --model and the MEDIUM options (app/sss-fit/main.cpp).
  {
    CLI::App app{"fuzz sss-fit"};
    std::string model_name = "better-dipole";
    app.add_option("--model", model_name);
    app::MediumArgs medium;
    app::add_medium_options(app, medium);
    if (parse(app, args)) {
      if (const auto model = profiles::parse_model(model_name)) {
        auto r = app::resolve_medium(medium, *model, profiles::ModelOptions{});
        if (auto* ok = std::get_if<app::ResolvedMedium>(&r))
        {
          check_medium(ok->medium, "a resolved --medium validates");
          sss::fuzz::count_accepted();
        }
      }
    }
  }

  // sss-viewer / sss-reference: the overrides applied to every SSS material of a scene.
  {
    static const scene::Scene base = scene::sphere_scene();
    CLI::App app{"fuzz sss-viewer"};
    app::MaterialOverrideArgs overrides;
    app::add_material_override_options(app, overrides);
    if (parse(app, args)) {
      scene::Scene s;
      s.materials = base.materials;  // the overrides only touch materials
      auto r = app::apply_material_overrides(s, overrides);
      if (std::holds_alternative<int>(r)) {
        sss::fuzz::count_accepted();
        for (const auto& m : s.materials)
          if (m.sss.enabled) {
            check_medium(m.sss.effective_medium(), "an overridden material validates");
            sss::fuzz::fuzz_check(m.sss.gaussians >= scene::kMinGaussians &&
                           m.sss.gaussians <= scene::kMaxGaussians,
                       "overridden gaussians in 1..8");
          }
      }
    }
  }
  return 0;
}
