// RenderOptions: what the frame is asked to do, a plain struct with defaults (pbrt-v4
// style). The CLI (app/sss-viewer) and the tests fill it.
#pragma once

#include "shaders/shared/config.h"

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace sss::renderer {

// The real-time SSS technique, one value for what the CLI spells with two options (--sss
// off|screen|texture and --mode separable|gaussians, which only screen reads):
//   off        no spatial spread: the total reflectance applied locally;
//   separable  screen space, Jimenez's separable kernel (the default);
//   gaussians  screen space, each Gaussian of the fit as its own blur;
//   texture    texture space: irradiance in each subsurface object's UV atlas, blurred
//              there (renderer/README.md "Texture space").
// The values are the shaders' SSS_TECHNIQUE_* (shaders/shared/config.h), which they read in
// FrameUniforms::options.y.
enum class SssTechnique : int {
  Off = SSS_TECHNIQUE_OFF,
  Separable = SSS_TECHNIQUE_SEPARABLE,
  Gaussians = SSS_TECHNIQUE_GAUSSIANS,
  Texture = SSS_TECHNIQUE_TEXTURE,
};
std::span<const SssTechnique> all_techniques();  // in enum order
std::string_view technique_name(SssTechnique technique);  // "off" | "separable" | ...
std::optional<SssTechnique> parse_technique(std::string_view name);
// The CLI's spellings: --sss SSS and --mode MODE as one technique, or what is wrong with
// them ("--sss: expected off, screen or texture, got 'x'"). MODE is only checked, not used,
// when SSS is off or texture.
std::variant<SssTechnique, std::string> technique_from_cli(std::string_view sss, std::string_view mode);

// --aa: anti-aliasing of the display image (the PNG and the window): none, or FXAA, a
// post-process over the tonemapped frame (renderer/README.md "Anti-aliasing"). The HDR
// image (the EXR, the compare suite, the references' counterpart) is never filtered.
enum class Antialias { Off, Fxaa };
std::string_view antialias_name(Antialias aa);  // "off" | "fxaa"
std::optional<Antialias> parse_antialias(std::string_view name);

// --debug-view: what the display image shows instead of the shaded frame (the HDR image
// stays the shaded frame). renderer/README.md "Debug views" says what each one maps.
enum class DebugView {
  None,          // the shaded frame
  Irradiance,    // E / pi (a white Lambert surface's radiance), tonemapped
  Specular,      // the specular radiance, tonemapped
  Scattered,     // diffuse after SSS, before albedo (R * E or E) / pi, tonemapped
  KernelRadius,  // range_mm x pixels per mm, heat map; magenta below 1 px
  ProfileId,     // one flat colour per material id, black background
  Thickness,     // mm through the object along light 0 (shadow map), heat map
  UvStretch,     // mm of surface per unit of u (red) and v (green); grey without UVs
  SingleScattering,  // S(1) alone (shading.glsl), tonemapped, with or without the switch
};
std::string_view debug_view_name(DebugView view);  // "none" | "irradiance" | ...
std::optional<DebugView> parse_debug_view(std::string_view name);
std::span<const DebugView> all_debug_views();  // None first, in enum order
// Whether `view` draws a value on a heat map that RenderOptions::debug_range sets.
bool debug_view_has_range(DebugView view);
// The unit of that heat map: "px" (kernel-radius, log2 scale), "mm" (thickness), "mm per
// unit of UV" (uv-stretch); "" for the others.
std::string_view debug_view_unit(DebugView view);
// "" when `range` can be the heat map's of `view` (both finite, LO < HI, LO >= 0, and LO > 0
// on kernel-radius's log scale; {0, 0} is the automatic range), else what is wrong.
std::string debug_range_error(DebugView view, const std::array<float, 2>& range);
// "" when `colour` can be RenderOptions::background (each finite and in [0, 1]), else what
// is wrong.
std::string background_error(const std::array<float, 3>& colour);

// When the texture path recomputes an object's irradiance atlas: every frame, or only
// when something it depends on changed (lights, materials, the object's texture size,
// transmission, the shadow map size; not the camera: diffuse irradiance does not depend
// on the view, so the frame is the same either way).
enum class TextureUpdate { EveryFrame, OnChange };
std::string_view texture_update_name(TextureUpdate update);  // "every-frame" | "on-change"
std::optional<TextureUpdate> parse_texture_update(std::string_view name);

// The texture path's settings for one object (a scene instance, by its node name).
struct TextureObjectOptions {
  std::string name;
  std::uint32_t size = 1024;  // irradiance texture size, kMinTextureSize..kMaxTextureSize
  TextureUpdate update = TextureUpdate::OnChange;
};
inline constexpr std::uint32_t kMinTextureSize = 256;
inline constexpr std::uint32_t kMaxTextureSize = 2048;
// "" when `size` is a valid texture size, else what is wrong with it ("expected 256..2048,
// got 100").
std::string texture_size_error(long long size);

struct RenderOptions {
  std::uint32_t width = 640;
  std::uint32_t height = 360;
  SssTechnique technique = SssTechnique::Separable;
  int separable_taps = 17;  // odd, 3 .. SSS_MAX_TAPS
  float exposure = 1.0f;    // display image only (the EXR is linear, unexposed)
  std::uint32_t shadow_map_size = 1024;
  // Off by default here and headless, where the PNG is what the golden suite compares pixel
  // by pixel; the window turns it on (sss-viewer --aa).
  Antialias antialias = Antialias::Off;
  // --background R,G,B: the display image's colour behind the geometry, as sRGB codes in
  // [0, 1], opaque (alpha 1 there, so the PNG is opaque). None: black with alpha 0 (the
  // PNG is transparent there, which the compare suite uses as its mask). The HDR image
  // keeps 0 behind the geometry either way. The window sets a grey (sss-viewer
  // --background), so a cube's unlit face does not vanish into the background.
  std::optional<std::array<float, 3>> background;
  // --background environment: the scene's environment light behind the geometry in the
  // display image (its radiance in each pixel's view direction, bilinear in the
  // equirectangular image as scene::Environment::radiance, then exposure, tonemap and
  // sRGB like the geometry; opaque). Without an environment the background stays as
  // above. The HDR image keeps 0 there, so comparisons with the references are unchanged.
  bool background_environment = false;
  DebugView debug_view = DebugView::None;
  // --debug-range LO,HI: the debug view's heat map from LO to HI in the view's unit
  // (kernel-radius: pixels, on a log2 scale; thickness: mm; uv-stretch: mm per unit of UV).
  // {0, 0}: the view's own range for the frame (Renderer::debug_range(); renderer/README.md
  // "Debug views"). The other views have no scale and ignore it.
  std::array<float, 2> debug_range{0.0f, 0.0f};
  // --transmission: light through thin parts of SSS materials, from the shadow maps'
  // thickness (renderer/README.md "Transmission"). Off: reflection only.
  bool transmission = true;
  // --sky-occlusion: with an environment light, what the scene blocks of it is taken away
  // (reference/SkyOcclusion.h: baked per vertex of each instance with Embree rays when the
  // first frame with an environment needs it; shading.glsl). Off: every surface sees the
  // whole sky, as before (a concave part gets the whole sky's irradiance).
  bool sky_occlusion = true;
  // --fresnel: the directional Fresnel factors of the separable BSSRDF on subsurface
  // light (renderer/README.md "Directional Fresnel"): the light entering is E·(N·L)·F_t(η,
  // θi), the light leaving M·F_t(η, θo)/(cπ) instead of M/π. Off: every incident watt
  // enters and leaves as from a Lambertian surface, the default: measured against the
  // ground truth it is the closer of the two on every scene but the textured tile once
  // silhouettes are left out (README "Directional Fresnel"), because the profiles assume
  // normal incidence and no single scattering, which the Lambertian entry happens to make
  // up for.
  bool fresnel = false;
  // --single-scattering: the lecture's S = S_d + S(1): once-scattered light per pixel from
  // the planar closed form with the material's real g, shadowed, not blurred
  // (renderer/README.md "Single scattering"), and profiles built without their own
  // once-scattered light (profiles::ModelOptions::single_scattering_apart). Off: the
  // profiles as they are (mc-table's and pbd's contain isotropic single scattering). On
  // by default: measured against the ground truth it brings every suite scene of the
  // default model closer but the textured tile (README "Single scattering").
  bool single_scattering = true;
  // --sss texture: each object's irradiance texture size and update policy, unless
  // texture_objects names it (by instance name; the first entry that matches wins).
  std::uint32_t texture_size = 1024;
  TextureUpdate texture_update = TextureUpdate::OnChange;
  std::vector<TextureObjectOptions> texture_objects;
};

// --texture-object NAME=SIZE[:every-frame|on-change]: one object's settings (the update
// policy defaults to `fallback`); a readable error for anything else.
std::variant<TextureObjectOptions, std::string> parse_texture_object(std::string_view text,
                                                                     TextureUpdate fallback);

// The texture settings of the instance called `name`.
TextureObjectOptions texture_options_for(const RenderOptions& options, std::string_view name);

}  // namespace sss::renderer
