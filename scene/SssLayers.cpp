#include "scene/SssLayers.h"

#include "scene/GltfJson.h"
#include "scene/SssExtras.h"

#include "profiles/Presets.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace sss::scene {

namespace {

using nlohmann::json;
using profiles::Medium;

constexpr std::array<std::string_view, 6> kLayerKeys = {"sigma_a", "sigma_s", "g",
                                                        "eta",     "preset",  "thickness_mm"};

std::string key_list() {
  std::string s;
  for (std::string_view k : kLayerKeys) s += (s.empty() ? "" : ", ") + std::string(k);
  return s;
}

std::string layer_name(std::size_t k) { return "layers[" + std::to_string(k) + "]"; }

// An error named inside entry k ("sigma_a[2]", "" for the entry itself) named from the array.
FieldError in_layer(std::size_t k, FieldError e) {
  e.field = layer_name(k) + (e.field.empty() ? "" : "." + e.field);
  return e;
}

// One entry; its errors name the field inside the entry ("sigma_a[2]", "thickness_mm").
std::variant<Medium, FieldError> parse_layer(const json& o, bool last) {
  if (!o.is_object()) return FieldError{"", "must be a JSON object (one layer)"};
  for (const auto& item : o.items())
    if (std::find(kLayerKeys.begin(), kLayerKeys.end(), item.key()) == kLayerKeys.end())
      return FieldError{item.key(), "unknown field; expected one of " + key_list()};

  double thickness = std::numeric_limits<double>::infinity();
  if (auto e = detail::read_thickness(o, "thickness_mm", thickness)) return *e;
  if (!o.contains("thickness_mm") && !last) {
    return FieldError{"thickness_mm",
                      "is required on every layer but the last (only the last may be "
                      "semi-infinite)"};
  }

  const bool preset = o.contains("preset");
  const bool coefficients = o.contains("sigma_a") || o.contains("sigma_s");
  Medium m;
  if (preset) {
    for (const char* k : {"sigma_a", "sigma_s", "g", "eta"})
      if (o.contains(k)) return FieldError{k, "cannot be combined with a preset (it has its own)"};
    const json& p = o["preset"];
    if (!p.is_string()) return FieldError{"preset", "must be a preset name (a string), got " + p.dump()};
    const profiles::Preset* found = profiles::find_preset(p.get<std::string>());
    if (!found)
      return FieldError{"preset", "unknown preset " + p.dump() + "; known: " + profiles::preset_names()};
    m = profiles::preset_medium(*found);
    for (int c = 0; c < 3; ++c)
      if (auto e = m.channel(c).validate(std::string("[") + kChannelNames[c] + "]"))
        return FieldError{"preset", "preset " + p.dump() + " cannot be a layer: " + e->what()};
  } else if (coefficients) {
    for (const char* k : {"sigma_a", "sigma_s"})
      if (!o.contains(k)) return FieldError{k, "is required with sigma_a and sigma_s"};
    m.g.fill(0.0);
    m.eta.fill(1.3);
    bool scalar = false;
    for (auto [k, dst] : {std::pair{"sigma_a", &m.sigma_a}, std::pair{"sigma_s", &m.sigma_s},
                          std::pair{"g", &m.g}, std::pair{"eta", &m.eta}})
      if (o.contains(k))
        if (auto e = detail::read_rgb(o, k, *dst, scalar)) return *e;
    for (int c = 0; c < 3; ++c)
      if (auto e = m.channel(c).validate("[" + std::to_string(c) + "]"))
        return detail::as_written(*e, o);
  } else {
    return FieldError{"", "needs a preset, or sigma_a and sigma_s"};
  }
  m.thickness_mm = thickness;
  return m;
}

// Layer k's η against the top layer's, named where the user gave (or did not give) it.
std::optional<FieldError> check_eta(const json& layers, const profiles::LayerStack& stack,
                                    std::size_t k) {
  for (int c = 0; c < 3; ++c) {
    if (stack[k].eta[c] == stack[0].eta[c]) continue;
    const json& o = layers[k];
    const std::string why = " but the top layer's is " + message_number(stack[0].eta[c]) +
                            ": every layer of a stack has the same eta (the interfaces "
                            "between layers are index-matched)";
    if (o.contains("preset"))
      return FieldError{"preset", "preset " + o["preset"].dump() + " has eta " +
                                      message_number(stack[k].eta[c]) + why};
    if (!o.contains("eta"))
      return FieldError{"eta", "is 1.3 (the default, as none is given)" + why};
    FieldError e{"eta[" + std::to_string(c) + "]", "is " + message_number(stack[k].eta[c]) + why};
    return detail::as_written(e, o);
  }
  return std::nullopt;
}

// profiles::validate_layers names "layers[k].sigma_a[G]": rename the field inside the
// entry as the user wrote it ("sigma_a[1]", or "sigma_a" for a single number).
FieldError as_written_in_stack(FieldError e, const json& layers) {
  const std::string prefix = "layers[";
  if (e.field.rfind(prefix, 0) != 0) return e;
  const auto close = e.field.find("].", prefix.size());
  if (close == std::string::npos) return e;
  std::size_t k = 0;
  try {
    k = std::stoul(e.field.substr(prefix.size(), close - prefix.size()));
  } catch (const std::exception&) {
    return e;
  }
  if (k >= layers.size() || !layers[k].is_object()) return e;
  FieldError inner{e.field.substr(close + 2), e.message};
  return in_layer(k, detail::as_written(inner, layers[k]));
}

}  // namespace

std::variant<profiles::LayerStack, FieldError> parse_sss_layers(const json& layers) {
  if (!layers.is_array())
    return FieldError{"layers", "must be an array of layers, top first, got " +
                                    std::string(layers.type_name())};
  if (layers.empty()) return FieldError{"layers", "needs at least one layer"};
  if (layers.size() > static_cast<std::size_t>(profiles::kMaxLayers))
    return FieldError{"layers", "has " + std::to_string(layers.size()) + " layers; at most " +
                                    std::to_string(profiles::kMaxLayers) + " are allowed"};
  profiles::LayerStack stack;
  stack.reserve(layers.size());
  for (std::size_t k = 0; k < layers.size(); ++k) {
    auto layer = parse_layer(layers[k], k + 1 == layers.size());
    if (auto* e = std::get_if<FieldError>(&layer)) return in_layer(k, *e);
    stack.push_back(std::get<Medium>(layer));
  }
  for (std::size_t k = 1; k < stack.size(); ++k)
    if (auto e = check_eta(layers, stack, k)) return in_layer(k, *e);
  if (auto e = profiles::validate_layers(stack)) return as_written_in_stack(*e, layers);
  return stack;
}

std::variant<profiles::LayerStack, FieldError> parse_sss_layers_text(std::string_view text) {
  if (auto e = check_json_depth(text, kMaxJsonDepth)) return FieldError{"", *e};
  json doc;
  try {
    doc = json::parse(text.begin(), text.end());
  } catch (const json::parse_error& e) {
    // "[json.exception.parse_error.101] parse error at line 3, column 5: ...": keep from
    // "parse error", which says where.
    std::string what = e.what();
    if (const auto at = what.find("] "); what.rfind("[json.exception", 0) == 0 && at != std::string::npos)
      what = what.substr(at + 2);
    return FieldError{"", "is not valid JSON: " + what};
  }
  if (!doc.is_object())
    return FieldError{"", "must be a JSON object {\"layers\": [...]}, got " +
                              std::string(doc.type_name())};
  for (const auto& item : doc.items())
    if (item.key() != "layers")
      return FieldError{item.key(), "unknown field; the file holds {\"layers\": [...]} only"};
  if (!doc.contains("layers"))
    return FieldError{"layers", "is required: the file holds {\"layers\": [...]}, top first"};
  return parse_sss_layers(doc["layers"]);
}

std::variant<profiles::LayerStack, FieldError> parse_sss_layers_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return FieldError{path, "is a directory, not a JSON file"};
  errno = 0;
  std::ifstream f(path, std::ios::binary);
  if (!f) {
    const int err = errno;
    return FieldError{path, std::string("cannot be opened: ") +
                                (err ? std::strerror(err) : "unknown error")};
  }
  std::ostringstream s;
  s << f.rdbuf();
  if (f.bad()) return FieldError{path, "cannot be read"};
  auto parsed = parse_sss_layers_text(s.str());
  if (auto* e = std::get_if<FieldError>(&parsed); e && e->field.empty()) e->field = path;
  return parsed;
}

}  // namespace sss::scene
