#include "EnvironmentArgs.h"

#include <stdexcept>

namespace sss::app {

void add_environment_options(CLI::App& app, EnvironmentArgs& args) {
  app.add_option("--environment", args.environment,
                 "Light from every direction: none (default), R,G,B (a uniform sky's linear "
                 "radiance; 1,1,1 gives an open surface E = pi), or FILE.exr (an "
                 "equirectangular HDR image, +Y up, its centre looking down -Z). The GPU takes its "
                 "irradiance from spherical harmonics less what the scene blocks (a per-vertex "
                 "bake; sss-viewer --sky-occlusion) and its specular from a prefiltered map "
                 "without occlusion; the references sample both with shadow rays (README "
                 "\"Environment light\")");
  app.add_option("--environment-intensity", args.intensity,
                 "Multiplies the environment's radiance, >= 0 (default 1)");
}

std::optional<EnvironmentError> apply_environment(scene::Scene& scene, const EnvironmentArgs& args) {
  if (args.environment == "none") {
    if (args.intensity != 1.0f)
      return EnvironmentError{"--environment-intensity: needs --environment R,G,B or FILE.exr"};
    scene.environment.reset();
    return std::nullopt;
  }
  try {
    scene.environment = scene::load_environment(args.environment, args.intensity);
  } catch (const std::invalid_argument& e) {
    // A value with commas is a colour; anything else named a file.
    const bool file = args.environment.find(',') == std::string::npos &&
                      std::string(e.what()).rfind("the environment's intensity", 0) != 0;
    return EnvironmentError{"--environment: " + std::string(e.what()), file};
  }
  return std::nullopt;
}

}  // namespace sss::app
