// Material: the surface of a mesh. Metallic-roughness PBR (glTF core) for the specular
// and the colour, plus an SssMaterial that says how light scatters underneath.
//
// SssMaterial holds where its optics came from (a preset name, σa/σs/g/η, or an artist's
// colour + mean free path) and the Medium resolved from that source under the chosen
// model (DESIGN.md §3): every renderer reads `medium` and never resolves the source again.
#pragma once

#include "profiles/ArtistMapping.h"
#include "profiles/GaussianFit.h"
#include "profiles/Layered.h"
#include "profiles/Medium.h"
#include "profiles/OpenPbr.h"
#include "profiles/Profile.h"

#include <glm/vec4.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace sss::scene {

using profiles::kDefaultGaussians;
using profiles::kMaxGaussians;
using profiles::kMinGaussians;

// Where the albedo (base colour) multiplies the scattered light: after scattering only,
// or √albedo before and after (d'Eon & Luebke 2007).
enum class AlbedoMode { PostScatter, PrePost };
std::string_view albedo_mode_name(AlbedoMode mode);  // "post-scatter" | "pre-post"
std::optional<AlbedoMode> parse_albedo_mode(std::string_view name);

struct PresetSource {
  std::string name;  // profiles::presets(), e.g. "skin1"
};
struct CoefficientSource {
  profiles::Medium medium;  // σa, σs, g, η per channel, mm^-1
};
struct ArtistSource {
  profiles::ArtistParameters parameters;  // colour in (0,1), reduced mfp in mm
};
// OpenPBR's (or Autodesk Standard Surface's) subsurface parameters, profiles/OpenPbr.h:
// colours linear Rec.709, lengths in mm; the colour inverted by `inversion` (the spec's
// van de Hulst by default, or the material's model's total reflectance).
struct OpenPbrSource {
  profiles::OpenPbrSubsurface parameters;
  profiles::AlbedoInversion inversion = profiles::AlbedoInversion::VanDeHulst;
  bool standard_surface = false;  // given (and written back) as Standard Surface's
  double thickness_mm = std::numeric_limits<double>::infinity();  // a slab's, as extras.sss "thickness"
};
using SssSource = std::variant<PresetSource, CoefficientSource, ArtistSource, OpenPbrSource>;

struct SssMaterial {
  bool enabled = false;
  SssSource source = PresetSource{"skin1"};
  profiles::Medium medium{};  // resolved from `source` under `model`, mm^-1
  profiles::Model model = profiles::kDefaultModel;
  int gaussians = kDefaultGaussians;  // terms of the sum-of-Gaussians fit, 1..8
  // The object scatters as if it were `scale` times larger: a distance d (mm) on the
  // object is a distance d·scale in the medium. Equivalently σa and σs are multiplied
  // by scale (effective_medium()).
  double scale = 1.0;
  AlbedoMode albedo_mode = AlbedoMode::PostScatter;
  // A layered material (extras.sss.layers, issue 19): the stack, top first (its medium
  // profiles::LayerStack, thickness_mm per layer, the last may be infinite). `medium` is
  // then its top layer (what single scattering sees) and `model` is Model::Layered.
  // Empty for a material of one medium.
  profiles::LayerStack layers;

  profiles::Medium effective_medium() const;
  // The stack with the scale applied to each layer as effective_medium() applies it.
  profiles::LayerStack effective_layers() const;
  // Whether light leaves through a far face (a finite slab or a stack with a finite
  // last layer), and that face's depth in mm after the scale (infinity when none).
  bool transmits() const;
  double effective_thickness_mm() const;
  // The material's R(r) (and T(r)): the layered model for a stack, else `model` on the
  // effective medium. Throws std::invalid_argument as RgbProfile does.
  profiles::RgbProfile profile(const profiles::ModelOptions& opt = {}) const;
  // What the model does with this medium that the user should know, a line each: mc-table
  // (and a stack, whose top layer it looks up) outside its tabulated g range falls back to
  // the similarity relation (profiles::mc_table_g_warnings). Empty for other models.
  std::vector<std::string> model_warnings() const;
};

// The medium a source describes. Artist sources are inverted through `model`'s total
// reflectance. Errors name the field ("preset", "sigma_a[G]", "color[R]", ...).
std::variant<profiles::Medium, FieldError> resolve_medium(const SssSource& source,
                                                          profiles::Model model);

// An enabled SssMaterial with its medium resolved. Rejects gaussians outside [1, 8]
// ("gaussians") and a scale that is not finite and > 0 ("scale").
std::variant<SssMaterial, FieldError> make_sss_material(
    SssSource source, profiles::Model model = profiles::kDefaultModel,
    int gaussians = kDefaultGaussians, double scale = 1.0,
    AlbedoMode albedo_mode = AlbedoMode::PostScatter);

// An enabled layered SssMaterial: the stack (top first, checked by profiles::validate_layers,
// whose errors name "layers[k].field") is the medium and the model (Model::Layered); its top
// layer is `medium` and the source, as extras.sss.layers, --layers and the viewer's layer
// editor make one. Other errors as make_sss_material's.
std::variant<SssMaterial, FieldError> make_layered_sss_material(
    profiles::LayerStack layers, int gaussians = kDefaultGaussians, double scale = 1.0,
    AlbedoMode albedo_mode = AlbedoMode::PostScatter);

// For built-in content: throws std::invalid_argument if the preset is unknown or unusable.
SssMaterial preset_sss_material(std::string_view preset);

struct Material {
  std::string name;
  glm::vec4 base_color{1.0f};                       // linear RGBA factor
  std::optional<std::uint32_t> base_color_texture;  // Scene::textures; sRGB-encoded RGBA
  float metallic = 1.0f;                            // glTF defaults
  float roughness = 1.0f;
  std::optional<std::uint32_t> normal_texture;  // Scene::textures; linear, tangent space
  float normal_scale = 1.0f;
  // Scale on the dielectric specular reflectance (F0 = 0.04 · specular). 0 turns the
  // specular lobe off and lets all incident light enter the surface: builtin:edge uses
  // it so that the exitant flux is exactly R ∗ E.
  float specular = 1.0f;
  bool double_sided = false;
  SssMaterial sss;  // sss.enabled == false: an opaque PBR surface
};

}  // namespace sss::scene
