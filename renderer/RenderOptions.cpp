#include "renderer/RenderOptions.h"

namespace sss::renderer {

std::string_view sss_mode_name(SssMode mode) { return mode == SssMode::Off ? "off" : "screen"; }

std::string_view sss_kind_name(SssKind kind) {
  return kind == SssKind::Separable ? "separable" : "gaussians";
}

std::optional<SssKind> parse_sss_kind(std::string_view name) {
  if (name == "separable") return SssKind::Separable;
  if (name == "gaussians") return SssKind::Gaussians;
  return std::nullopt;
}

namespace {
constexpr DebugView kDebugViews[] = {DebugView::None,         DebugView::Irradiance,
                                     DebugView::Specular,     DebugView::Scattered,
                                     DebugView::KernelRadius, DebugView::ProfileId,
                                     DebugView::Thickness,    DebugView::UvStretch};
}  // namespace

std::string_view debug_view_name(DebugView view) {
  switch (view) {
    case DebugView::None: return "none";
    case DebugView::Irradiance: return "irradiance";
    case DebugView::Specular: return "specular";
    case DebugView::Scattered: return "scattered";
    case DebugView::KernelRadius: return "kernel-radius";
    case DebugView::ProfileId: return "profile-id";
    case DebugView::Thickness: return "thickness";
    case DebugView::UvStretch: return "uv-stretch";
  }
  return "none";
}

std::optional<DebugView> parse_debug_view(std::string_view name) {
  for (DebugView v : kDebugViews)
    if (debug_view_name(v) == name) return v;
  return std::nullopt;
}

std::span<const DebugView> all_debug_views() { return kDebugViews; }

}  // namespace sss::renderer
