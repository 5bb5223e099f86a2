// RenderOptions: what the frame is asked to do, a plain struct with defaults (pbrt-v4
// style). The CLI (app/sss-viewer) and the tests fill it.
#pragma once

#include <cstdint>
#include <optional>
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

struct RenderOptions {
  std::uint32_t width = 640;
  std::uint32_t height = 360;
  SssMode sss = SssMode::Screen;
  SssKind kind = SssKind::Separable;
  int separable_taps = 17;  // odd, 3 .. SSS_MAX_TAPS
  float exposure = 1.0f;    // display image only (the EXR is linear, unexposed)
  std::uint32_t shadow_map_size = 1024;
};

}  // namespace sss::renderer
