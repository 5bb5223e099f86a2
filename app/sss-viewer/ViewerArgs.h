// The sss-viewer command line (DESIGN.md §4) as a plain struct, and what it changes in a
// loaded scene: --model, --gaussians, --albedo and the MEDIUM flags override every SSS
// material (MaterialOverrides.h).
#pragma once

#include "EnvironmentArgs.h"
#include "MaterialOverrides.h"

#include "renderer/RenderOptions.h"
#include "scene/Scene.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace sss::app {

// The window's background (sRGB codes): a dark grey like a DCC viewport's, so that an
// unlit face (black) stands out from it.
inline constexpr std::array<float, 3> kWindowBackground{0.22f, 0.22f, 0.22f};

struct ViewerArgs {
  std::string scene = "builtin:bunny";
  bool headless = false;
  std::string out;
  std::string screenshot;
  int width = 640;
  int height = 360;
  int frames = 1;
  std::string sss = "screen";
  std::string mode = "separable";
  MaterialOverrideArgs material;  // --model, --gaussians, --albedo, MEDIUM
  EnvironmentArgs environment;    // --environment, --environment-intensity
  int taps = 17;
  int shadow_map_size = 1024;  // texels a side (RenderOptions::shadow_map_size)
  float exposure = 1.0f;
  // --background auto (window: the environment if any, else kWindowBackground; headless:
  // none) | none | environment | R,G,B (sRGB)
  std::string background = "auto";
  std::string aa = "auto";  // --aa auto (window: fxaa, headless: off) | off | fxaa
  std::string debug_view = "none";  // --debug-view: renderer::parse_debug_view names
  std::vector<double> debug_range;  // --debug-range LO,HI (empty: the view's automatic)
  std::string transmission = "on";  // --transmission on | off
  std::string sky_occlusion = "on";  // --sky-occlusion on | off
  std::string fresnel = "off";      // --fresnel on | off
  std::string single_scattering = "on";  // --single-scattering on | off
  int texture_size = 1024;              // --texture-size (--sss texture)
  std::string texture_update = "on-change";  // --texture-update every-frame | on-change
  std::vector<std::string> texture_objects;  // --texture-object NAME=SIZE[:POLICY], repeatable
  std::string atlas_out;  // --atlas-out PREFIX: headless --sss texture writes the atlases
  bool no_specular = false;  // --no-specular: headless EXR --out less the specular target
  bool stats = false;
  bool describe_frame = false;  // print the frame graph and exit
  std::string device;
  std::string vsync = "on";  // window: on (FIFO) | off (MAILBOX / IMMEDIATE)
  bool validation = false;   // --validation or SSS_VALIDATION=1
  bool test_resize = false;  // hidden: resize and minimize the window between frames
  bool test_resize_storm = false;  // hidden: 50 size changes, some within one frame
  std::string test_host_oom;  // hidden: load | frame: std::bad_alloc thrown there
  std::string test_open;     // hidden: opens this file after two frames, as a drop would
  // hidden: renders the reference at frame 2 and shows it: split | reference | error
  std::string test_compare;
  float interactive_scale = 0.5f;  // --interactive-scale: render size while the view moves
  bool test_interaction = false;   // hidden: every frame counts as interacting (timing)
  std::string test_edit;     // hidden: preset=NAME | model=NAME | layers=FILE.json, edited at the first frame
  // --soak N (headless): N frames, the material changed every soak_every frames (Soak.h)
  int soak = 0;
  int soak_every = 100;
  int soak_cycle = 10;
  long soak_max_growth_kb = 1024;
  std::string soak_csv, soak_svg;
};

}  // namespace sss::app
