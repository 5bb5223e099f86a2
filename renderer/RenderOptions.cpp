#include "renderer/RenderOptions.h"

#include "profiles/Medium.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <system_error>

namespace sss::renderer {

namespace {
constexpr SssTechnique kTechniques[] = {SssTechnique::Off, SssTechnique::Separable,
                                       SssTechnique::Gaussians, SssTechnique::Texture};

// The value among `values` whose name_of(value) is `name`: every option's parser.
template <class Enum, class Values, class NameOf>
std::optional<Enum> parse_named(const Values& values, std::string_view name, NameOf name_of) {
  for (const Enum v : values)
    if (name_of(v) == name) return v;
  return std::nullopt;
}
}  // namespace

std::span<const SssTechnique> all_techniques() { return kTechniques; }

std::string_view technique_name(SssTechnique technique) {
  switch (technique) {
    case SssTechnique::Off: return "off";
    case SssTechnique::Separable: return "separable";
    case SssTechnique::Gaussians: return "gaussians";
    case SssTechnique::Texture: return "texture";
  }
  return "separable";
}

std::optional<SssTechnique> parse_technique(std::string_view name) {
  return parse_named<SssTechnique>(kTechniques, name, technique_name);
}

std::variant<SssTechnique, std::string> technique_from_cli(std::string_view sss, std::string_view mode) {
  if (sss != "off" && sss != "screen" && sss != "texture")
    return "--sss: expected off, screen or texture, got '" + std::string(sss) + "'";
  if (mode != "separable" && mode != "gaussians")
    return "--mode: expected separable or gaussians, got '" + std::string(mode) + "'";
  if (sss == "off") return SssTechnique::Off;
  if (sss == "texture") return SssTechnique::Texture;
  return mode == "separable" ? SssTechnique::Separable : SssTechnique::Gaussians;
}

std::string_view texture_update_name(TextureUpdate update) {
  return update == TextureUpdate::EveryFrame ? "every-frame" : "on-change";
}

std::optional<TextureUpdate> parse_texture_update(std::string_view name) {
  constexpr TextureUpdate kUpdates[] = {TextureUpdate::EveryFrame, TextureUpdate::OnChange};
  return parse_named<TextureUpdate>(kUpdates, name, texture_update_name);
}

std::string texture_size_error(long long size) {
  if (size >= kMinTextureSize && size <= kMaxTextureSize) return {};
  return "expected " + std::to_string(kMinTextureSize) + ".." + std::to_string(kMaxTextureSize) +
         ", got " + std::to_string(size);
}

std::variant<TextureObjectOptions, std::string> parse_texture_object(std::string_view text,
                                                                     TextureUpdate fallback) {
  const std::string given(text);
  const std::size_t eq = text.rfind('=');
  if (eq == std::string_view::npos || eq == 0)
    return "expected NAME=SIZE[:every-frame|on-change], got '" + given + "'";
  TextureObjectOptions o;
  o.name = std::string(text.substr(0, eq));
  o.update = fallback;
  std::string_view rest = text.substr(eq + 1);
  if (const std::size_t colon = rest.find(':'); colon != std::string_view::npos) {
    const auto update = parse_texture_update(rest.substr(colon + 1));
    if (!update)
      return "'" + given + "': the update policy must be every-frame or on-change, got '" +
             std::string(rest.substr(colon + 1)) + "'";
    o.update = *update;
    rest = rest.substr(0, colon);
  }
  std::uint32_t size = 0;
  const auto [end, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), size);
  if (ec != std::errc() || end != rest.data() + rest.size())
    return "'" + given + "': the size must be an integer, got '" + std::string(rest) + "'";
  if (const std::string e = texture_size_error(size); !e.empty())
    return "'" + given + "': the size " + e;
  o.size = size;
  return o;
}

TextureObjectOptions texture_options_for(const RenderOptions& options, std::string_view name) {
  for (const TextureObjectOptions& o : options.texture_objects)
    if (o.name == name) return o;
  return {std::string(name), options.texture_size, options.texture_update};
}

namespace {
constexpr DebugView kDebugViews[] = {DebugView::None,         DebugView::Irradiance,
                                     DebugView::Specular,     DebugView::Scattered,
                                     DebugView::KernelRadius, DebugView::ProfileId,
                                     DebugView::Thickness,    DebugView::UvStretch,
                                     DebugView::SingleScattering};
}  // namespace

std::string background_error(const std::array<float, 3>& colour) {
  for (const float c : colour)
    if (!(c >= 0.0f && c <= 1.0f))
      return "each of R, G, B must lie in [0, 1] (sRGB), got " + message_number(c);
  return "";
}

std::string_view antialias_name(Antialias aa) { return aa == Antialias::Fxaa ? "fxaa" : "off"; }

std::optional<Antialias> parse_antialias(std::string_view name) {
  constexpr Antialias kModes[] = {Antialias::Off, Antialias::Fxaa};
  return parse_named<Antialias>(kModes, name, antialias_name);
}

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
    case DebugView::SingleScattering: return "single-scattering";
  }
  return "none";
}

std::optional<DebugView> parse_debug_view(std::string_view name) {
  return parse_named<DebugView>(kDebugViews, name, debug_view_name);
}

std::span<const DebugView> all_debug_views() { return kDebugViews; }

bool debug_view_has_range(DebugView view) {
  return view == DebugView::KernelRadius || view == DebugView::Thickness ||
         view == DebugView::UvStretch;
}

std::string_view debug_view_unit(DebugView view) {
  switch (view) {
    case DebugView::KernelRadius: return "px";
    case DebugView::Thickness: return "mm";
    case DebugView::UvStretch: return "mm per unit of UV";
    default: return "";
  }
}

std::string debug_range_error(DebugView view, const std::array<float, 2>& range) {
  const auto [lo, hi] = range;
  if (lo == 0.0f && hi == 0.0f) return {};
  const auto num = [](float v) {
    std::ostringstream o;
    o << v;
    return o.str();
  };
  const std::string given = num(lo) + "," + num(hi);
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi))
    return "expected LO,HI with LO < HI (0,0: automatic), got " + given;
  if (view == DebugView::KernelRadius && !(lo > 0.0f))
    return "kernel-radius draws log2 pixels: LO must be > 0, got " + given;
  if (!(lo >= 0.0f)) return "LO must be >= 0, got " + given;
  return {};
}

}  // namespace sss::renderer
