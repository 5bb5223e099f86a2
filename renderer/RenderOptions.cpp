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

}  // namespace sss::renderer
