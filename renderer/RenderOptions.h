// RenderOptions: what the frame is asked to do, a plain struct with defaults (pbrt-v4
// style). The CLI (app/sss-viewer) and the tests fill it.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace sss::renderer {

// --sss: off (no spatial spread: the total reflectance applied locally) or screen space.
// Texture space is issue 6.
enum class SssMode { Off, Screen };
// --mode: Jimenez's separable kernel, or each Gaussian of the fit as its own blur.
enum class SssKind { Separable, Gaussians };

std::string_view sss_mode_name(SssMode mode);  // "off" | "screen"
std::string_view sss_kind_name(SssKind kind);  // "separable" | "gaussians"
std::optional<SssKind> parse_sss_kind(std::string_view name);

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
};
std::string_view debug_view_name(DebugView view);  // "none" | "irradiance" | ...
std::optional<DebugView> parse_debug_view(std::string_view name);
std::span<const DebugView> all_debug_views();  // None first, in enum order

struct RenderOptions {
  std::uint32_t width = 640;
  std::uint32_t height = 360;
  SssMode sss = SssMode::Screen;
  SssKind kind = SssKind::Separable;
  int separable_taps = 17;  // odd, 3 .. SSS_MAX_TAPS
  float exposure = 1.0f;    // display image only (the EXR is linear, unexposed)
  std::uint32_t shadow_map_size = 1024;
  DebugView debug_view = DebugView::None;
  // --transmission: light through thin parts of SSS materials, from the shadow maps'
  // thickness (renderer/README.md "Transmission"). Off: reflection only.
  bool transmission = true;
};

}  // namespace sss::renderer
